#pragma once
// The JSON result of checking a part program (what `kontur check --json` prints): the file, the
// dialect it was read in, per block its line, type, length and feed, and the totals. Built here, in
// the library, so that the command and the Python module (python/) give the same document.
#include <kontur/gcode/reader.hpp>
#include <string>

namespace kontur::report {

/// Reads and validates `program` with `options` and returns the JSON text (indented by 2, no
/// trailing newline): "file", "valid", "dialect" {name, reason}, "blocks" (empty when
/// `with_blocks` is false) and "totals", in one reading. Throws InputError (file, line, column,
/// rule) at the first error; nothing is returned then.
[[nodiscard]] std::string program_check_json(const std::string& program, const gcode::ReaderOptions& options,
                                             bool with_blocks = true);

}  // namespace kontur::report
