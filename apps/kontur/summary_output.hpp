#pragma once
// What `kontur run` and `kontur verify` say at the end: the JSON summary (built by the library:
// kontur/report/summary.hpp) to a file or a stream, and the short summary for a person.
#include <cstdio>
#include <filesystem>
#include <kontur/gcode/reader.hpp>
#include <kontur/machine.hpp>
#include <kontur/pipeline.hpp>
#include <string>
#include <vector>

namespace kontur::app {

/// Where the summaries of a run or a verify go.
struct SummaryOutputs {
  std::string file;           ///< --summary FILE: the JSON, atomically (never over an input); "-": stdout
  bool json = false;          ///< --json: the JSON on stdout
  bool quiet = false;         ///< --quiet: no short summary
  bool stdout_taken = false;  ///< the setpoints or the report go to stdout
  /// The JSON goes to stdout (--json or --summary -).
  [[nodiscard]] bool json_on_stdout() const noexcept { return json || file == "-"; }
};

/// The end of a run or a verify: the JSON summary `json` where `to` says, and unless quiet the
/// short summary for a person on stdout (on stderr when stdout carries the setpoints, the report
/// or the JSON): program and dialect (as `reading` took it), machine, moves and path length,
/// machining time and setpoints, the largest ratios against the limits, path and chord error,
/// PASS or FAIL with the failures, then the lines of `footer` (what was written where) and the
/// summary file. PASS and FAIL are coloured only on a terminal when NO_COLOR is not set.
void write_summaries(const SummaryOutputs& to, const std::string& json, const std::vector<std::filesystem::path>& inputs,
                     const std::string& program, const Machine& machine, const gcode::ReaderOptions& reading,
                     const RunResult& result, const std::vector<program::Move>& moves, std::string footer);

}  // namespace kontur::app
