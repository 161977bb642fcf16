#pragma once
// The speed profile of a chain of pieces joined smoothly: instead of one S-curve at the smallest
// of the pieces' speed caps, a jerk-limited profile that rises and falls with each piece's own cap
// and its own acceleration and jerk limits, and carries its acceleration across the junctions
// between them. The motion planner runs it over one chain, and over a run of chains that join
// smoothly (plan/motion_planner.hpp).
//
// Method: a greedy step in time. At every step of `step_s` the largest jerk of {+J, 0, -J}
// (clamped so that |a| <= A; J and A of the stretches the step runs through) is taken whose next
// state is still safe: from it, bringing the acceleration to zero (at the smallest jerk of the
// stretches that takes) and then one change of speed reaches every junction ahead at or below
// its cap, and the end at exactly its end speed. That change is judged at the smallest limits of
// the stretches it runs through: braking, it cruises first and brakes at the end, so only the
// stretches before the junction that the braking covers count; where stretches have speed bands,
// under bands of those limits at speed levels (shares of the largest cap and the look-ahead's band
// tops, shares of the smallest), each band over the stretches the change can pass at its speeds:
// not those nearer to its slow end than the bands below it let it change speed (a braking into a
// tight stretch passes it slowly, and may brake harder before it). When no jerk is safe,
// that manoeuvre is carried out, exactly, towards the constraint that binds; where its S-curve
// would pass an earlier junction above that junction's speed, it aims at that junction instead.
// The profile ends exactly at its length and end speed. The result is checked phase by phase
// against every stretch's cap, acceleration and jerk; the caller keeps the S-curve at the smallest
// cap (the look-ahead's plan, always valid) where the check fails or where it is not faster.
#include <kontur/plan/banded_profile.hpp>
#include <kontur/plan/scurve.hpp>
#include <kontur/trajectory/path_profile.hpp>

#include <limits>
#include <optional>
#include <span>

namespace kontur::plan {

/// A stretch of a chain with its own speed cap and limits.
struct CapStretch {
  double length_mm = 0.0;  ///< [mm]
  double cap_mm_s = 0.0;   ///< speed cap over it [mm/s]
  /// its own acceleration [mm/s^2] and jerk [mm/s^3] limits at every speed up to its cap (the
  /// chain's where larger)
  double max_acceleration = std::numeric_limits<double>::infinity();
  double max_jerk = std::numeric_limits<double>::infinity();
  /// on a curve: more acceleration at lower speeds (constraints.hpp's acceleration_bands; n = 0:
  /// none), with the bands' jerk, used at the speeds below the cap where it leaves more
  AccelerationBands bands{};
};

/// The profile over the stretches (in order) from v0 to v1 [mm/s] with zero acceleration at both
/// ends, v <= the cap of the stretch it runs through, |a| and |j| within that stretch's limits at
/// the speeds it runs at (its cap's, or a speed band's below it; each at most `limits`'). Requires v0 at most the first stretch's cap, v1 at most the last's,
/// and v1 within reach of v0 (as the look-ahead plans a chain: one S-curve at its smallest cap,
/// which takes `time_bound_s` [s]). Steps of `step_s` [s]; gives up (nullopt) after
/// chain_profile_max_steps_per_flat * time_bound_s [s] of steps or where the check fails.
[[nodiscard]] std::optional<trajectory::PathProfile> plan_chain_profile(std::span<const CapStretch> stretches,
                                                                        double v0, double v1,
                                                                        const PathLimits& limits, double step_s,
                                                                        double time_bound_s);

}  // namespace kontur::plan
