#include <kontur/tolerances.hpp>
#include <kontur/verify/checker.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace kontur::verify {
namespace {

constexpr double kRelative = 1e-6;  // limits may be met, not exceeded by more than this

// Newton on (C(u) - p) . C'(u) = 0 in the bracket [a, b], from u.
double refine(const Curve& c, const Vec3& p, double a, double b, double u) {
  for (int i = 0; i < 60; ++i) {
    const Derivatives d = c.derivatives(u, 2);
    const Vec3 r = d[0] - p;
    const double f = r.dot(d[1]), fp = d[1].squaredNorm() + r.dot(d[2]);
    // (rounding can make f exactly zero: u is then the foot of the normal, unless it is a farthest
    // point or C' vanishes there)
    if (f == 0.0 && fp > 0.0 && d[1].squaredNorm() > 0.0) return u;
    if (f > 0.0) b = u; else a = u;
    double next = fp > 0.0 ? u - f / fp : 0.5 * (a + b);
    if (!(next >= a && next <= b)) next = 0.5 * (a + b);
    // A few units in the last place: Newton's step is then rounding noise (it may creep forever).
    if (std::abs(next - u) <= 1e-14 * std::max(1.0, std::abs(u))) return next;
    u = next;
  }
  return u;
}

// Closest parameter on a curve to p: 16 samples on every span (a NURBS with uneven weights
// moves very unevenly in u), Newton around the best, and Newton around `u_hint` (the previous
// setpoint's parameter: setpoints advance along the move); the closer of the two wins.
double project(const Curve& c, const std::vector<double>& bp, const Vec3& p, double u_hint) {
  // Setpoints advance along the move: the local refinement from the previous parameter lands on
  // the path almost always, and the global search is done only when it does not.
  const double h = (c.u_max() - c.u_min()) * 1e-3;
  const double u_local = refine(c, p, std::max(c.u_min(), u_hint - h), std::min(c.u_max(), u_hint + 64 * h),
                                std::clamp(u_hint, c.u_min(), c.u_max()));
  const double d_local = (c.point(u_local) - p).squaredNorm();
  if (d_local <= 1e-24) return u_local;  // within 1e-12 mm
  double best_u = c.u_min(), best_d = (c.point(best_u) - p).squaredNorm(), step = c.u_max() - c.u_min();
  for (std::size_t i = 0; i + 1 < bp.size(); ++i) {
    const double hs = (bp[i + 1] - bp[i]) / 16.0;
    for (int k = 0; k <= 16; ++k) {
      const double u = bp[i] + hs * k;
      const double d = (c.point(u) - p).squaredNorm();
      if (d < best_d) {
        best_d = d;
        best_u = u;
        step = hs;
      }
    }
  }
  const double u_global = refine(c, p, std::max(c.u_min(), best_u - step), std::min(c.u_max(), best_u + step), best_u);
  return (c.point(u_global) - p).squaredNorm() < d_local ? u_global : u_local;
}

// Distance from p to the segment [a, b] [mm].
double segment_distance(const Vec3& p, const Vec3& a, const Vec3& b) noexcept {
  const Vec3 ab = b - a;
  const double len2 = ab.squaredNorm();
  const double t = len2 > 0.0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  return (p - a - t * ab).norm();
}

}  // namespace

