#include "report_output.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace kontur::app {
namespace {
std::string& invocation_text() {
  static std::string text;
  return text;
}

const char* axis_colors[3] = {"#d62728", "#2ca02c", "#1f77b4"};
const char* axis_names[3] = {"x", "y", "z"};

/// Per-axis series of a 3-vector quantity over time.
void add_axis_plot(report::Report& r, const std::string& title, const std::string& y_label,
                   const std::vector<double>& t, const std::vector<Vec3>& v) {
  report::Plot p;
  p.title = title;
  p.x_label = "t [s]";
  p.y_label = y_label;
  for (int a = 0; a < 3; ++a) {
    report::Series s;
    s.name = axis_names[a];
    s.color = axis_colors[a];
    s.x = t;
    s.y.resize(v.size());
    for (std::size_t i = 0; i < v.size(); ++i) s.y[i] = v[i][a];
    p.series.push_back(std::move(s));
  }
  r.plots.push_back(std::move(p));
}
}  // namespace

const std::string& invocation() { return invocation_text(); }

void set_invocation(int argc, char** argv) {
  std::string s;
  for (int i = 0; i < argc; ++i) {
    if (i > 0) s += ' ';
    s += i == 0 ? std::string("kontur") : std::string(argv[i]);
  }
  invocation_text() = s;
}

void add_report_option(CLI::App* cmd, std::string& path) {
  cmd->add_option("--report", path,
                  "write a self-contained HTML report (3-D path, projections, plots, tables; docs/report.md) to "
                  "FILE, atomically; - writes it to the standard output")
      ->type_name("FILE");
}

report::Polyline labelled_points(const std::string& name, const std::vector<Vec3>& points,
                                 const std::vector<std::string>& labels, const std::string& color, double size_px) {
  report::Polyline p;
  p.name = name;
  p.points_mm = points;
  p.labels = labels;
  p.style = report::Style::markers;
  p.color = color;
  p.marker_px = size_px;
  return p;
}

void add_frame_axes(report::Report& r, const std::string& name, const Eigen::Matrix4d& to_machine, double length_mm) {
  const Vec3 origin = to_machine.block<3, 1>(0, 3);
  const char* primes[3] = {"x'", "y'", "z'"};
  for (int a = 0; a < 3; ++a) {
    report::Polyline p;
    p.name = fmt::format("{} {}", name, primes[a]);
    const Vec3 dir = to_machine.block<3, 1>(0, a);
    p.points_mm = {origin, origin + length_mm * dir};
    p.labels = {"", primes[a]};
    p.style = report::Style::line;
    p.color = axis_colors[a];
    p.width_px = 4.0;
    r.polylines.push_back(std::move(p));
  }
}

