#include "run_report.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <map>

#include "arc_output.hpp"
#include "report_output.hpp"

namespace kontur::app {
namespace {

// Buckets of the streaming decimation: at most 2 * buckets * (2 + 2 channels) points per series,
// e.g. 16000 for the three axes of a plot; the writer then keeps at most about
// RunReportBuilder::render_options().max_points_2d per series, with the same min/max rule.
constexpr std::size_t kBuckets = 1000;
constexpr std::size_t kMaxLabelledBlocks = 200;  // more block starts are drawn without labels

const char* axis_colors[3] = {"#d62728", "#2ca02c", "#1f77b4"};
const char* axis_names[3] = {"x", "y", "z"};

std::vector<double> channel(const report::StreamDecimator::Kept& k, std::size_t channels, std::size_t c) {
  std::vector<double> v(k.x.size());
  for (std::size_t i = 0; i < v.size(); ++i) v[i] = k.values[i * channels + c];
  return v;
}

// The limits of the linear axes as dashed lines at +limit and -limit, axes with equal limits
// sharing one pair ("X, Y").
std::vector<report::LimitLine> axis_limit_lines(const Machine& m, double AxisLimits::*field, const char* what) {
  std::map<double, std::string> by_value;
  for (const AxisLimits& ax : m.axes) {
    if (linear_axis_index(ax.name) < 0) continue;
    std::string& names = by_value[ax.*field];
    names += names.empty() ? std::string(1, ax.name) : fmt::format(", {}", ax.name);
  }
  std::vector<report::LimitLine> lines;
  for (const auto& [value, names] : by_value) {
    lines.push_back({fmt::format("+{} {} ({})", what, names, num(value)), value, "#d62728"});
    lines.push_back({fmt::format("-{} {}", what, names), -value, "#d62728"});
  }
  return lines;
}

report::Plot axis_plot(const report::StreamDecimator& d, const std::string& title, const std::string& unit,
                       std::vector<report::LimitLine> limits) {
  const auto k = d.kept();
  report::Plot p;
  p.title = title;
  p.x_label = "t [s]";
  p.y_label = unit;
  for (std::size_t a = 0; a < 3; ++a) {
    report::Series s;
    s.name = axis_names[a];
    s.color = axis_colors[a];
    s.x = k.x;
    s.y = channel(k, 3, a);
    s.source_points = d.count();
    p.series.push_back(std::move(s));
  }
  p.limits = std::move(limits);
  return p;
}

std::string ratio(double r) { return fmt::format("{:.4f}", r); }
std::string sci(double v) { return v == 0.0 ? std::string("0") : fmt::format("{:.3e}", v); }

}  // namespace

RunReportBuilder::RunReportBuilder(const Machine& machine, const std::vector<program::Move>& moves,
                                   const AxisLayout& layout)
    : machine_(machine),
      moves_(moves),
      layout_(layout),
      path_(4, kBuckets),
      speed_(2, kBuckets),
      velocity_(3, kBuckets),
      acceleration_(3, kBuckets),
      jerk_(3, kBuckets),
      error_(2, kBuckets) {}

report::RenderOptions RunReportBuilder::render_options() {
  report::RenderOptions o;
  o.max_points_2d = 12000;  // a run's time plots: 12000 points per series (the default is 4000)
  return o;
}

void RunReportBuilder::observe(const verify::SampleMeasure& s) {
  const double speed = s.velocity.norm();  // chord length of the period over T [mm/s]
  // The commanded feed, as far as the machine can go (a program may command more).
  const double feed = s.move < moves_.size() ? std::min(moves_[s.move].feed_mm_s, machine_.max_feed_mm_s) : 0.0;
  if (s.move >= max_speed_mm_s_.size()) max_speed_mm_s_.resize(s.move + 1, 0.0);
  max_speed_mm_s_[s.move] = std::max(max_speed_mm_s_[s.move], speed);
  max_speed_all_ = std::max(max_speed_all_, speed);
  const double p[4] = {s.position[0], s.position[1], s.position[2], speed};
  path_.add(s.t_s, p);
  const double sf[2] = {speed, feed};
  speed_.add(s.t_s, sf);
  velocity_.add(s.t_s, std::span<const double>(s.velocity.data(), 3));
  acceleration_.add(s.t_s, std::span<const double>(s.acceleration.data(), 3));
  jerk_.add(s.t_s, std::span<const double>(s.jerk.data(), 3));
  if (s.index == 0) {  // the layout is known once the setpoints come
    extra_letters_.clear();
    for (int i = 0; i < layout_.size(); ++i)
      if (extra_axis_index(layout_.letter(i)) >= 0) {
        extra_index_[extra_letters_.size()] = i;
        extra_letters_ += layout_.letter(i);
      }
    for (auto& d : extra_)
      d = extra_letters_.empty() ? nullptr : std::make_unique<report::StreamDecimator>(extra_letters_.size(), kBuckets);
  }
  if (!extra_letters_.empty()) {
    const AxisVector* q[4] = {&s.position, &s.velocity, &s.acceleration, &s.jerk};
    std::array<double, max_axes> v{};
    for (std::size_t k = 0; k < 4; ++k) {
      for (std::size_t e = 0; e < extra_letters_.size(); ++e) v[e] = (*q[k])[extra_index_[e]];
      extra_[k]->add(s.t_s, std::span<const double>(v.data(), extra_letters_.size()));
    }
  }
  const double e[2] = {s.chord_error_mm, s.path_error_mm};
  error_.add(s.t_s, e);
}

report::Report RunReportBuilder::build(const verify::Report& r, double total_s, const std::string& program) const {
  report::Report rep;
  rep.title = fmt::format("kontur run {}", program);
  rep.subtitle = invocation();
  const bool passed = r.passed(machine_);
  double path_length_mm = 0.0;
  for (const program::Move& m : moves_) path_length_mm += m.length_mm;
  auto& sum = rep.summary;
  sum.push_back({"result", passed ? "PASS: every limit held" : "FAIL: a limit was exceeded"});
  for (const auto& f : r.failures(machine_)) sum.push_back({"failure", f});
  sum.push_back({"program", program});
  sum.push_back({"machine", machine_.source});
  sum.push_back({"servo period", fmt::format("{} s", num(machine_.servo_period_s))});
  sum.push_back({"total time", fmt::format("{} s", fixed(total_s, 6))});
  sum.push_back({"path length (rapids included)", fmt::format("{} mm", fixed(path_length_mm, 6))});
  sum.push_back({"moves / setpoints", fmt::format("{} / {}", moves_.size(), r.samples)});
  sum.push_back({"max path speed |dp|/T", fmt::format("{} mm/s", fixed(max_speed_all_, 6))});
  auto axis = [](char c) { return c == ' ' ? std::string() : fmt::format(" (axis {})", c); };
  sum.push_back({"max axis velocity / limit", ratio(r.max_velocity_ratio) + axis(r.worst_velocity_axis)});
  sum.push_back({"max axis acceleration / limit", ratio(r.max_acceleration_ratio) + axis(r.worst_acceleration_axis)});
  sum.push_back({"max axis jerk / limit", ratio(r.max_jerk_ratio) + axis(r.worst_jerk_axis)});
  sum.push_back({"max path error (limit 1e-6 mm)", fmt::format("{} mm", sci(r.max_path_error_mm))});
  sum.push_back({"max chord error",
                 fmt::format("{} mm (tolerance {} mm)", sci(r.max_chord_error_mm), num(machine_.chord_tolerance_mm))});
  sum.push_back({"start / end error", fmt::format("{} / {} mm", sci(r.start_error_mm), sci(r.end_error_mm))});
  if (r.worst_extra_axis != ' ')
    sum.push_back({"max extra axis error (limit 1e-6)",
                   fmt::format("{} {} (axis {})", sci(r.max_extra_axis_error),
                               extra_axis_index(r.worst_extra_axis) < 3 ? "deg" : "mm", r.worst_extra_axis)});

  // The path coloured by path speed, and the start of every block.
  {
    const auto k = path_.kept();
    report::Polyline pl;
    pl.name = "path";
    pl.width_px = 4.0;
    for (std::size_t i = 0; i < k.x.size(); ++i)
      pl.points_mm.emplace_back(k.values[i * 4], k.values[i * 4 + 1], k.values[i * 4 + 2]);
    pl.scalar = channel(k, 4, 3);
    pl.scalar_name = "path speed [mm/s]";
    pl.source_points = path_.count();
    rep.polylines.push_back(std::move(pl));
    report::Polyline starts;
    starts.name = "block starts";
    starts.style = report::Style::markers;
    starts.color = "#ff7f0e";
    starts.marker_px = 4.0;
    const bool labelled = r.blocks.size() <= kMaxLabelledBlocks;
    for (const auto& b : r.blocks) {
      if (b.samples == 0) continue;
      starts.points_mm.push_back(b.first_point);
      if (labelled) starts.labels.push_back(fmt::format("N{}", b.source_line));
    }
    if (!starts.points_mm.empty()) rep.polylines.push_back(std::move(starts));
  }
  // Path speed against the commanded feed.
  {
    const auto k = speed_.kept();
    report::Plot p;
    p.title = "Path speed and commanded feed over time";
    p.x_label = "t [s]";
    p.y_label = "v [mm/s]";
    report::Series v{"path speed |p_k - p_k-1| / T", k.x, channel(k, 2, 0), "#1f77b4", false, speed_.count()};
    report::Series f{"commanded feed, at most the machine's max feed (rapid feed on rapids)",
                     k.x,
                     channel(k, 2, 1),
                     "#7f7f7f",
                     false,
                     speed_.count()};
    p.series = {std::move(v), std::move(f)};
    p.limits.push_back(
        {fmt::format("machine max feed {} mm/s", num(machine_.max_feed_mm_s)), machine_.max_feed_mm_s, "#d62728"});
    rep.plots.push_back(std::move(p));
  }
  rep.plots.push_back(axis_plot(velocity_, "Axis velocity over time (backward differences)", "v [mm/s]",
                                axis_limit_lines(machine_, &AxisLimits::max_velocity, "max velocity")));
  rep.plots.push_back(axis_plot(acceleration_, "Axis acceleration over time (second differences)", "a [mm/s^2]",
                                axis_limit_lines(machine_, &AxisLimits::max_acceleration, "max acceleration")));
  rep.plots.push_back(axis_plot(jerk_, "Axis jerk over time (third differences)", "j [mm/s^3]",
                                axis_limit_lines(machine_, &AxisLimits::max_jerk, "max jerk")));
  if (!extra_letters_.empty() && extra_[0]) {
    // The extra axes: A B C in [deg], U V W in [mm]; their limits as dashed lines.
    static const char* colors[] = {"#ff7f0e", "#9467bd", "#8c564b", "#e377c2", "#17becf", "#bcbd22"};
    const char* what[4] = {"position", "velocity", "acceleration", "jerk"};
    const char* unit[4] = {"", "/s", "/s^2", "/s^3"};
    double AxisLimits::*field[4] = {nullptr, &AxisLimits::max_velocity, &AxisLimits::max_acceleration,
                                    &AxisLimits::max_jerk};
    for (std::size_t q = 0; q < 4; ++q) {
      const auto k = extra_[q]->kept();
      report::Plot p;
      p.title = fmt::format("Extra axes {} over time{}", what[q], q == 0 ? "" : " (backward differences)");
      p.x_label = "t [s]";
      p.y_label = fmt::format("[deg{}] (A B C), [mm{}] (U V W)", unit[q], unit[q]);
      for (std::size_t e = 0; e < extra_letters_.size(); ++e) {
        const char c = extra_letters_[e];
        report::Series sr;
        sr.name = std::string(1, static_cast<char>(c - 'A' + 'a'));
        sr.color = colors[extra_axis_index(c)];
        sr.x = k.x;
        sr.y = channel(k, extra_letters_.size(), e);
        sr.source_points = extra_[q]->count();
        p.series.push_back(std::move(sr));
        if (field[q] != nullptr)
          if (const AxisLimits* ax = machine_.axis(c)) {
            const double lim = ax->*field[q];
            p.limits.push_back({fmt::format("+max {} {} ({})", what[q], c, num(lim)), lim, colors[extra_axis_index(c)]});
            p.limits.push_back({fmt::format("-max {} {}", what[q], c), -lim, colors[extra_axis_index(c)]});
          }
      }
      rep.plots.push_back(std::move(p));
    }
  }
  {
    const auto k = error_.kept();
    report::Plot p;
    p.title = "Chord error and path error over time";
    p.x_label = "t [s]";
    p.y_label = "error [mm]";
    report::Series c{"chord error (bow of the path from each period's chord)",
                     k.x,
                     channel(k, 2, 0),
                     "#9467bd",
                     false,
                     error_.count()};
    report::Series e{
        "path error (distance of the setpoint from the path)", k.x, channel(k, 2, 1), "#8c564b", false, error_.count()};
    p.series = {std::move(c), std::move(e)};
    p.limits.push_back({fmt::format("chord tolerance {} mm", num(machine_.chord_tolerance_mm)),
                        machine_.chord_tolerance_mm, "#d62728"});
    rep.plots.push_back(std::move(p));
  }
  // The blocks: a click shades the block's time span on every plot, zooms to it and marks its start.
  {
    report::Table t;
    t.title = "Blocks (click a row: its time span on the plots, its start in the views)";
    t.columns = {"#",
                 "line",
                 "type",
                 "length [mm]",
                 "feed [mm/s]",
                 "t start [s]",
                 "time [s]",
                 "setpoints",
                 "max speed [mm/s]",
                 "max v/limit",
                 "max a/limit",
                 "max j/limit",
                 "max path error [mm]",
                 "max chord error [mm]"};
    double t_prev = 0.0;
    for (std::size_t i = 0; i < r.blocks.size() && i < moves_.size(); ++i) {
      const auto& b = r.blocks[i];
      const auto& m = moves_[i];
      const bool has = b.samples > 0;
      const double max_speed = i < max_speed_mm_s_.size() ? max_speed_mm_s_[i] : 0.0;
      t.rows.push_back({fmt::format("{}", i + 1), fmt::format("{}", b.source_line), m.type, fixed(m.length_mm, 6),
                        fixed(m.feed_mm_s, 3), has ? fixed(b.t_first_s, 6) : "-",
                        has ? fixed(b.t_last_s - b.t_first_s, 6) : "-", fmt::format("{}", b.samples),
                        fixed(max_speed, 3), ratio(b.max_velocity_ratio), ratio(b.max_acceleration_ratio),
                        ratio(b.max_jerk_ratio), sci(b.max_path_error_mm), sci(b.max_chord_error_mm)});
      if (has) {
        t.links.push_back({b.t_first_s, b.first_point, b.t_last_s});
        t_prev = b.t_last_s;
      } else {
        t.links.push_back({t_prev, std::nullopt, std::nullopt});
      }
    }
    rep.tables.push_back(std::move(t));
  }
  rep.notes.push_back(
      "Velocity, acceleration and jerk are the backward differences of the setpoints per servo period T, as the "
      "independent checker computes them: (p_k - p_k-1) / T, then the same on those. The path speed is the chord of "
      "a period over T. The path error is the distance of a setpoint from its programmed move; the chord error the "
      "largest distance of the path from the chord between two setpoints of the same move.");
  rep.notes.push_back(fmt::format(
      "Large runs are decimated for display without losing the extrema: in each of at most {} runs of consecutive "
      "setpoints the first and last setpoint and the setpoints with the smallest and largest value of every plotted "
      "quantity are kept (docs/report.md). The summary and the table are computed on every setpoint.",
      2 * kBuckets));
  return rep;
}

}  // namespace kontur::app
