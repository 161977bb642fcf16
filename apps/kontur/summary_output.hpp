#pragma once
// What `kontur run` and `kontur verify` say at the end: the JSON summary (built by the library:
// kontur/report/summary.hpp) to a file or a stream, and the short summary for a person.
#include <cstdio>
#include <filesystem>
#include <kontur/gcode/dialect.hpp>
#include <kontur/machine.hpp>
#include <kontur/pipeline.hpp>
#include <optional>
#include <string>
#include <vector>

namespace kontur::app {

/// Writes the summary text: to `path` atomically (never over one of `inputs`), to stdout for "-",
/// or to stderr when no path is given (nothing with `quiet`).
void write_summary(const std::string& summary, const std::string& path, bool quiet,
                   const std::vector<std::filesystem::path>& inputs);

/// The short summary for a person, a few lines on `out`: program (and dialect), machine, moves and
/// path length, machining time and setpoints, the largest ratios against the limits, path and
/// chord error, PASS or FAIL with the failures, then `footer` (if any). PASS and FAIL are
/// coloured only when `out` is a terminal and NO_COLOR is not set.
void print_human_summary(std::FILE* out, const std::string& program, const Machine& machine,
                         const std::optional<gcode::DialectChoice>& dialect, const RunResult& result,
                         const std::vector<program::Move>& moves, const std::string& footer);

}  // namespace kontur::app
