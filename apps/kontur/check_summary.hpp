#pragma once
// The JSON summary of a check of setpoints (docs/setpoints.md): per program and per block.
// Written by `kontur run` and `kontur verify`.
#include "run_report.hpp"

#include <kontur/machine.hpp>
#include <kontur/verify/checker.hpp>

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace kontur::app {

/// The summary of `report` (the check of setpoints ending at `total_time_s` [s] against the program's
/// moves `run_moves` on `machine`).
[[nodiscard]] nlohmann::ordered_json check_summary(const std::string& program, const Machine& machine,
                                                   const verify::Report& report,
                                                   const std::vector<RunMove>& run_moves, double total_time_s);

}  // namespace kontur::app
