#pragma once
// `kontur run --time-optimal`: the time-optimal reference of the program's path (the library's
// plan::time_optimal_profile, acceleration-limited, corners by the servo-period rule) and the
// online planner's total time against it, as fields of the JSON summary.
#include <kontur/machine.hpp>
#include <kontur/plan/time_optimal.hpp>

#include <nlohmann/json.hpp>

#include <span>

namespace kontur::app {

/// Adds "time_optimal_s" (the reference's total time [s]) and "time_ratio" (online_time_s over it)
/// to `summary`.
void add_time_optimal_summary(nlohmann::ordered_json& summary, std::span<const plan::TimeOptimalMove> moves,
                              const Machine& machine, double online_time_s);

}  // namespace kontur::app
