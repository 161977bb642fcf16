// `kontur verify PROGRAM SETPOINTS`: the independent check of `kontur run`, for any setpoint file
// (Kontur's CSV or binary, or another planner's written in the same format): finite differences
// of the setpoints against the machine's axis limits, the distance of every setpoint and every
// chord from the programmed path, the start and end. Nothing of the planner is used.
#include "check_summary.hpp"
#include "commands.hpp"
#include "run_report.hpp"

#include <kontur/error.hpp>
#include <kontur/io/atomic_file.hpp>
#include <kontur/io/setpoint_reader.hpp>
#include <kontur/machine.hpp>
#include <kontur/plan/program_path.hpp>
#include <kontur/verify/checker.hpp>

#include <fmt/format.h>

#include <cmath>
#include <filesystem>
#include <iostream>
#include <memory>

namespace kontur::app {
namespace {

struct VerifyOptions {
  std::string program;
  std::string setpoints;
  std::string machine;
  std::string summary;
  std::string report;
  bool quiet = false;
  bool no_blend = false;
};

bool verify_setpoints(const VerifyOptions& o) {
  std::vector<std::filesystem::path> inputs = {o.program, o.setpoints};
  if (!o.machine.empty()) inputs.emplace_back(o.machine);
  if (!o.report.empty()) check_output_not_input(o.report, inputs);
  const Machine machine = o.machine.empty() ? default_machine() : read_machine(o.machine);
  if (o.machine.empty()) validate(machine);
  // The path, as `kontur run` builds it: the same corner blends, each checked against the
  // programmed lines it replaces.
  plan::ProgramPath path(machine, !o.no_blend);
  path.read(o.program, {});
  const std::vector<verify::PathMove>& moves = path.check_moves();
  const std::vector<RunMove> run_moves = run_moves_of(path);
  if (moves.empty())
    throw InputError("program-no-motion", fmt::format("{}: the program has no move to check setpoints against", o.program));
  const SetpointFile file = read_setpoints(o.setpoints);
  if (file.samples.empty())
    throw InputError("setpoints-empty", fmt::format("{}: the file holds no setpoint", o.setpoints));
  if (file.period_s && std::abs(*file.period_s - machine.servo_period_s) > 1e-12 * machine.servo_period_s)
    throw InputError("setpoints-period",
                     fmt::format("{}: written at a servo period of {} s, but the machine's is {} s (give --machine)",
                                 o.setpoints, *file.period_s, machine.servo_period_s));
  std::unique_ptr<RunReportBuilder> builder;
  if (!o.report.empty()) builder = std::make_unique<RunReportBuilder>(machine, run_moves);
  const verify::Report r = verify::check(file.samples, moves, machine, [&](const verify::SampleMeasure& m) {
    if (builder) builder->observe(m);
  });
  nlohmann::ordered_json j = check_summary(o.program, machine, r, run_moves, file.samples.back().t_s);
  j["setpoint_file"] = o.setpoints;
  if (builder) {
    const report::Report rep = builder->build(r, file.samples, o.program);
    report::write_html_report(rep, o.report, inputs, RunReportBuilder::render_options());
  }
  write_summary(j, o.summary, o.quiet, inputs);
  return r.passed(machine);
}

}  // namespace

void register_verify_command(CLI::App& app, int& exit_code) {
  auto o = std::make_shared<VerifyOptions>();
  CLI::App* cmd = app.add_subcommand(
      "verify", "Check a setpoint file (CSV or binary, docs/setpoints.md) against a part program and a machine, "
                "independently of the planner: axis velocity, acceleration and jerk by finite differences, the "
                "distance of setpoints and chords from the path, the start and the end.");
  cmd->add_option("PROGRAM", o->program, "part program (G-code) the setpoints should follow")->required();
  cmd->add_option("SETPOINTS", o->setpoints, "setpoint file: CSV (t,x,y,z,v,block) or binary (KONTURSP)")->required();
  cmd->add_option("--machine", o->machine, "machine file: Kontur TOML, or LinuxCNC INI (default: embedded)");
  cmd->add_option("--summary", o->summary, "JSON summary file, per program and per block (default: stderr); - for stdout");
  cmd->add_option("--report", o->report, "write the HTML report of the setpoints to FILE (docs/report.md)")
      ->type_name("FILE");
  cmd->add_flag("--quiet", o->quiet, "no summary on stderr (errors are still printed)");
  cmd->add_flag("--no-blend", o->no_blend, "the path without corner blends (setpoints of kontur run --no-blend)");
  cmd->footer("Example:\n  kontur run examples/programs/square_arc.ngc -o square_arc.csv --quiet\n"
              "  kontur verify examples/programs/square_arc.ngc square_arc.csv --summary -\n"
              "Exit codes: 0 within every limit, 1 invalid program, machine or setpoint file, 2 wrong command line, "
              "4 a limit exceeded or the path left (see \"failures\" in the summary).");
  cmd->callback([o, &exit_code]() { exit_code = verify_setpoints(*o) ? exit_ok : exit_check_failed; });
}

}  // namespace kontur::app
