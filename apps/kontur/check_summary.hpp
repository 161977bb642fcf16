#pragma once
// The JSON summary of a check of setpoints (docs/setpoints.md): per program and per block.
// Written by `kontur run` and `kontur verify`.
#include "run_report.hpp"

#include <kontur/machine.hpp>
#include <kontur/verify/checker.hpp>

#include <nlohmann/json.hpp>

#include <filesystem>
#include <string>
#include <vector>

namespace kontur::app {

/// The summary of `report` (the check of setpoints ending at `total_time_s` [s] against the program's
/// moves `run_moves` on `machine`).
[[nodiscard]] nlohmann::ordered_json check_summary(const std::string& program, const Machine& machine,
                                                   const verify::Report& report,
                                                   const std::vector<RunMove>& run_moves, double total_time_s);

/// Writes the summary: to `path` atomically (never over one of `inputs`), to stdout for "-", or to
/// stderr when no path is given (nothing with `quiet`).
void write_summary(const nlohmann::ordered_json& summary, const std::string& path, bool quiet,
                   const std::vector<std::filesystem::path>& inputs);

}  // namespace kontur::app
