#include "arc_output.hpp"

#include <kontur/error.hpp>
#include <kontur/geometry/length.hpp>

#include <fmt/format.h>

#include <cerrno>
#include <cmath>
#include <cstdlib>

namespace kontur::app {

namespace {
constexpr int max_rows = 10'000'000;  // largest step table the command prints

std::vector<std::string> split(const std::string& text, char sep) {
  std::vector<std::string> parts;
  std::string cur;
  for (const char c : text) {
    if (c == sep) {
      parts.push_back(cur);
      cur.clear();
    } else {
      cur += c;
    }
  }
  parts.push_back(cur);
  return parts;
}

bool parse_double(const std::string& s, double& v) {
  if (s.empty()) return false;
  char* end = nullptr;
  errno = 0;
  v = std::strtod(s.c_str(), &end);
  return end != nullptr && *end == '\0' && end != s.c_str();
}
}  // namespace

void add_motion_options(CLI::App* cmd, ArcMotionOptions& o) {
  cmd->add_option("--omega", o.omega, "problem type 1: angular speed omega [rad/s] (t = theta / omega)");
  cmd->add_option("--time", o.time, "problem type 2: time t [s] (omega = theta / t)");
  cmd->add_option("--steps", o.steps, "number of equal angle steps N >= 1 (with --omega or --time)");
  cmd->add_option("--feed", o.feed, "constant-feed mode: feed F [mm/min] along the arc (with --period)");
  cmd->add_option("--period", o.period, "constant-feed mode: servo period T [s]");
  cmd->add_option("--limits", o.limits, "machine limits xmin,ymin,zmin,xmax,ymax,zmax [mm]: points and steps outside are an error");
  cmd->add_flag("--json", o.json, "print the report as JSON");
  cmd->add_flag("--csv", o.csv, "print only the step table as CSV (the constant-feed table with --feed)");
}

Vec3 parse_point(const std::string& text, const std::string& name) {
  const auto parts = split(text, ',');
  Vec3 p;
  bool ok = parts.size() == 3;
  for (std::size_t k = 0; ok && k < 3; ++k) ok = parse_double(parts[k], p[static_cast<int>(k)]);
  if (!ok)
    throw InputError("point-format",
                     fmt::format("{} = '{}': a point is x,y,z, three numbers [mm] separated by commas", name, text));
  return p;
}

std::optional<MachineLimits> parse_limits(const std::string& text) {
  if (text.empty()) return std::nullopt;
  const auto parts = split(text, ',');
  double v[6] = {0, 0, 0, 0, 0, 0};
  bool ok = parts.size() == 6;
  for (std::size_t k = 0; ok && k < 6; ++k) ok = parse_double(parts[k], v[k]);
  if (!ok)
    throw InputError("limits-format",
                     fmt::format("--limits '{}': six numbers xmin,ymin,zmin,xmax,ymax,zmax [mm] are needed", text));
  MachineLimits l;
  l.min_mm = Vec3(v[0], v[1], v[2]);
  l.max_mm = Vec3(v[3], v[4], v[5]);
  validate_limits(l);
  return l;
}

void validate_motion_options(const ArcMotionOptions& o) {
  const bool angular = o.omega || o.time;
  const bool feed = o.feed || o.period;
  if (o.omega && o.time)
    throw InputError("problem-type", "--omega and --time: give one of them (problem type 1 or 2), not both");
  if (!angular && !feed)
    throw InputError("problem-type", "give --omega W or --time T with --steps N (the seed's modes), or --feed F "
                                     "--period T (constant feed), or both");
  if (angular && !o.steps) throw InputError("steps-missing", "--steps N is needed with --omega or --time");
  if (!angular && o.steps) throw InputError("problem-type", "--steps N needs --omega W or --time T");
  if (o.omega && !(std::isfinite(*o.omega) && *o.omega > 0.0))
    throw InputError("omega-positive", fmt::format("--omega {}: the angular speed must be finite and > 0 [rad/s]", *o.omega));
  if (o.time && !(std::isfinite(*o.time) && *o.time > 0.0))
    throw InputError("time-positive", fmt::format("--time {}: the time must be finite and > 0 [s]", *o.time));
  if (o.steps && *o.steps < 1) throw InputError("steps-positive", fmt::format("--steps {}: N must be >= 1", *o.steps));
  if (o.steps && *o.steps > max_rows)
    throw InputError("steps-too-many", fmt::format("--steps {}: at most {} steps are printed", *o.steps, max_rows));
  if (feed && !(o.feed && o.period)) throw InputError("feed-period", "--feed F and --period T go together");
  if (o.feed && !(std::isfinite(*o.feed) && *o.feed > 0.0))
    throw InputError("feed-positive", fmt::format("--feed {}: the feed must be finite and > 0 [mm/min]", *o.feed));
  if (o.period && !(std::isfinite(*o.period) && *o.period > 0.0))
    throw InputError("period-positive", fmt::format("--period {}: the servo period must be finite and > 0 [s]", *o.period));
  if (o.json && o.csv) throw InputError("output-format", "--json and --csv: choose one");
  if (o.csv && angular && feed)
    throw InputError("output-format", "--csv prints one table: give either --omega/--time or --feed, not both");
}

AngularProblem problem_of(const ArcMotionOptions& o) {
  return o.omega ? AngularProblem::omega_given : AngularProblem::time_given;
}
double problem_value(const ArcMotionOptions& o) { return o.omega ? *o.omega : *o.time; }

void check_path_inside(const MachineLimits& limits, const Curve& curve, const std::vector<MotionSample>& samples,
                       const char* what) {
  for (std::size_t i = 0; i < samples.size(); ++i)
    check_inside_limits(limits, samples[i].point, fmt::format("{} {}", what, i));
  constexpr int dense = 1024;
  for (int i = 0; i <= dense; ++i) {
    const double u = curve.u_min() + (curve.u_max() - curve.u_min()) * i / dense;
    check_inside_limits(limits, curve.point(u), fmt::format("the arc at {:.4g} % of its parameter range", 100.0 * i / dense));
  }
}

std::string num(double v, int digits) {
  if (!std::isfinite(v)) return "-";  // never printed by construction; kept as a guard
  if (v == 0.0) v = 0.0;
  std::string s = fmt::format("{:.{}g}", v, digits);
  if (s.size() > 1 && s[0] == '-' && std::strtod(s.c_str(), nullptr) == 0.0) s.erase(0, 1);
  return s;
}

std::string fixed(double v, int decimals) {
  if (!std::isfinite(v)) return "-";
  std::string s = fmt::format("{:.{}f}", v, decimals);
  if (s.size() > 1 && s[0] == '-' && std::strtod(s.c_str(), nullptr) == 0.0) s.erase(0, 1);
  return s;
}

std::string point_text(const Vec3& p, int digits) {
  return fmt::format("({}, {}, {})", num(p.x(), digits), num(p.y(), digits), num(p.z(), digits));
}

std::string point_fixed(const Vec3& p) {
  return fmt::format("({}, {}, {})", fixed(p.x(), 9), fixed(p.y(), 9), fixed(p.z(), 9));
}

std::string matrix_text(const Eigen::Matrix4d& m) {
  std::string out;
  for (int r = 0; r < 4; ++r) {
    out += "    ";
    for (int c = 0; c < 4; ++c) out += fmt::format(" {:>16}", fixed(m(r, c), 9));
    out += "\n";
  }
  return out;
}

nlohmann::ordered_json point_json(const Vec3& p) {
  auto z = [](double v) { return v == 0.0 ? 0.0 : v; };
  return nlohmann::ordered_json::array({z(p.x()), z(p.y()), z(p.z())});
}

nlohmann::ordered_json matrix_json(const Eigen::Matrix4d& m) {
  auto j = nlohmann::ordered_json::array();
  for (int r = 0; r < 4; ++r) {
    auto row = nlohmann::ordered_json::array();
    for (int c = 0; c < 4; ++c) row.push_back(m(r, c) == 0.0 ? 0.0 : m(r, c));
    j.push_back(row);
  }
  return j;
}

Vec3 apply(const Eigen::Matrix4d& m, const Vec3& p) {
  return m.topLeftCorner<3, 3>() * p + m.topRightCorner<3, 1>();
}

void print_angular_table(const std::vector<AngularRow>& rows, const char* angle_name, const char* frame_name) {
  fmt::print("\nsteps (coordinates [mm] in the {} frame, then in the machine frame)\n", frame_name);
  fmt::print("  {:>8} {:>14} {:>14} {:>14} {:>14} {:>14} {:>14} {:>14} {:>14}\n", "i", "t [s]",
             fmt::format("{} [deg]", angle_name), "x'", "y'", "z'", "x", "y", "z");
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const auto& r = rows[i];
    fmt::print("  {:>8} {:>14} {:>14} {:>14} {:>14} {:>14} {:>14} {:>14} {:>14}\n", i, fixed(r.sample.time_s, 6),
               fixed(r.angle_rad * 180.0 / 3.14159265358979323846, 6), fixed(r.relative.x()), fixed(r.relative.y()),
               fixed(r.relative.z()), fixed(r.sample.point.x()), fixed(r.sample.point.y()), fixed(r.sample.point.z()));
  }
}

