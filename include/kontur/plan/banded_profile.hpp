#pragma once
// The speed profile of a curved piece that runs alone in its chain (an arc or a NURBS between two
// corners), with an acceleration bound that depends on the speed.
//
// On a curve an axis's acceleration is t_i a + K_i v^2: the centripetal part K_i v^2 takes a share
// of the axis's limit that grows with the speed, so the path acceleration a left over is largest at
// low speed. The S-curve of the look-ahead uses one acceleration, the one left at the piece's speed
// cap (with a centripetal share of 0.9 only 0.44 A on a circle); this profile uses, in each speed
// band [top_{k-1}, top_k], the acceleration left at its top speed (AccelerationBands, computed by
// constraints.hpp's acceleration_bands), so that it speeds up and brakes harder where it is slow.
//
// Method: a change of speed from va up to vb (from and to zero acceleration) is the time-optimal
// one under the staircase bound a <= alpha_k while v is in band k and |j| <= J. In the plane of the
// speed and the squared acceleration g = a^2 the jerk is half the slope (j = a da/dv = g'/2), so the
// fastest change takes the largest g with |g'| <= 2J under the bound: the least of
// alpha(u)^2 + 2J |v - u| over every speed u, zero at va and vb (one sweep up and one down over the
// band edges). In each band that is a ramp up at +J, a flat along the band's acceleration and a ramp
// down at -J; the accelerations may rise from one band to the next (a chain profile's change of
// speed that passes its tight stretches only at its slow end, plan/chain_profile.hpp), where the
// ramp up starts only once the speed is past the tight band's top. A braking is the time mirror of
// the change up from its end speed. A profile is such a change up from v0 to a peak speed, a cruise
// and a braking to v1; the peak is the largest (at most the cap) whose two changes fit in the
// length, by bisection.
#include <kontur/plan/scurve.hpp>
#include <kontur/trajectory/path_profile.hpp>

#include <array>
#include <limits>
#include <optional>

namespace kontur::plan {

/// Path acceleration bounds by speed band: at speeds v <= top_mm_s[k] the path acceleration may be
/// up to acceleration[k] (top speeds ascending, the last top the piece's speed cap with its
/// S-curve's acceleration; on a curve the accelerations do not rise with the speed, across the
/// stretches of a chain they may). The path jerk is `max_jerk` at every speed
/// (at most the S-curve's: the cross term 3 K_i v a is largest in some band). n = 0: no bands (a
/// line, or nothing to gain), the S-curve's constant limits hold.
struct AccelerationBands {
  static constexpr int kMax = 26;  // (chain_profile.cpp: one more than its speed levels and band tops)
  std::array<double, kMax> top_mm_s{};      ///< [mm/s]
  std::array<double, kMax> acceleration{};  ///< [mm/s^2]
  int n = 0;
  double max_jerk = 0.0;  ///< [mm/s^3]
  /// The bound at speed v [mm/s] (the last band's above its top).
  [[nodiscard]] double at(double v) const noexcept;
};

/// Duration [s] of the fastest change of speed from va up to vb [mm/s] (va <= vb <= the last top)
/// under the bands, from and to zero acceleration.
[[nodiscard]] double banded_change_time(double va, double vb, const AccelerationBands& bands);

/// Distance [mm] covered by that change (infinity where the bands are invalid).
[[nodiscard]] double banded_change_distance(double va, double vb, const AccelerationBands& bands);

/// The time [s] that change loses against covering its distance at vb: its duration less its
/// distance over vb (infinity where the bands are invalid). A profile that speeds up from va to a
/// cap vb and brakes back takes about length / vb plus this for each of the two changes. Where the
/// change needs more than `within_mm` [mm] (the share of a stretch it has), it speeds up over the
/// whole of it without reaching vb: the time that takes less within_mm over vb.
[[nodiscard]] double banded_change_time_lost(double va, double vb, const AccelerationBands& bands,
                                             double within_mm = std::numeric_limits<double>::infinity());

/// The largest speed [mm/s] (at most the last top) reachable from v_from within `distance` [mm] by
/// speeding up under the bands; by symmetry the largest from which braking to v_from fits. v_from
/// where the bands are invalid or v_from is above the last top.
[[nodiscard]] double banded_reachable_velocity(double v_from, double distance, const AccelerationBands& bands);

/// As braking_velocity (scurve.hpp) under the bands: the largest speed [mm/s] (at most the last
/// top) from which braking to every end speed in [v_after, that speed] fits in `distance` [mm]
/// (the braking distance is not monotone in the end speed; its largest is looked for at v / 3, at
/// a_k^2 / 2J of each band, at the band tops and on a grid of end speeds). Monotone in v_after.
/// `at_least` [mm/s]: a speed the caller has already (the S-curve's): where braking to v_after
/// alone does not beat it, it is given back without the search over end speeds.
[[nodiscard]] double banded_braking_velocity(double v_after, double distance, const AccelerationBands& bands,
                                             double at_least = 0.0);

/// The profile over `distance` [mm] from v0 to v1 [mm/s] (both at most the last top; v1 reachable
/// from v0 as the look-ahead planned it), zero acceleration at both ends, |a| <= bands.at(v),
/// |j| <= bands.max_jerk, v <= the last top. None where the bands are empty or invalid or the
/// speed change from v0 to v1 alone does not fit in the distance.
[[nodiscard]] std::optional<trajectory::PathProfile> plan_banded_profile(double distance, double v0, double v1,
                                                                         const AccelerationBands& bands);

}  // namespace kontur::plan
