#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <kontur/error.hpp>
#include <kontur/gcode/tool_table.hpp>
#include <kontur/io/setpoint_reader.hpp>
#include <kontur/pipeline.hpp>
#include <kontur/plan/constraints.hpp>
#include <kontur/plan/motion_planner.hpp>
#include <kontur/plan/time_optimal.hpp>
#include <kontur/report/summary.hpp>
#include <memory>

namespace kontur {
namespace {

// A dwell (G4) of the program: the moves before it [count] and its time [s].
struct DwellAfter {
  std::size_t moves_before = 0;
  double seconds = 0.0;
};

// The time of the fastest acceleration-limited profile along the path [s]: a corner is passed with
// the velocity jump of one servo period that keeps the acceleration (what the online planner's
// junction rule allows on such a machine). It stops at each dwell, as the planner does, and waits
// the dwell's time there, counted to the move before it (to the first move before any), as the
// summary counts the planner's.
plan::TimeOptimalProfile time_optimal_reference(const std::vector<program::Move>& moves,
                                                const std::vector<DwellAfter>& dwells, const Machine& machine) {
  std::vector<plan::TimeOptimalMove> reference;
  reference.reserve(moves.size());
  for (const program::Move& m : moves) reference.push_back({m.curve.get(), m.feed_mm_s, m.exact_stop});
  for (const DwellAfter& d : dwells)
    if (d.moves_before > 0 && d.moves_before <= reference.size()) reference[d.moves_before - 1].exact_stop = true;
  plan::TimeOptimalOptions options;
  options.corners = plan::CornerRule::servo_period;
  plan::TimeOptimalProfile profile = plan::time_optimal_profile(reference, machine, options);
  for (const DwellAfter& d : dwells) {
    profile.total_time_s += d.seconds;
    if (profile.move_time_s.empty()) continue;
    const std::size_t k = d.moves_before > 0 ? std::min(d.moves_before, profile.move_time_s.size()) - 1 : 0;
    profile.move_time_s[k] += d.seconds;
  }
  return profile;
}

}  // namespace

Pipeline::Pipeline(Machine machine, PipelineOptions options)
    : machine_(std::move(machine)),
      options_(options),
      path_(
          machine_, options.blend, options.smooth,
          [this](const Curve& blend, double feed_mm_s) { return plan::curve_speed_cap(blend, feed_mm_s, machine_); },
          [this](const Derivatives& end_in, const Derivatives& start_out) {
            const plan::Junction j = plan::junction(end_in, start_out, machine_);
            return program::JunctionPass{j.velocity, j.jerk_share};  // (velocity infinite where smooth)
          }) {}

gcode::ReaderOptions program_reader_options(const std::string& program, const ProgramReading& reading,
                                            const Machine* machine) {
  gcode::ReaderOptions ro;
  ro.block_delete = reading.block_delete;
  ro.subroutine_path = reading.subroutine_path;
  if (!reading.tool_table.empty())
    ro.tool_table = std::make_shared<const gcode::ToolTable>(
        gcode::ToolTable::read(reading.tool_table, machine ? machine->tool_table_mm_per_unit : 1.0));
  // A program that cannot be opened is reported by the reader, with its own message.
  std::error_code ec;
  if (!std::filesystem::is_regular_file(program, ec)) {
    ro.dialect = reading.dialect;
    return ro;
  }
  const gcode::DialectChoice choice =
      reading.dialect ? gcode::DialectChoice{*reading.dialect, reading.given_reason}
                      : gcode::choose_dialect(program, std::nullopt, machine ? machine->dialect : std::nullopt,
                                              machine ? machine->source : std::string());
  ro.dialect = choice.dialect;
  ro.dialect_reason = choice.reason;
  return ro;
}

gcode::ReaderOptions Pipeline::reader_options() const {
  gcode::ReaderOptions o = options_.reader;
  if (!o.dialect && machine_.dialect) {
    o.dialect = machine_.dialect;
    o.dialect_reason = "the machine file's dialect";
  }
  if (o.subroutine_path.empty()) o.subroutine_path = machine_.subroutine_path;
  if (!o.arc_radius_tolerance_mm) o.arc_radius_tolerance_mm = machine_.arc_radius_tolerance_mm;
  if (!o.arc_radius_tolerance_inch) o.arc_radius_tolerance_inch = machine_.arc_radius_tolerance_inch;
  if (!o.tool_table && !machine_.tool_table.empty())  // the machine file's, in its linear units
    o.tool_table = std::make_shared<const gcode::ToolTable>(
        gcode::ToolTable::read(machine_.tool_table, machine_.tool_table_mm_per_unit));
  return o;
}

namespace {

// A file's size and modification time: whether it changed between two reads ("" when it cannot be
// read; the reader then says why).
std::string file_stamp(const std::string& path) {
  std::error_code ec;
  const auto size = std::filesystem::file_size(path, ec);
  if (ec) return {};
  const auto time = std::filesystem::last_write_time(path, ec);
  if (ec) return {};
  return std::to_string(size) + "/" + std::to_string(time.time_since_epoch().count());
}

}  // namespace

const AxisLayout& Pipeline::prepare(const std::string& program) {
  // X Y Z, then the machine's extra axes the program moves (seen in the reader's validating pass,
  // which run() then does not repeat): the setpoint files of X Y Z programs keep their X Y Z columns.
  std::string letters = "XYZ";
  bool machine_extra = false;
  for (const AxisLimits& a : machine_.axes) machine_extra = machine_extra || extra_axis_index(a.name) >= 0;
  std::array<bool, extra_axis_count> moved{};
  std::function<void(const gcode::Block&)> seen;
  if (machine_extra)
    seen = [&](const gcode::Block& b) {
      for (std::size_t e = 0; e < moved.size(); ++e) moved[e] = moved[e] || b.extra_start[e] != b.extra_end[e];
    };
  prepared_.reset();  // (a program that fails to validate leaves nothing validated behind)
  prepared_stamp_ = file_stamp(program);
  prepared_ = gcode::validate_program(program, reader_options(), seen);
  for (int e = 0; e < extra_axis_count; ++e)
    if (moved[static_cast<std::size_t>(e)] && machine_.axis(extra_axis_letters[e]) != nullptr)
      letters += extra_axis_letters[e];
  layout_ = AxisLayout::from_letters(letters);
  return layout_;
}

RunResult Pipeline::run(const std::string& program, const PipelineEvents& events) {
  // (a program file changed since prepare() is validated again)
  if (!prepared_ || prepared_->path != program || prepared_stamp_ != file_stamp(program)) prepare(program);
  const gcode::ValidatedProgram validated = std::move(*prepared_);
  prepared_.reset();  // the next run reads (and validates) its program again
  trajectory::Trajectory trajectory;
  plan::MotionPlanner planner(machine_, trajectory);
  trajectory::Sampler sampler(trajectory, machine_.servo_period_s, layout_, options_.derivatives);
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
  std::vector<DwellAfter> dwells;  // (for the time-optimal reference)
  handlers.move = [&](const program::Move& m) { planner.push(m); };
  handlers.dwell = [&](const program::Dwell& d) {
    planner.dwell(d.seconds, d.source_line);
    // (the path holds every move taken before the dwell)
    if (d.seconds > 0.0) dwells.push_back({path_.moves().size(), d.seconds});
  };
  handlers.block = [&](const gcode::Block& b) {
    drain();
    if (events.progress) events.progress(b.location.line);
  };
  path_.read(validated, handlers);
  planner.finish();
  drain();
  if (!checker) return result;
  result.check = checker->finish();
  result.passed = result.check.passed(machine_);
  report::SummaryExtras extras;
  extras.dialect = path_.dialect();
  // The reference plans the tool path (X Y Z) only: none for a program that moves extra axes.
  const bool extra = std::any_of(path_.moves().begin(), path_.moves().end(),
                                 [](const program::Move& m) { return program::moves_extra_axes(m); });
  if (options_.time_optimal && !extra) {
    plan::TimeOptimalProfile reference = time_optimal_reference(path_.moves(), dwells, machine_);
    extras.time_optimal_s = reference.total_time_s;
    extras.move_time_optimal_s = std::move(reference.move_time_s);
  }
  result.summary_json =
      report::summary_json(program, machine_, result.check, path_.moves(), result.total_time_s, extras);
  return result;
}

RunResult Pipeline::verify(const std::string& program, const std::string& setpoints, const PipelineEvents& events) {
  return verify(
      program, setpoints,
      [&](const HeaderVisitor& header, const SetpointVisitor& visit) { for_each_setpoint(setpoints, visit, header); },
      events);
}

RunResult Pipeline::verify(const std::string& program, const std::string& setpoints, const SetpointSource& source,
                           const PipelineEvents& events) {
  // The path, as run() builds it: the same corner blends, each checked against the programmed
  // lines it replaces.
  path_.read(program, {}, reader_options());
  const std::vector<program::Move>& moves = path_.moves();
  if (moves.empty())
    throw InputError("program-no-motion",
                     fmt::format("{}: the program has no move to check setpoints against", program));
  // The checker measures in the file's layout, which must have every axis the program moves.
  std::unique_ptr<verify::Checker> checker;
  RunResult result;
  auto header = [&](const SetpointHeader& h) {
    // A binary file's period is checked from its header, before any setpoint.
    if (h.period_s && std::abs(*h.period_s - machine_.servo_period_s) > 1e-12 * machine_.servo_period_s)
      throw InputError("setpoints-period",
                       fmt::format("{}: written at a servo period of {} s, but the machine's is {} s (give --machine)",
                                   setpoints, *h.period_s, machine_.servo_period_s));
    for (const program::Move& m : moves)
      for (int e = 0; e < extra_axis_count; ++e)
        if (m.extra_start[static_cast<std::size_t>(e)] != m.extra_end[static_cast<std::size_t>(e)] &&
            h.layout.index_of(extra_axis_letters[e]) < 0)
          throw InputError("setpoints-axes",
                           fmt::format("{}: the program moves {} (line {}), but the file has no column for it (its "
                                       "axes: {})",
                                       setpoints, extra_axis_letters[e], m.source_line, h.layout.letters()));
    layout_ = h.layout;
    checker = std::make_unique<verify::Checker>(moves, machine_, layout_, events.observer);
  };
  source(header, [&](const trajectory::Setpoint& s) {
    if (!checker) header(SetpointHeader{});  // a source without a header: X Y Z
    ++result.setpoints;
    result.total_time_s = s.t_s;
    if (events.setpoint) events.setpoint(s);
    checker->add(s);
  });
  if (result.setpoints == 0)
    throw InputError("setpoints-empty", fmt::format("{}: holds no setpoint", setpoints));
  result.check = checker->finish();
  result.passed = result.check.passed(machine_);
  report::SummaryExtras extras;
  extras.dialect = path_.dialect();
  extras.setpoint_file = setpoints;
  result.summary_json = report::summary_json(program, machine_, result.check, moves, result.total_time_s, extras);
  return result;
}

}  // namespace kontur