void print_angular_csv(const std::vector<AngularRow>& rows) {
  fmt::print("i,t_s,angle_rad,x_rel_mm,y_rel_mm,z_rel_mm,x_mm,y_mm,z_mm\n");
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const auto& r = rows[i];
    fmt::print("{},{},{},{},{},{},{},{},{}\n", i, num(r.sample.time_s, 17), num(r.angle_rad, 17), num(r.relative.x(), 17),
               num(r.relative.y(), 17), num(r.relative.z(), 17), num(r.sample.point.x(), 17),
               num(r.sample.point.y(), 17), num(r.sample.point.z(), 17));
  }
}

nlohmann::ordered_json angular_json(const std::vector<AngularRow>& rows) {
  auto j = nlohmann::ordered_json::array();
  for (const auto& r : rows) {
    nlohmann::ordered_json e;
    e["t_s"] = r.sample.time_s;
    e["angle_rad"] = r.angle_rad;
    e["relative_mm"] = point_json(r.relative);
    e["machine_mm"] = point_json(r.sample.point);
    j.push_back(e);
  }
  return j;
}

void print_feed_table(const ConstantFeedStepper& feed, const std::vector<MotionSample>& samples) {
  fmt::print("\nconstant feed F = {} mm/min at the servo period T = {} s: {} mm per period, {} periods, t = {} s\n",
             num(feed.feed_mm_min()), num(feed.period_s()), num(feed.step_mm()), samples.size() - 1,
             num(feed.time_s()));
  fmt::print("  {:>8} {:>14} {:>14} {:>14} {:>14} {:>14} {:>14}\n", "k", "t [s]", "s [mm]", "u", "x", "y", "z");
  for (std::size_t k = 0; k < samples.size(); ++k) {
    const auto& m = samples[k];
    fmt::print("  {:>8} {:>14} {:>14} {:>14} {:>14} {:>14} {:>14}\n", k, fixed(m.time_s, 6), fixed(m.arc_mm, 6),
               fixed(m.u, 9), fixed(m.point.x()), fixed(m.point.y()), fixed(m.point.z()));
  }
}

