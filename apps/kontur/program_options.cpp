#include "program_options.hpp"

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
  gcode::ReaderOptions ro;
  ro.block_delete = !options.no_block_delete;
  ro.subroutine_path = options.subroutine_path;
  if (!options.tool_table.empty())
    ro.tool_table = std::make_shared<const gcode::ToolTable>(
        gcode::ToolTable::read(options.tool_table, machine ? machine->tool_table_mm_per_unit : 1.0));
  std::optional<gcode::Dialect> given;
  if (!options.dialect.empty()) {
    given = gcode::parse_dialect(options.dialect);
    if (!given)
      throw CLI::ValidationError("--dialect", fmt::format("{}: not a G-code dialect (expected one of {})",
                                                          options.dialect, gcode::dialect_names()));
  }
  // A program that cannot be opened is reported by the reader, with its own message.
  std::error_code ec;
  if (!std::filesystem::is_regular_file(program, ec)) {
    ro.dialect = given;
    return ro;
  }
  const gcode::DialectChoice choice = gcode::choose_dialect(
      program, given, machine ? machine->dialect : std::nullopt, machine ? machine->source : std::string());
  ro.dialect = choice.dialect;
  ro.dialect_reason = choice.reason;
  if (!quiet) std::fprintf(stderr, "kontur: dialect: %s (%s)\n", gcode::to_string(choice.dialect), choice.reason.c_str());
  return ro;
}

}  // namespace kontur::app
