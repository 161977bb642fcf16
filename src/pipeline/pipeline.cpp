#include <fmt/format.h>

#include <cmath>
#include <kontur/error.hpp>
#include <kontur/io/setpoint_reader.hpp>
#include <kontur/pipeline.hpp>
#include <kontur/plan/constraints.hpp>
#include <kontur/plan/motion_planner.hpp>
#include <kontur/plan/time_optimal.hpp>
#include <kontur/report/summary.hpp>

namespace kontur {
namespace {

// The time of the fastest acceleration-limited profile along the path [s]: a corner is passed with
// the velocity jump of one servo period that keeps the acceleration (what the online planner's
// junction rule allows on such a machine).
double time_optimal_time(const std::vector<program::Move>& moves, const Machine& machine) {
  std::vector<plan::TimeOptimalMove> reference;
  reference.reserve(moves.size());
  for (const program::Move& m : moves) reference.push_back({m.curve.get(), m.feed_mm_s, m.exact_stop});
  plan::TimeOptimalOptions options;
  options.corners = plan::CornerRule::servo_period;
  return plan::time_optimal_profile(reference, machine, options).total_time_s;
}

}  // namespace

Pipeline::Pipeline(Machine machine, PipelineOptions options)
    : machine_(std::move(machine)),
      options_(options),
      path_(machine_, options.blend, options.smooth, [this](const Curve& blend, double feed_mm_s) {
        return plan::curve_speed_cap(blend, feed_mm_s, machine_);
      }) {}

gcode::ReaderOptions Pipeline::reader_options() const {
  gcode::ReaderOptions o = options_.reader;
  if (!o.dialect && machine_.dialect) {
    o.dialect = machine_.dialect;
    o.dialect_reason = "the machine file's dialect";
  }
  if (o.subroutine_path.empty()) o.subroutine_path = machine_.subroutine_path;
  if (!o.arc_radius_tolerance_mm) o.arc_radius_tolerance_mm = machine_.arc_radius_tolerance_mm;
  if (!o.arc_radius_tolerance_inch) o.arc_radius_tolerance_inch = machine_.arc_radius_tolerance_inch;
  return o;
}

RunResult Pipeline::run(const std::string& program, const PipelineEvents& events) {
  trajectory::Trajectory trajectory;
  plan::MotionPlanner planner(machine_, trajectory);
  trajectory::Sampler sampler(trajectory, machine_.servo_period_s, layout_);
  std::unique_ptr<verify::Checker> checker;
  if (options_.check) checker = std::make_unique<verify::Checker>(path_.moves(), machine_, layout_, events.observer);
  RunResult result;
  trajectory::Setpoint sp;
  auto drain = [&] {
    while (sampler.next(sp)) {
      ++result.setpoints;
      result.total_time_s = sp.t_s;
      if (events.setpoint) events.setpoint(sp);
      if (checker) checker->add(sp);
    }
  };
  program::PathHandlers handlers;
  handlers.move = [&](const program::Move& m) { planner.push(m); };
  handlers.dwell = [&](const program::Dwell& d) { planner.dwell(d.seconds, d.source_line); };
  handlers.block = [&](const gcode::Block& b) {
    drain();
    if (events.progress) events.progress(b.location.line);
  };
  path_.read(program, handlers, reader_options());
  planner.finish();
  drain();
  if (!checker) return result;
  result.check = checker->finish();
  result.passed = result.check.passed(machine_);
  report::SummaryExtras extras;
  extras.dialect = path_.dialect();
  if (options_.time_optimal) extras.time_optimal_s = time_optimal_time(path_.moves(), machine_);
  result.summary_json =
      report::summary_json(program, machine_, result.check, path_.moves(), result.total_time_s, extras);
  return result;
}

RunResult Pipeline::verify(const std::string& program, const std::string& setpoints, const PipelineEvents& events) {
  // The path, as run() builds it: the same corner blends, each checked against the programmed
  // lines it replaces.
  path_.read(program, {}, reader_options());
  const std::vector<program::Move>& moves = path_.moves();
  if (moves.empty())
    throw InputError("program-no-motion",
                     fmt::format("{}: the program has no move to check setpoints against", program));
  verify::Checker checker(moves, machine_, layout_, events.observer);
  RunResult result;
  // A binary file's period is checked from its header, before any setpoint.
  auto same_period = [&](double period_s) {
    if (std::abs(period_s - machine_.servo_period_s) > 1e-12 * machine_.servo_period_s)
      throw InputError("setpoints-period",
                       fmt::format("{}: written at a servo period of {} s, but the machine's is {} s (give --machine)",
                                   setpoints, period_s, machine_.servo_period_s));
  };
  for_each_setpoint(
      setpoints,
      [&](const trajectory::Setpoint& s) {
        ++result.setpoints;
        result.total_time_s = s.t_s;
        if (events.setpoint) events.setpoint(s);
        checker.add(s);
      },
      same_period);
  if (result.setpoints == 0)
    throw InputError("setpoints-empty", fmt::format("{}: the file holds no setpoint", setpoints));
  result.check = checker.finish();
  result.passed = result.check.passed(machine_);
  report::SummaryExtras extras;
  extras.dialect = path_.dialect();
  extras.setpoint_file = setpoints;
  result.summary_json = report::summary_json(program, machine_, result.check, moves, result.total_time_s, extras);
  return result;
}

}  // namespace kontur