double corner_deviation(const Curve& c, const ProgrammedCorner& pc) {
  auto dev = [&](double u) {
    const Vec3 p = c.point(u);
    return std::min(segment_distance(p, pc.before, pc.corner), segment_distance(p, pc.corner, pc.after));
  };
  const int n = tolerances::blend_deviation_samples;
  const double u0 = c.u_min(), h = (c.u_max() - c.u_min()) / n;
  double best = 0.0;
  int best_k = 0;
  for (int k = 0; k <= n; ++k) {
    const double v = dev(u0 + h * k);
    if (v > best) {
      best = v;
      best_k = k;
    }
  }
  double lo = std::max(c.u_min(), u0 + h * (best_k - 1)), hi = std::min(c.u_max(), u0 + h * (best_k + 1));
  const double g = 0.5 * (std::sqrt(5.0) - 1.0);
  double x1 = hi - g * (hi - lo), x2 = lo + g * (hi - lo), f1 = dev(x1), f2 = dev(x2);
  for (int i = 0; i < 60; ++i) {
    if (f1 < f2) {
      lo = x1;
      x1 = x2;
      f1 = f2;
      x2 = lo + g * (hi - lo);
      f2 = dev(x2);
    } else {
      hi = x2;
      x2 = x1;
      f2 = f1;
      x1 = hi - g * (hi - lo);
      f1 = dev(x1);
    }
  }
  return std::max({best, f1, f2});
}

bool Report::passed(const Machine& machine) const noexcept {
  return finite && uniform_time && max_velocity_ratio <= 1 + kRelative && max_acceleration_ratio <= 1 + kRelative &&
         max_jerk_ratio <= 1 + kRelative && max_path_error_mm <= 1e-6 &&
         max_chord_error_mm <= machine.chord_tolerance_mm * (1 + kRelative) && start_error_mm <= 1e-9 &&
         end_error_mm <= 1e-9 && max_blend_deviation_ratio <= 1 + tolerances::blend_deviation_relative;
}

std::vector<std::string> Report::failures(const Machine& machine) const {
  std::vector<std::string> f;
  if (!finite) f.push_back("a setpoint is NaN or infinite");
  if (!uniform_time) f.push_back("the setpoints are not one servo period apart");
  auto limit = [&](const char* what, double r, char axis) {
    if (r > 1 + kRelative) f.push_back(fmt::format("{} of axis {} at {:.6f} times its limit", what, axis, r));
  };
  limit("velocity", max_velocity_ratio, worst_velocity_axis);
  limit("acceleration", max_acceleration_ratio, worst_acceleration_axis);
  limit("jerk", max_jerk_ratio, worst_jerk_axis);
  if (max_path_error_mm > 1e-6) f.push_back(fmt::format("a setpoint is {:.3g} mm off the path", max_path_error_mm));
  if (max_chord_error_mm > machine.chord_tolerance_mm * (1 + kRelative))
    f.push_back(fmt::format("a chord is {:.3g} mm off the path (tolerance {} mm)", max_chord_error_mm,
                            machine.chord_tolerance_mm));
  if (start_error_mm > 1e-9) f.push_back(fmt::format("the first setpoint is {:.3g} mm from the start", start_error_mm));
  if (end_error_mm > 1e-9) f.push_back(fmt::format("the last setpoint is {:.3g} mm from the end", end_error_mm));
  if (max_blend_deviation_ratio > 1 + tolerances::blend_deviation_relative)
    f.push_back(fmt::format("a corner blend is {:.6g} mm from the programmed corner (tolerance {} mm)",
                            max_blend_deviation_mm, blend_tolerance_mm));
  return f;
}

Report check(const std::vector<Sample>& s, const std::vector<PathMove>& moves, const Machine& machine) {
  return check(s, moves, machine, Observer{});
}

