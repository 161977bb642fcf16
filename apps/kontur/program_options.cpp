#include "program_options.hpp"

#include <kontur/pipeline.hpp>

#include <fmt/format.h>

#include <cstdio>
#include <filesystem>
#include <memory>

namespace kontur::app {

void add_program_read_options(CLI::App* cmd, ProgramReadOptions& options) {
  cmd->add_option("--dialect", options.dialect,
                  fmt::format("the program's G-code dialect: {} (default: the machine file's, else detected from the "
                              "program and printed with the reason)",
                              gcode::dialect_names()));
  cmd->add_option("--subroutine-path", options.subroutine_path,
                  "folder searched for a subroutine in a file of its own (LinuxCNC: o<name> call runs name.ngc); "
                  "repeat for more folders (default: the machine file's [RS274NGC] SUBROUTINE_PATH, else the "
                  "program's folder)");
  cmd->add_option("--tool-table", options.tool_table,
                  "the tool table (LinuxCNC's format: T1 P1 D6.0 Z10.0 ;comment) for G43 H, G41 / G42 D and the Fanuc "
                  "family's H and D registers (default: the machine file's [EMCIO] TOOL_TABLE or tool_table, else none)");
  cmd->add_flag("--no-block-delete", options.no_block_delete, "read blocks starting with '/' (skipped by default)");
}

gcode::ReaderOptions reader_options(const ProgramReadOptions& options, const std::string& program,
                                    const Machine* machine, bool quiet) {
  ProgramReading reading;
  reading.block_delete = !options.no_block_delete;
  reading.subroutine_path = options.subroutine_path;
  reading.tool_table = options.tool_table;
  if (!options.dialect.empty()) {
    reading.dialect = gcode::parse_dialect(options.dialect);
    if (!reading.dialect)
      throw CLI::ValidationError("--dialect", fmt::format("{}: not a G-code dialect (expected one of {})",
                                                          options.dialect, gcode::dialect_names()));
  }
  gcode::ReaderOptions ro = program_reader_options(program, reading, machine);
  if (!quiet && !ro.dialect_reason.empty())
    std::fprintf(stderr, "kontur: dialect: %s (%s)\n", gcode::to_string(*ro.dialect), ro.dialect_reason.c_str());
  return ro;
}

}  // namespace kontur::app
