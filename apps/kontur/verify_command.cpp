// `kontur verify PROGRAM SETPOINTS`: the independent check of `kontur run`, for any setpoint file
// (Kontur's CSV or binary, or another planner's written in the same format): finite differences
// of the setpoints against the machine's axis limits, the distance of every setpoint and every
// chord from the programmed path, the start and end. Nothing of the planner is used.
#include <fmt/format.h>

#include <cmath>
#include <filesystem>
#include <iostream>
#include <kontur/error.hpp>
#include <kontur/io/atomic_file.hpp>
#include <kontur/machine.hpp>
#include <kontur/pipeline.hpp>
#include <memory>

#include "commands.hpp"
#include "program_options.hpp"
#include "run_report.hpp"
#include "summary_output.hpp"

namespace kontur::app {
namespace {

struct VerifyOptions {
  std::string program;
  std::string setpoints;
  std::string machine;
  std::string summary;
  std::string report;
  bool quiet = false;
  bool json = false;
  bool no_blend = false;
  bool no_smooth = false;
  ProgramReadOptions read;
};

bool verify_setpoints(const VerifyOptions& o) {
  std::vector<std::filesystem::path> inputs = {o.program, o.setpoints};
  if (!o.machine.empty()) inputs.emplace_back(o.machine);
  if (!o.report.empty()) check_output_not_input(o.report, inputs);
  Machine machine = o.machine.empty() ? default_machine() : read_machine(o.machine);
  if (o.machine.empty()) validate(machine);
  PipelineOptions options;
  options.blend = !o.no_blend;
  options.smooth = !o.no_smooth;
  // The summary says which dialect was taken and why.
  options.reader = reader_options(o.read, o.program, &machine, true);
  Pipeline pipeline(std::move(machine), options);
  std::unique_ptr<RunReportBuilder> builder;
  if (!o.report.empty()) builder = std::make_unique<RunReportBuilder>(pipeline.machine(), pipeline.moves(), pipeline.layout());
  PipelineEvents events;
  if (builder) events.observer = [&](const verify::SampleMeasure& m) { builder->observe(m); };
  const RunResult result = pipeline.verify(o.program, o.setpoints, events);
  if (builder) {
    const report::Report rep = builder->build(result.check, result.total_time_s, o.program);
    report::write_html_report(rep, o.report, inputs, RunReportBuilder::render_options());
  }
  std::string footer = fmt::format("checked   {}", o.setpoints);
  if (!o.report.empty()) footer += fmt::format("\nreport    {} (open it in a browser)", o.report);
  write_summaries({o.summary, o.json, o.quiet, false}, result.summary_json, inputs, o.program, pipeline.machine(),
                  options.reader, result, pipeline.moves(), footer);
  return result.passed;
}

}  // namespace

void register_verify_command(CLI::App& app, int& exit_code) {
  auto o = std::make_shared<VerifyOptions>();
  CLI::App* cmd = app.add_subcommand(
      "verify",
      "Check a setpoint file (CSV or binary, docs/setpoints.md) against a part program and a machine, "
      "independently of the planner: axis velocity, acceleration and jerk by finite differences, the "
      "distance of setpoints and chords from the path, the start and the end.");
  cmd->add_option("PROGRAM", o->program, "part program (G-code) the setpoints should follow")->required();
  cmd->add_option("SETPOINTS", o->setpoints,
                  "setpoint file: CSV (t,x,y,z,v,block), binary (KONTURSP), or a segment stream (KONTURSG, replayed by "
                  "the lower level)")
      ->required();
  cmd->add_option("--machine", o->machine, "machine file: Kontur TOML, or LinuxCNC INI (default: embedded)");
  cmd->add_option("--summary", o->summary,
                  "JSON summary file, per program and per block (docs/setpoints.md); - for stdout (as --json)");
  cmd->add_flag("--json", o->json, "print the JSON summary on stdout instead of the short one");
  cmd->add_option("--report", o->report, "write the HTML report of the setpoints to FILE (docs/report.md)")
      ->type_name("FILE");
  cmd->add_flag("--quiet", o->quiet, "no short summary (errors are still printed)");
  cmd->add_flag("--no-blend", o->no_blend, "the path without corner blends (setpoints of kontur run --no-blend)");
  cmd->add_flag("--no-smooth", o->no_smooth,
                "the path with dense lines as programmed (setpoints of kontur run --no-smooth)");
  add_program_read_options(cmd, o->read);
  cmd->footer(
      "Example:\n  kontur run examples/programs/square_arc.ngc -o square_arc.csv --quiet\n"
      "  kontur verify examples/programs/square_arc.ngc square_arc.csv   (the short summary: limits, PASS/FAIL)\n"
      "  kontur verify examples/programs/square_arc.ngc square_arc.csv --json   (the JSON summary on stdout)\n"
      "Exit codes: 0 within every limit, 1 invalid program, machine or setpoint file, 2 wrong command line, "
      "4 a limit exceeded or the path left (see \"failures\" in the summary).");
  cmd->callback([o, &exit_code]() { exit_code = verify_setpoints(*o) ? exit_ok : exit_check_failed; });
}

}  // namespace kontur::app
