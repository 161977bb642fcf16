// `kontur run PROGRAM`: Kontur's main job. The program's blocks (validated first: a program with
// an error yields no setpoint) are planned on the machine and sampled at its servo period; the
// setpoints go to a CSV or binary file (or stdout), and a JSON summary checks them independently.
#include "commands.hpp"
#include "time_optimal_summary.hpp"

#include <kontur/error.hpp>
#include <kontur/gcode/reader.hpp>
#include <kontur/io/atomic_file.hpp>
#include <kontur/io/setpoint_writer.hpp>
#include <kontur/machine.hpp>
#include <kontur/plan/motion_planner.hpp>
#include <kontur/plan/program_moves.hpp>
#include <kontur/verify/checker.hpp>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <iostream>
#include <memory>

namespace kontur::app {
namespace {

struct RunOptions {
  std::string program;
  std::string machine;
  std::string output = "-";
  std::string format = "csv";
  std::string summary;
  bool time_optimal = false;
};

bool run_program(const RunOptions& o) {
  const Machine machine = o.machine.empty() ? default_machine() : read_machine(o.machine);
  if (o.machine.empty()) validate(machine);
  const SetpointFormat format = o.format == "binary" ? SetpointFormat::binary : SetpointFormat::csv;
  plan::MotionPlanner planner(machine);
  std::vector<std::shared_ptr<const Curve>> curves;  // kept for the check
  std::vector<verify::PathMove> moves;
  std::vector<verify::Sample> samples;
  std::vector<plan::TimeOptimalMove> reference_moves;  // for --time-optimal
  auto produce = [&](std::ostream& out) {
    SetpointWriter writer(out, format, machine.servo_period_s);
    plan::Setpoint sp;
    auto drain = [&] {
      while (planner.next(sp)) {
        writer.write(sp);
        samples.push_back({sp.t_s, sp.position, sp.source_line});
      }
    };
    gcode::for_each_block(o.program, [&](const gcode::Block& b) {
      const plan::MoveInput move = plan::move_input(b, machine);
      const auto& curve = move.curve;
      if (!curve) {  // a dwell: the motion stops and stays
        if (b.type == gcode::BlockType::dwell) planner.dwell(b.dwell_s, b.location.line);
        drain();
        return;
      }
      planner.push(move);
      curves.push_back(curve);
      moves.push_back({curve.get(), b.location.line});
      reference_moves.push_back({curve.get(), feed, exact});
      drain();
    });
    planner.finish();
    drain();
  };
  if (o.output == "-") {
    produce(std::cout);
  } else {
    write_file_atomically(o.output, produce, {o.program, o.machine});
  }
  const verify::Report r = verify::check(samples, moves, machine);
  nlohmann::ordered_json j;
  j["program"] = o.program;
  j["machine"] = machine.source;
  j["servo_period_s"] = machine.servo_period_s;
  j["setpoints"] = r.samples;
  j["total_time_s"] = samples.empty() ? 0.0 : samples.back().t_s;
  j["moves"] = moves.size();
  if (o.time_optimal) add_time_optimal_summary(j, reference_moves, machine, j["total_time_s"].get<double>());
  j["max_velocity_ratio"] = r.max_velocity_ratio;
  j["max_acceleration_ratio"] = r.max_acceleration_ratio;
  j["max_jerk_ratio"] = r.max_jerk_ratio;
  j["max_path_error_mm"] = r.max_path_error_mm;
  j["max_chord_error_mm"] = r.max_chord_error_mm;
  j["chord_tolerance_mm"] = machine.chord_tolerance_mm;
  j["end_error_mm"] = r.end_error_mm;
  j["passed"] = r.passed(machine);
  j["failures"] = r.failures(machine);
  const std::string text = j.dump(2) + "\n";
  if (o.summary.empty()) {
    std::cerr << text;
  } else {
    write_file_atomically(o.summary, [&](std::ostream& out) { out << text; }, {o.program, o.machine});
  }
  return r.passed(machine);
}

}  // namespace

void register_run_command(CLI::App& app, int& exit_code) {
  auto o = std::make_shared<RunOptions>();
  CLI::App* cmd = app.add_subcommand("run", "Run a part program: plan the motion on the machine and write the "
                                            "setpoints at its servo period, with an independent check of the limits.");
  cmd->add_option("PROGRAM", o->program, "part program (G-code)")->required();
  cmd->add_option("--machine", o->machine, "machine file: Kontur TOML, or LinuxCNC INI (default: embedded)");
  cmd->add_option("-o,--output", o->output, "setpoint file, '-' for stdout")->capture_default_str();
  cmd->add_option("--format", o->format, "csv or binary (docs/setpoints.md)")
      ->check(CLI::IsMember({"csv", "binary"}))
      ->capture_default_str();
  cmd->add_option("--summary", o->summary, "JSON summary file (default: stderr)");
  cmd->add_flag("--time-optimal", o->time_optimal,
                "add the time-optimal reference (acceleration-limited) and the ratio of the total time to it");
  cmd->footer("Example:\n  kontur run examples/programs/square.ngc -o square.csv --summary square.json\n"
              "Exit codes: 0 setpoints written and within the limits, 1 invalid program or machine, 2 wrong command "
              "line, 4 setpoints written but the check found a limit exceeded (see the summary).");
  cmd->callback([o, &exit_code]() { exit_code = run_program(*o) ? exit_ok : exit_check_failed; });
}

}  // namespace kontur::app
