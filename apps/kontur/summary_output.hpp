#pragma once
// Where `kontur run` and `kontur verify` write the JSON summary (built by the library:
// kontur/report/summary.hpp).
#include <filesystem>
#include <string>
#include <vector>

namespace kontur::app {

/// Writes the summary text: to `path` atomically (never over one of `inputs`), to stdout for "-",
/// or to stderr when no path is given (nothing with `quiet`).
void write_summary(const std::string& summary, const std::string& path, bool quiet,
                   const std::vector<std::filesystem::path>& inputs);

}  // namespace kontur::app
