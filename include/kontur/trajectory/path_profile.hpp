#pragma once
// The motion law s(t) of a chain of pieces: a sequence of phases of constant jerk (an S-curve's
// seven, or the many of a profile that follows the speed caps of the pieces it runs through,
// plan/chain_profile.hpp). Built by the planner; sample() is noexcept and allocation-free (the
// phases are shared, immutable, between the segments of the chain).
#include <kontur/trajectory/scurve_profile.hpp>

#include <memory>
#include <vector>

namespace kontur::trajectory {

/// One phase: its start time [s], the state at its start, and its jerk [mm/s^3].
struct ProfilePhase {
  double t0_s = 0.0;
  PathState start;
  double jerk = 0.0;
};

/// Appends the phases of an S-curve that last (its states as it integrates them), shifted by
/// t0_s [s] and s0_mm [mm]: how a PathProfile is made of an S-curve, whole or as a part.
void append_phases(const ScurveProfile& s, double t0_s, double s0_mm, std::vector<ProfilePhase>& out);

class PathProfile {
 public:
  /// An empty profile (no motion).
  PathProfile() = default;
  /// The seven phases of an S-curve (phases of no duration are left out).
  explicit PathProfile(const ScurveProfile& s);
  /// Phases in time order from t = 0, ending at `duration_s` in the exact state `end` (zero
  /// acceleration); the phases' own integration meets it up to rounding.
  PathProfile(std::vector<ProfilePhase> phases, double duration_s, const PathState& end);

  /// Total duration [s].
  [[nodiscard]] double duration() const noexcept { return data_ ? data_->duration_s : 0.0; }
  /// Distance [mm].
  [[nodiscard]] double distance() const noexcept { return data_ ? data_->end.s : 0.0; }
  [[nodiscard]] double start_velocity() const noexcept;
  [[nodiscard]] double end_velocity() const noexcept { return data_ ? data_->end.v : 0.0; }
  /// Number of phases.
  [[nodiscard]] std::size_t phases() const noexcept { return data_ ? data_->phases.size() : 0; }
  /// State at time t [s] (clamped to [0, duration]); at the end exactly the end state.
  [[nodiscard]] PathState sample(double t) const noexcept;
  /// The first time [s] at which the profile has covered `s_mm` (bisection).
  [[nodiscard]] double time_at(double s_mm) const noexcept;
  /// Appends its phases, shifted by t0_s [s] and s0_mm [mm] (as append_phases does an S-curve's):
  /// a profile as a part of a longer one.
  void append_phases_to(double t0_s, double s0_mm, std::vector<ProfilePhase>& out) const;

 private:
  struct Data {
    std::vector<ProfilePhase> phases;
    double duration_s = 0.0;
    PathState end;
    // The phases' distance, run to duration_s, differs from end.s by the rounding of their solution
    // (about 1e-13 of it); sample() maps it onto end.s by s0 + (s - s0) * scale (s0: the start),
    // so the motion arrives smoothly instead of being clamped a period early (a jerk of
    // 1e-13 mm / T^3 at a stop).
    double s0 = 0.0, scale = 1.0;
  };
  std::shared_ptr<const Data> data_;
};

}  // namespace kontur::trajectory