void add_arc_motion(report::Report& r, const Curve& curve, const std::optional<AngularTiming>& timing,
                    const std::vector<AngularRow>& rows, const char* angle_name, const char* frame_name,
                    const ConstantFeedStepper* feed, const std::vector<MotionSample>& feed_samples) {
  const double u0 = curve.u_min(), u1 = curve.u_max();
  constexpr int dense = 1000;
  report::Polyline path;
  path.name = "path";
  path.width_px = 6.0;
  std::vector<double> t_dense;
  std::vector<Vec3> v_dense, a_dense, j_dense;
  std::vector<double> speed_dense;
  for (int i = 0; i <= dense; ++i) {
    const double f = static_cast<double>(i) / dense;
    const double u = u0 + (u1 - u0) * f;
    const Derivatives d = curve.derivatives(u, 3);
    path.points_mm.push_back(d[0]);
    if (timing) {
      // The seed's mode: u grows linearly in time, du/dt = (u1 - u0) / t.
      const double du_dt = (u1 - u0) / timing->time_s;
      t_dense.push_back(f * timing->time_s);
      v_dense.push_back(d[1] * du_dt);
      a_dense.push_back(d[2] * du_dt * du_dt);
      j_dense.push_back(d[3] * du_dt * du_dt * du_dt);
      speed_dense.push_back(d[1].norm() * du_dt);
    }
  }
  if (timing) {
    path.scalar = speed_dense;
    path.scalar_name = "path speed [mm/s]";
  } else if (feed) {
    path.scalar.assign(path.points_mm.size(), feed->feed_mm_min() / 60.0);
    path.scalar_name = "path speed [mm/s]";
  }
  r.polylines.push_back(std::move(path));

  if (timing) {
    std::vector<Vec3> pts;
    for (const auto& row : rows) pts.push_back(row.sample.point);
    report::Polyline steps;
    steps.name = fmt::format("steps ({} equal {} steps)", timing->steps, angle_name);
    steps.points_mm = pts;
    steps.style = report::Style::markers;
    steps.color = "#ff7f0e";
    steps.marker_px = 6.0;
    r.polylines.push_back(std::move(steps));

    report::Plot speed;
    speed.title = fmt::format("Path speed over time (equal {} steps)", angle_name);
    speed.x_label = "t [s]";
    speed.y_label = "v [mm/s]";
    speed.series.push_back({"path speed", t_dense, speed_dense, "#1f77b4", false, 0});
    speed.limits.push_back({"mean speed V = l / t", timing->mean_speed_mm_s, "#7f7f7f"});
    r.plots.push_back(std::move(speed));
    add_axis_plot(r, "Axis velocity over time", "v [mm/s]", t_dense, v_dense);
    add_axis_plot(r, "Axis acceleration over time", "a [mm/s^2]", t_dense, a_dense);
    add_axis_plot(r, "Axis jerk over time", "j [mm/s^3]", t_dense, j_dense);

    report::Table table;
    table.title = fmt::format("Steps (coordinates [mm] in the {} frame, then in the machine frame)", frame_name);
    table.columns = {"i", "t [s]", fmt::format("{} [deg]", angle_name), "x'", "y'", "z'", "x", "y", "z"};
    for (std::size_t i = 0; i < rows.size(); ++i) {
      const auto& row = rows[i];
      table.rows.push_back({fmt::format("{}", i), fixed(row.sample.time_s, 6),
                            fixed(row.angle_rad * 180.0 / std::numbers::pi, 6), fixed(row.relative.x()),
                            fixed(row.relative.y()), fixed(row.relative.z()), fixed(row.sample.point.x()),
                            fixed(row.sample.point.y()), fixed(row.sample.point.z())});
      table.links.push_back({row.sample.time_s, row.sample.point, std::nullopt});
    }
    r.tables.push_back(std::move(table));
  }

  if (feed && feed_samples.size() >= 2) {
    const double period = feed->period_s();
    std::vector<Vec3> pts;
    for (const auto& m : feed_samples) pts.push_back(m.point);
    report::Polyline steps;
    steps.name = fmt::format("setpoints every {} s", num(period));
    steps.points_mm = pts;
    steps.style = report::Style::markers;
    steps.color = "#9467bd";
    steps.marker_px = 3.0;
    r.polylines.push_back(std::move(steps));

    // Backward differences of the setpoints: velocity at the end of each period, then
    // acceleration and jerk from those (what a drive sees).
    std::vector<double> tv, speed;
    std::vector<Vec3> v, a, jk;
    std::vector<double> ta, tj;
    for (std::size_t k = 1; k < feed_samples.size(); ++k) {
      const double dt = feed_samples[k].time_s - feed_samples[k - 1].time_s;
      if (!(dt > 0.0)) continue;
      tv.push_back(feed_samples[k].time_s);
      v.push_back((feed_samples[k].point - feed_samples[k - 1].point) / dt);
      speed.push_back((feed_samples[k].arc_mm - feed_samples[k - 1].arc_mm) / dt);
    }
    for (std::size_t k = 1; k < v.size(); ++k) {
      ta.push_back(tv[k]);
      a.push_back((v[k] - v[k - 1]) / (tv[k] - tv[k - 1]));
    }
    for (std::size_t k = 1; k < a.size(); ++k) {
      tj.push_back(ta[k]);
      jk.push_back((a[k] - a[k - 1]) / (ta[k] - ta[k - 1]));
    }
    report::Plot sp;
    sp.title = fmt::format("Path speed per servo period (constant feed, T = {} s)", num(period));
    sp.x_label = "t [s]";
    sp.y_label = "v [mm/s]";
    sp.series.push_back({"path speed (arc per period / T)", tv, speed, "#1f77b4", true, 0});
    sp.limits.push_back(
        {fmt::format("commanded feed {} mm/min", num(feed->feed_mm_min())), feed->feed_mm_min() / 60.0, "#d62728"});
    r.plots.push_back(std::move(sp));
    add_axis_plot(r, "Axis velocity per servo period (constant feed)", "v [mm/s]", tv, v);
    if (!a.empty()) add_axis_plot(r, "Axis acceleration per servo period (constant feed)", "a [mm/s^2]", ta, a);
    if (!jk.empty()) add_axis_plot(r, "Axis jerk per servo period (constant feed)", "j [mm/s^3]", tj, jk);

    report::Table table;
    table.title =
        fmt::format("Constant feed F = {} mm/min, T = {} s: setpoints [mm]", num(feed->feed_mm_min()), num(period));
    table.columns = {"k", "t [s]", "s [mm]", "u", "x", "y", "z"};
    // Made lazily: only the rows shown (at most max_rows of millions of periods) are formatted.
    table.row_count = feed_samples.size();
    table.make_row = [&feed_samples](std::size_t k) {
      const auto& m = feed_samples[k];
      return std::vector<std::string>{fmt::format("{}", k), fixed(m.time_s, 6), fixed(m.arc_mm, 6), fixed(m.u, 9),
                                      fixed(m.point.x()),   fixed(m.point.y()), fixed(m.point.z())};
    };
    table.make_link = [&feed_samples](std::size_t k) {
      return report::RowLink{feed_samples[k].time_s, feed_samples[k].point, std::nullopt};
    };
    r.tables.push_back(std::move(table));
  }
}

void add_arc_motion(report::Report& r, const Curve& curve, const ArcMotion& motion, const char* angle_name,
                    const char* frame_name) {
  add_arc_motion(r, curve, motion.timing, motion.rows, angle_name, frame_name, motion.feed ? &*motion.feed : nullptr,
                 motion.feed_samples);
}

void add_problem_summary(report::Report& r, const ArcMotionOptions& o, const AngularTiming& timing, const char* angle) {
  r.summary.push_back({"problem type", fmt::format("{}: {}", o.omega ? 1 : 2, problem_text(o, angle))});
  r.summary.push_back({"omega, t, N", fmt::format("{} rad/s, {} s, {}", num(timing.omega_rad_s), num(timing.time_s), timing.steps)});
}

void add_feed_and_limits_summary(report::Report& r, const ArcMotion& motion, const std::optional<MachineLimits>& limits) {
  if (const auto& feed = motion.feed)
    r.summary.push_back({"constant feed", fmt::format("F = {} mm/min, T = {} s: {} mm per period, {} periods, t = {} s",
                                                        num(feed->feed_mm_min()), num(feed->period_s()),
                                                        num(feed->step_mm()), motion.feed_samples.size() - 1,
                                                        num(feed->time_s()))});
  if (limits) r.summary.push_back({"machine limits [mm]", limits_text(*limits)});
}

}  // namespace kontur::app
