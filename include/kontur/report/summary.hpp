#pragma once
#include <kontur/gcode/dialect.hpp>
// The JSON summary of a run or of a check of a setpoint file (docs/setpoints.md): per program
// (time, setpoints, maxima against the limits, pass/fail, failures) and per move ("blocks").
// Built here, in the library, so that the command, the tests and the bindings print the same.
#include <kontur/machine.hpp>
#include <kontur/program/move.hpp>
#include <kontur/verify/checker.hpp>
#include <optional>
#include <string>
#include <vector>

namespace kontur::report {

/// What a summary adds after the per-move table, when given.
struct SummaryExtras {
  std::optional<double> time_optimal_s;      ///< run --time-optimal: the reference time [s] (and time_ratio)
  /// run --time-optimal: the reference's time on each move [s] (per block: time_optimal_s)
  std::vector<double> move_time_optimal_s;
  std::optional<std::string> setpoint_file;  ///< verify: the file checked
  std::optional<gcode::DialectChoice> dialect;  ///< the dialect the program was read in, and why
};

/// The summary as JSON text (indented by 2, ending in a newline). `program` as the user named it;
/// `total_time_s` the time of the last setpoint [s] (0 without setpoints).
[[nodiscard]] std::string summary_json(const std::string& program, const Machine& machine, const verify::Report& r,
                                       const std::vector<program::Move>& moves, double total_time_s,
                                       const SummaryExtras& extras = {});

}  // namespace kontur::report
