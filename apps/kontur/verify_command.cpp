// `kontur verify PROGRAM SETPOINTS`: the independent check of `kontur run`, for any setpoint file
// (Kontur's CSV or binary, or another planner's written in the same format): finite differences
// of the setpoints against the machine's axis limits, the distance of every setpoint and every
// chord from the programmed path, the start and end. Nothing of the planner is used.
#include "check_summary.hpp"
#include "commands.hpp"
#include "run_report.hpp"

#include <kontur/error.hpp>
#include <kontur/gcode/reader.hpp>
#include <kontur/io/atomic_file.hpp>
#include <kontur/io/setpoint_reader.hpp>
#include <kontur/length.hpp>
#include <kontur/machine.hpp>
#include <kontur/plan/corner_blend.hpp>
#include <kontur/plan/program_moves.hpp>
#include <kontur/verify/checker.hpp>

#include <fmt/format.h>

#include <cmath>
#include <deque>
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
  // The path, as `kontur run` builds it: the same corner blends (plan::CornerBlender), each checked
  // against the programmed lines it replaces.
  std::vector<std::shared_ptr<const Curve>> curves;
  std::vector<verify::PathMove> moves;
  std::vector<RunMove> run_moves;
  std::deque<verify::ProgrammedCorner> corners;
  plan::CornerBlender blender(!o.no_blend, &machine);
  std::vector<plan::BlendedMove> ready;
  struct BlockInfo {
    const char* type;
    double length_mm;
    const Curve* curve;
  };
  std::vector<BlockInfo> block_info;
  auto take_ready = [&] {
    for (const plan::BlendedMove& bm : ready) {
      const auto& curve = bm.move.curve;
      curves.push_back(curve);
      const verify::ProgrammedCorner* corner = nullptr;
      if (bm.blend) corner = &corners.emplace_back(verify::ProgrammedCorner{bm.before, bm.corner, bm.after, bm.tolerance_mm});
      moves.push_back({curve.get(), bm.move.source_line, corner});
      const BlockInfo& info = block_info[bm.tag];
      run_moves.push_back({bm.move.source_line, bm.blend ? "blend" : info.type,
                           curve.get() == info.curve ? info.length_mm : length(*curve), bm.move.feed_mm_s});
    }
    ready.clear();
  };
  gcode::for_each_block(o.program, [&](const gcode::Block& b) {
    const plan::MoveInput move = plan::move_input(b, machine);
    if (!move.curve) {  // a dwell: no path, and no blend across it
      blender.flush(ready);
      take_ready();
      return;
    }
    const auto len = b.length_mm();
    block_info.push_back({gcode::to_string(b.type), len ? *len : length(*move.curve), move.curve.get()});
    blender.push(move, plan::corner_tolerance(b, machine), block_info.size() - 1, ready);
    take_ready();
  });
  blender.flush(ready);
  take_ready();
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
