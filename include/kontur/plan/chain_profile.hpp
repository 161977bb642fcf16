#pragma once
// The speed profile of a chain of pieces joined smoothly: instead of one S-curve at the smallest
// of the pieces' speed caps, a jerk-limited profile that rises and falls with each piece's own cap
// and carries its acceleration across the junctions between them.
//
// Method: a greedy step in time. At every step of `step_s` the largest jerk of {+J, 0, -J}
// (clamped so that |a| <= A) is taken whose next state is still safe: from it, bringing the
// acceleration to zero and then one S-curve change of speed reaches every junction ahead at or
// below its cap, and the chain's end at exactly its end speed. When no jerk is safe, that
// manoeuvre is carried out, exactly, towards the constraint that binds (the chain's end: the
// profile ends exactly at its length and end speed). The result is checked phase by phase against
// every piece's cap; the caller keeps the S-curve at the smallest cap (the look-ahead's plan,
// always valid) where the check fails or where it is not faster.
#include <kontur/plan/scurve.hpp>
#include <kontur/trajectory/path_profile.hpp>

#include <optional>
#include <span>

namespace kontur::plan {

/// A stretch of a chain with its own speed cap.
struct CapStretch {
  double length_mm = 0.0;  ///< [mm]
  double cap_mm_s = 0.0;   ///< speed cap over it [mm/s]
};

/// The profile over the stretches (in order) from v0 to v1 [mm/s] with zero acceleration at both
/// ends, v <= the cap of the stretch it runs through, |a| <= limits.max_acceleration,
/// |j| <= limits.max_jerk. Requires v0 and v1 at most every cap and v1 within reach of v0 over the
/// summed length (as the look-ahead plans a chain: one S-curve at its smallest cap, which takes
/// `time_bound_s` [s]). Steps of `step_s` [s]; gives up (nullopt) after
/// chain_profile_max_steps_per_flat * time_bound_s [s] of steps or where the check fails.
[[nodiscard]] std::optional<trajectory::PathProfile> plan_chain_profile(std::span<const CapStretch> stretches,
                                                                        double v0, double v1,
                                                                        const PathLimits& limits, double step_s,
                                                                        double time_bound_s);

}  // namespace kontur::plan
