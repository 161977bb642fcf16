// `kontur machine [FILE]`: read and validate a machine (Kontur TOML or LinuxCNC INI, or the
// embedded default) and print the limits Kontur will use, as Kontur's TOML (units converted to mm).
#include "commands.hpp"

#include <kontur/machine.hpp>

#include <fmt/format.h>

#include <memory>

namespace kontur::app {

void register_machine_command(CLI::App& app, int& exit_code) {
  auto file = std::make_shared<std::string>();
  CLI::App* cmd = app.add_subcommand(
      "machine", "Validate a machine file (Kontur TOML, or LinuxCNC INI by the .ini extension) and print the limits "
                 "Kontur uses, in mm and s, as Kontur's TOML. Without FILE: the embedded default machine.");
  cmd->add_option("FILE", *file, "machine file (.toml, or LinuxCNC .ini)");
  cmd->footer("Examples:\n  kontur machine\n  kontur machine examples/machines/default.toml\n"
              "  kontur machine ../shared/data/gcode/linuxcnc-tp/configs/XYZ.ini\n"
              "Exit codes: 0 valid machine, 1 invalid machine or file, 2 wrong command line.");
  cmd->callback([file, &exit_code]() {
    const Machine m = file->empty() ? default_machine() : read_machine(*file);
    if (file->empty()) validate(m);
    fmt::print("{}", to_toml(m));
    exit_code = exit_ok;
  });
}

}  // namespace kontur::app
