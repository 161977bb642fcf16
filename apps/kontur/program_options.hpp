#pragma once
// The options of every subcommand that reads a part program (check, run, verify): its dialect and
// block delete, and the line that says which dialect was taken and why.
#include <CLI/CLI.hpp>
#include <kontur/gcode/reader.hpp>
#include <kontur/machine.hpp>

#include <string>

namespace kontur::app {

struct ProgramReadOptions {
  std::string dialect;           ///< --dialect NAME (empty: the machine's, else detected)
  bool no_block_delete = false;  ///< --no-block-delete
  std::vector<std::string> subroutine_path;  ///< --subroutine-path DIR (repeatable)
  std::string tool_table;        ///< --tool-table FILE (empty: the machine file's, else none)
};

/// Adds --dialect, --subroutine-path, --tool-table and --no-block-delete to `cmd`.
void add_program_read_options(CLI::App* cmd, ProgramReadOptions& options);

/// The reader options for `program`: the dialect given with --dialect, else the machine's (if
/// `machine`), else detected from the program; prints "kontur: dialect: NAME (reason)" on stderr
/// unless `quiet` (run and verify: the summary says it). An unknown dialect name is a CLI::ValidationError (exit 2).
/// --tool-table FILE is read here (in the machine's linear units: an inch INI's table is in inches);
/// a broken table throws InputError.
[[nodiscard]] gcode::ReaderOptions reader_options(const ProgramReadOptions& options, const std::string& program,
                                                  const Machine* machine, bool quiet);

}  // namespace kontur::app
