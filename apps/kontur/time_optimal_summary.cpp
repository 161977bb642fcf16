#include "time_optimal_summary.hpp"

namespace kontur::app {

void add_time_optimal_summary(nlohmann::ordered_json& summary, std::span<const plan::TimeOptimalMove> moves,
                              const Machine& machine, double online_time_s) {
  plan::TimeOptimalOptions options;
  // The setpoints are sampled: a corner is passed with the velocity jump of one servo period that
  // keeps the acceleration (what the online planner's junction rule allows on such a machine).
  options.corners = plan::CornerRule::servo_period;
  const plan::TimeOptimalProfile reference = plan::time_optimal_profile(moves, machine, options);
  summary["time_optimal_s"] = reference.total_time_s;
  // No motion: both times are 0, the ratio 1 (never NaN in the output).
  summary["time_ratio"] = reference.total_time_s > 0.0 ? online_time_s / reference.total_time_s : 1.0;
}

}  // namespace kontur::app