void print_feed_csv(const std::vector<MotionSample>& samples) {
  fmt::print("k,t_s,s_mm,u,x_mm,y_mm,z_mm\n");
  for (std::size_t k = 0; k < samples.size(); ++k) {
    const auto& m = samples[k];
    fmt::print("{},{},{},{},{},{},{}\n", k, num(m.time_s, 17), num(m.arc_mm, 17), num(m.u, 17), num(m.point.x(), 17),
               num(m.point.y(), 17), num(m.point.z(), 17));
  }
}

nlohmann::ordered_json feed_json(const ConstantFeedStepper& feed, const std::vector<MotionSample>& samples) {
  nlohmann::ordered_json j;
  j["feed_mm_min"] = feed.feed_mm_min();
  j["period_s"] = feed.period_s();
  j["step_mm"] = feed.step_mm();
  j["periods"] = samples.size() - 1;
  j["time_s"] = feed.time_s();
  auto& rows = j["samples"] = nlohmann::ordered_json::array();
  for (const auto& m : samples) {
    nlohmann::ordered_json e;
    e["t_s"] = m.time_s;
    e["s_mm"] = m.arc_mm;
    e["u"] = m.u;
    e["machine_mm"] = point_json(m.point);
    rows.push_back(e);
  }
  return j;
}