Report check(const std::vector<Sample>& s, const std::vector<PathMove>& moves, const Machine& machine,
             const Observer& observer) {
  Report r;
  r.samples = static_cast<long>(s.size());
  const double T = machine.servo_period_s;
  for (const Sample& p : s) r.finite = r.finite && std::isfinite(p.t_s) && p.position.allFinite();
  if (!r.finite || s.empty() || moves.empty()) return r;
  for (std::size_t k = 1; k < s.size(); ++k)
    if (std::abs((s[k].t_s - s[k - 1].t_s) - T) > 1e-9 * T + 4e-16 * std::abs(s[k].t_s)) r.uniform_time = false;
  // The linear axes (rotary axes do not carry the path) and the largest ratio of each.
  struct Axis {
    const AxisLimits* limits;
    int index;
    double max_v = 0.0, max_a = 0.0, max_j = 0.0;
  };
  std::vector<Axis> axes;
  for (const AxisLimits& ax : machine.axes)
    if (const int i = linear_axis_index(ax.name); i >= 0) axes.push_back({&ax, i});
  r.blocks.resize(moves.size());
  // Corner blends: each within the tolerance of the programmed lines it replaces.
  for (const PathMove& pm : moves) {
    if (pm.corner == nullptr) continue;
    ++r.blends;
    const double dev = corner_deviation(*pm.curve, *pm.corner);
    const double ratio = pm.corner->tolerance_mm > 0.0 ? dev / pm.corner->tolerance_mm
                                                       : (dev > 0.0 ? std::numeric_limits<double>::infinity() : 0.0);
    r.max_blend_deviation_mm = std::max(r.max_blend_deviation_mm, dev);
    if (ratio >= r.max_blend_deviation_ratio) {
      r.max_blend_deviation_ratio = ratio;
      r.blend_tolerance_mm = pm.corner->tolerance_mm;
    }
  }
  for (std::size_t i = 0; i < moves.size(); ++i) r.blocks[i].source_line = moves[i].source_line;
  // Path: the start and end, each setpoint's distance from its move, each chord's bow.
  const Curve& first = *moves.front().curve;
  const Curve& last = *moves.back().curve;
  r.start_error_mm = (s.front().position - first.point(first.u_min())).norm();
  r.end_error_mm = (s.back().position - last.point(last.u_max())).norm();
  // Each setpoint lies on the current move or a later one (setpoints never go back); the next
  // move takes over once it is at least as close (a setpoint may skip a move shorter than a cycle).
  // Breakpoints of each move, computed once (the projection samples every span).
  std::vector<std::vector<double>> breakpoints(moves.size());
  auto spans_of = [&](std::size_t i) -> const std::vector<double>& {
    if (breakpoints[i].empty()) breakpoints[i] = moves[i].curve->breakpoints();
    return breakpoints[i];
  };
  std::size_t m = 0;
  double u_prev = moves[0].curve->u_min();
  std::size_t m_prev = 0;
  SampleMeasure sm;
  for (std::size_t k = 0; k < s.size(); ++k) {
    // Finite differences on each axis: velocity, acceleration and jerk ending at k.
    const Vec3& p0 = s[k].position;
    sm.velocity.setZero();
    sm.acceleration.setZero();
    sm.jerk.setZero();
    if (k >= 1) sm.velocity = (p0 - s[k - 1].position) / T;
    if (k >= 2) sm.acceleration = (p0 - 2 * s[k - 1].position + s[k - 2].position) / (T * T);
    if (k >= 3) sm.jerk = (p0 - 3 * s[k - 1].position + 3 * s[k - 2].position - s[k - 3].position) / (T * T * T);
    sm.velocity_ratio = sm.acceleration_ratio = sm.jerk_ratio = 0.0;
    for (Axis& ax : axes) {
      const int i = ax.index;
      if (k >= 1) {
        const double v = std::abs(s[k].position[i] - s[k - 1].position[i]) / T / ax.limits->max_velocity;
        ax.max_v = std::max(ax.max_v, v);
        sm.velocity_ratio = std::max(sm.velocity_ratio, v);
      }
      if (k >= 2) {
        const double a = std::abs(s[k].position[i] - 2 * s[k - 1].position[i] + s[k - 2].position[i]) / (T * T) /
                         ax.limits->max_acceleration;
        ax.max_a = std::max(ax.max_a, a);
        sm.acceleration_ratio = std::max(sm.acceleration_ratio, a);
      }
      if (k >= 3) {
        const double j = std::abs(s[k].position[i] - 3 * s[k - 1].position[i] + 3 * s[k - 2].position[i] -
                                  s[k - 3].position[i]) /
                         (T * T * T) / ax.limits->max_jerk;
        ax.max_j = std::max(ax.max_j, j);
        sm.jerk_ratio = std::max(sm.jerk_ratio, j);
      }
    }
    // The source line selects the move (searching forward: a program may pass the same place
    // twice); among consecutive moves of the same line (canned cycles), or where lines are not
    // known, the nearest of the next few wins.
    if (moves[m].source_line != s[k].source_line) {
      for (std::size_t n = m + 1; n < moves.size(); ++n)
        if (moves[n].source_line == s[k].source_line) {
          m = n;
          break;
        }
    }
    const Curve* c = moves[m].curve;
    double u = project(*c, spans_of(m), s[k].position, m == m_prev && k > 0 ? u_prev : c->u_min());
    double d = (c->point(u) - s[k].position).norm();
    // A setpoint whose line is no move's (a dwell) stays where the motion stopped; one on a known
    // line looks among the following moves of the same line only.
    const bool line_known = s[k].source_line != 0;
    const bool on_line = moves[m].source_line == s[k].source_line;
    for (std::size_t n = m + 1; n < moves.size() && n <= m + 8 && (on_line || !line_known); ++n) {
      if (on_line && moves[n].source_line != s[k].source_line) break;
      const Curve& cn = *moves[n].curve;
      const double un = project(cn, spans_of(n), s[k].position, cn.u_min());
      const double dn = (cn.point(un) - s[k].position).norm();
      if (dn < d || (dn <= d && un > cn.u_min())) {
        m = n;
        c = &cn;
        u = un;
        d = dn;
      }
    }
    r.max_path_error_mm = std::max(r.max_path_error_mm, d);
    double chord = 0.0;
    if (k > 0 && m == m_prev && u > u_prev) {
      // The bow of the path between the two setpoints from their chord.
      const Vec3 a = s[k - 1].position, b = s[k].position, ab = b - a;
      const double len2 = ab.squaredNorm();
      for (int q = 1; q < 8; ++q) {
        const Vec3 p = c->point(u_prev + (u - u_prev) * q / 8.0) - a;
        const double t = len2 > 0.0 ? std::clamp(p.dot(ab) / len2, 0.0, 1.0) : 0.0;
        chord = std::max(chord, (p - t * ab).norm());
      }
      r.max_chord_error_mm = std::max(r.max_chord_error_mm, chord);
    }
    BlockStats& b = r.blocks[m];
    if (b.samples++ == 0) {
      b.first_sample = static_cast<long>(k);
      b.t_first_s = s[k].t_s;
    }
    b.last_sample = static_cast<long>(k);
    b.t_last_s = s[k].t_s;
    b.max_path_error_mm = std::max(b.max_path_error_mm, d);
    b.max_chord_error_mm = std::max(b.max_chord_error_mm, chord);
    b.max_velocity_ratio = std::max(b.max_velocity_ratio, sm.velocity_ratio);
    b.max_acceleration_ratio = std::max(b.max_acceleration_ratio, sm.acceleration_ratio);
    b.max_jerk_ratio = std::max(b.max_jerk_ratio, sm.jerk_ratio);
    if (observer) {
      sm.index = k;
      sm.t_s = s[k].t_s;
      sm.position = p0;
      sm.path_error_mm = d;
      sm.chord_error_mm = chord;
      sm.move = m;
      observer(sm);
    }
    u_prev = u;
    m_prev = m;
  }
  // The worst axis: the first in the machine's order with the largest ratio.
  for (const Axis& ax : axes) {
    if (ax.max_v > r.max_velocity_ratio) {
      r.max_velocity_ratio = ax.max_v;
      r.worst_velocity_axis = ax.limits->name;
    }
    if (ax.max_a > r.max_acceleration_ratio) {
      r.max_acceleration_ratio = ax.max_a;
      r.worst_acceleration_axis = ax.limits->name;
    }
    if (ax.max_j > r.max_jerk_ratio) {
      r.max_jerk_ratio = ax.max_j;
      r.worst_jerk_axis = ax.limits->name;
    }
  }
  return r;
}

}  // namespace kontur::verify
