#pragma once
// The subcommands of the `kontur` tool. Each registers its options on the application and
// returns nothing; the chosen one runs from main() through the callback it set.
#include <CLI/CLI.hpp>

namespace kontur::app {

/// Exit codes of the command (documented in the README and in `kontur --help`).
enum ExitCode : int {
  exit_ok = 0,           ///< success
  exit_invalid_input = 1,///< the input (curve, program, machine, value) breaks a rule
  exit_usage = 2,        ///< the command line is wrong
  exit_internal = 3,     ///< a bug: please report it
  exit_check_failed = 4, ///< `kontur run` / `verify`: the independent check found a limit exceeded
};

/// `kontur spline FILE`: validate a curve, print its span polynomials, lengths, differences.
void register_spline_command(CLI::App& app, int& exit_code);
/// `kontur check PROGRAM`: validate a G-code program, print its blocks and totals.
void register_check_command(CLI::App& app, int& exit_code);
/// `kontur arc P1 P2 P3 ...`: circle through three points and the motion along it.
void register_arc_command(CLI::App& app, int& exit_code);
/// `kontur conic P1 .. P5 ...`: conic through five points and the motion along it.
void register_conic_command(CLI::App& app, int& exit_code);

/// `kontur run PROGRAM`: plan a part program on a machine and write its setpoints.
void register_run_command(CLI::App& app, int& exit_code);

/// `kontur verify PROGRAM SETPOINTS`: check a setpoint file against a program and a machine.
void register_verify_command(CLI::App& app, int& exit_code);

/// `kontur replay STREAM`: run the lower level on a segment stream and write its setpoints.
void register_replay_command(CLI::App& app, int& exit_code);

/// `kontur compress PROGRAM -o OUT`: fit runs of G1 lines by fewer blocks within a tolerance.
void register_compress_command(CLI::App& app, int& exit_code);

/// `kontur machine [FILE]`: validate a machine file and print the limits in use.
void register_machine_command(CLI::App& app, int& exit_code);

}  // namespace kontur::app