std::string limits_text(const MachineLimits& limits) {
  return point_text(limits.min_mm) + " .. " + point_text(limits.max_mm);
}

std::string angle_text(double rad) { return fmt::format("{} rad ({} deg)", num(rad, 9), num(rad * deg_per_rad, 10)); }

const char* seen_from_plus_z(const Vec3& normal) {
  return normal.z() > 0.0 ? "counter-clockwise" : normal.z() < 0.0 ? "clockwise" : "edge-on";
}

ArcMotion::ArcMotion(const Curve& curve, double sweep_rad, double length_mm, const Vec3& end_point,
                     const ArcMotionOptions& o, const std::function<double(double)>& table_angle,
                     const Eigen::Matrix4d& to_frame, const std::optional<MachineLimits>& limits)
    : table(curve) {
  std::vector<MotionSample> angular_samples;
  if (o.omega || o.time) {
    timing = angular_timing(sweep_rad, length_mm, problem_of(o), problem_value(o), *o.steps);
    const AngularStepper stepper(curve, *timing, end_point);
    for (int i = 0; i < stepper.samples(); ++i) {
      AngularRow r;
      r.sample = stepper.sample(i);
      r.angle_rad = table_angle(r.sample.u);
      r.relative = apply(to_frame, r.sample.point);
      rows.push_back(r);
      angular_samples.push_back(r.sample);
    }
  }
  if (o.feed) {
    feed.emplace(curve, table, end_point, *o.feed, *o.period, 10'000'000);
    for (long k = 0; k < feed->samples(); ++k) feed_samples.push_back(feed->sample(k));
  }
  if (limits) {
    check_path_inside(*limits, curve, angular_samples, "step");
    for (std::size_t k = 0; k < feed_samples.size(); ++k)
      check_inside_limits(*limits, feed_samples[k].point, fmt::format("period {}", k));
  }
}

std::string problem_text(const ArcMotionOptions& o, const char* angle) {
  return o.omega ? fmt::format("omega given, t = {} / omega", angle) : fmt::format("t given, omega = {} / t", angle);
}

void print_timing(const ArcMotionOptions& o, const AngularTiming& timing, const char* angle, const char* length,
                  const char* mean_note) {
  fmt::print("\nproblem type {}: {}\n", o.omega ? 1 : 2, problem_text(o, angle));
  fmt::print("omega = {} rad/s\nt = {} s\nN = {}\nV = {} / t = {} mm/s{}\ndt = {} s\ndphi = {}\n",
             num(timing.omega_rad_s), num(timing.time_s), timing.steps, length, num(timing.mean_speed_mm_s), mean_note,
             num(timing.dt_s), angle_text(timing.dphi_rad));
}

void print_motion_csv(const ArcMotion& m) {
  if (m.timing) print_angular_csv(m.rows);
  else print_feed_csv(m.feed_samples);
}

void add_motion_json(nlohmann::ordered_json& j, const ArcMotionOptions& o, const ArcMotion& m,
                     const nlohmann::ordered_json& speed_fields) {
  if (m.timing) {
    j["problem_type"] = o.omega ? 1 : 2;
    j["omega_rad_s"] = m.timing->omega_rad_s;
    j["time_s"] = m.timing->time_s;
    j["steps"] = m.timing->steps;
    for (auto f = speed_fields.begin(); f != speed_fields.end(); ++f) j[f.key()] = f.value();
    j["dt_s"] = m.timing->dt_s;
    j["dphi_rad"] = m.timing->dphi_rad;
    j["table"] = angular_json(m.rows);
  }
  if (m.feed) j["constant_feed"] = feed_json(*m.feed, m.feed_samples);
}

}  // namespace kontur::app
