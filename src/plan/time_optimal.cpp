// The time-optimal reference (docs/planner.md, "Time-optimal reference"). Reachability analysis
// on a grid of arc length: with x = s_dot^2 and u = s_ddot, x' = 2 u and every axis constraint
// |t_i u + k_i x| <= A_i is linear in (u, x), so at every grid point the admissible u is an
// interval whose ends are linear in x. The backward pass gives the largest x from which the rest
// of the path can still be run to rest (the controllable set [0, K_k]); the forward pass takes at
// every point the largest admissible u that stays controllable.
#include <kontur/geometry/differential.hpp>
#include <kontur/error.hpp>
#include <kontur/interpolate/curve_interpolator.hpp>
#include <kontur/geometry/length.hpp>
#include <kontur/plan/constraints.hpp>
#include <kontur/plan/time_optimal.hpp>
#include <kontur/tolerances.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <tuple>

namespace kontur::plan {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

using Row = AccelerationRow;  // |t u + k x| <= a at a grid point, t >= 0

// The constraints of one grid point.
struct Point {
  double s = 0.0;        // arc length from the path's start [mm]
  std::size_t move = 0;  // move of the segment that starts here
  double s_move = 0.0;   // arc length on that move [mm]
  double x_max = 0.0;    // largest admissible s_dot^2 (velocity caps and acceleration) [mm^2/s^2]
  std::array<Row, 3> rows{};
  int row_count = 0;
};

// Largest speed [mm/s] from the velocity limits at one side of a point: feed, max feed, axis
// velocities along the tangent, chord error. A point that moves an axis the machine lacks has a
// cap of zero (constraints.hpp): the path cannot be run, and is refused.
double speed_cap(const Vec3& t, const Vec3& k, double feed, const Machine& machine, const LinearAxes& axes,
                 std::size_t move) {
  if (const int i = missing_axis_moved(t, axes); i >= 0)
    throw InputError("missing-axis", fmt::format("time-optimal reference: move {} runs along axis {}, which the "
                                                 "machine '{}' does not have",
                                                 move + 1, "XYZ"[i], machine.name));
  return std::min(velocity_cap(t, feed, machine, axes), chord_cap(k.norm(), machine));
}

// The axis constraints |t_i u + k_i x| <= A_i of a point with unit tangent t and curvature
// vector k [1/mm], signed so that t_i >= 0.
void set_rows(Point& p, const Vec3& t, const Vec3& k, const LinearAxes& axes) {
  p.row_count = acceleration_rows(t, k, axes, p.rows);
}

// Lower and upper end of the admissible u at x: max / min over rows of (-+a - k x) / t.
double u_lower(const Point& p, double x) {
  double u = -kInf;
  for (int r = 0; r < p.row_count; ++r) {
    const Row& w = p.rows[static_cast<std::size_t>(r)];
    if (w.t > 0.0) u = std::max(u, (-w.a - w.k * x) / w.t);
  }
  return u;
}
double u_upper(const Point& p, double x) {
  double u = kInf;
  for (int r = 0; r < p.row_count; ++r) {
    const Row& w = p.rows[static_cast<std::size_t>(r)];
    if (w.t > 0.0) u = std::min(u, (w.a - w.k * x) / w.t);
  }
  return u;
}

// Largest x at which the admissible u interval is not empty (the acceleration part of the MVC).
double acceleration_x_max(const Point& p) {
  double x = kInf;
  for (int r = 0; r < p.row_count; ++r) {
    const Row& i = p.rows[static_cast<std::size_t>(r)];
    if (i.t == 0.0) {
      if (i.k != 0.0) x = std::min(x, i.a / std::abs(i.k));  // centripetal only: |k| x <= a
      continue;
    }
    for (int q = 0; q < p.row_count; ++q) {
      const Row& j = p.rows[static_cast<std::size_t>(q)];
      if (j.t == 0.0) continue;
      // lower end of row i <= upper end of row j (i == j: both ends of one row, |k| x <= ...)
      // (-a_i - k_i x) / t_i <= (a_j - k_j x) / t_j  <=>  x (k_j/t_j - k_i/t_i) <= a_j/t_j + a_i/t_i
      const double coef = j.k / j.t - i.k / i.t;
      if (coef > 0.0) x = std::min(x, (j.a / j.t + i.a / i.t) / coef);
    }
  }
  return x;
}

// The grid of one move: arc lengths [mm] on the move, parameter values, and which are corners
// (tangent discontinuities at C0 breakpoints inside the move).
struct MoveGrid {
  std::vector<double> s, u;
  std::vector<char> corner;
};

MoveGrid move_grid(const Curve& c, const ArcLengthTable& table, double step, int min_intervals, double max_turn) {
  const double len = table.length_mm();
  const int n = std::max(min_intervals, static_cast<int>(std::ceil(len / step)));
  struct Node {
    double s, u;
    char corner;
  };
  std::vector<Node> nodes;
  nodes.reserve(static_cast<std::size_t>(n) + 1);
  for (int j = 0; j <= n; ++j) {
    const double s = j == n ? len : len * j / n;
    nodes.push_back({s, j == 0 ? c.u_min() : j == n ? c.u_max() : table.u_of_s(s), 0});
  }
  // Breakpoints inside (span ends, where sharp features of splines sit): a grid point at each,
  // marked as a corner where the tangent jumps.
  const std::vector<double> bps = c.breakpoints();
  for (std::size_t b = 1; b + 1 < bps.size(); ++b) {
    Vec3 tl, kl, tr, kr;
    std::tie(tl, kl) = tangent_and_curvature(c.derivatives_left(bps[b], 2));
    std::tie(tr, kr) = tangent_and_curvature(c.derivatives(bps[b], 2));
    const char corner = (tl - tr).norm() > tolerances::time_optimal_corner_tangent ? 1 : 0;
    nodes.push_back({table.s_of_u(bps[b]), bps[b], corner});
  }
  std::sort(nodes.begin(), nodes.end(), [](const Node& a, const Node& b) { return a.s < b.s; });
  // Merge points closer than a tiny fraction of the step (keeping a corner's exact parameter),
  // then split any interval between two corners, so that no interval joins two stops.
  const double merge = 1e-9 * std::max(len, 1.0);
  std::vector<Node> merged;
  for (const Node& q : nodes) {
    if (!merged.empty() && q.s - merged.back().s <= merge) {
      if (q.corner && merged.size() > 1) merged.back() = q;  // never move the start point
      else if (q.corner) merged.back().corner = 1;
      continue;
    }
    merged.push_back(q);
  }
  if (merged.size() > 1 && len - merged.back().s > merge) merged.push_back({len, c.u_max(), 0});
  merged.back().s = len;
  merged.back().u = c.u_max();
  // Refine where the tangent turns by more than max_turn over one interval (tight arcs, and the
  // near-cusps of splines, which a uniform grid steps over): bisect in s, down to min_step.
  {
    std::vector<Node> refined;
    refined.reserve(merged.size());
    refined.push_back(merged.front());
    struct Span {
      Node a, b;
      int depth;
    };
    std::vector<Span> stack;
    auto tangent_right = [&](double u) { return unit_tangent(c.derivatives(u, 1)); };
    auto tangent_left = [&](double u) { return unit_tangent(c.derivatives_left(u, 1)); };
    for (std::size_t i = 1; i < merged.size(); ++i) {
      stack.push_back({merged[i - 1], merged[i], 0});
      while (!stack.empty()) {
        const Span sp = stack.back();
        stack.pop_back();
        const bool split = sp.depth < tolerances::time_optimal_max_refinement &&
                           sp.b.s - sp.a.s > 2.0 * tolerances::time_optimal_min_step_mm &&
                           (tangent_right(sp.a.u) - tangent_left(sp.b.u)).norm() > max_turn;
        if (!split) {
          refined.push_back(sp.b);
          continue;
        }
        const double sm = 0.5 * (sp.a.s + sp.b.s);
        const Node mid{sm, table.u_of_s(sm), 0};
        stack.push_back({mid, sp.b, sp.depth + 1});  // the later half is taken second
        stack.push_back({sp.a, mid, sp.depth + 1});
      }
    }
    merged.swap(refined);
  }
  MoveGrid g;
  for (std::size_t i = 0; i < merged.size(); ++i) {
    if (i > 0) {
      const bool stop_before = merged[i - 1].corner || i - 1 == 0;
      const bool stop_here = merged[i].corner || i + 1 == merged.size();
      if (stop_before && stop_here) {
        const double sm = 0.5 * (merged[i - 1].s + merged[i].s);
        g.s.push_back(sm);
        g.u.push_back(table.u_of_s(sm));
        g.corner.push_back(0);
      }
    }
    g.s.push_back(merged[i].s);
    g.u.push_back(merged[i].u);
    g.corner.push_back(merged[i].corner);
  }
  return g;
}

// Largest speed [mm/s] through a tangent discontinuity from tangent tl to tr.
double corner_speed(const Vec3& tl, const Vec3& tr, const Machine& machine, const LinearAxes& axes, CornerRule rule) {
  if (rule == CornerRule::stop) return 0.0;
  return corner_acceleration_cap(tr - tl, machine, axes, 1.0, 0.0);
}

// Time [s] over one grid segment of length d [mm] from speed v0 to v1 [mm/s]: the fastest motion
// with the path acceleration bounds of the segment's start point (at x = v0^2) that never runs
// faster than the higher end speed: accelerate (or brake) at the bound, cruise at max(v0, v1).
// Where the bound is active over the whole segment this is 2 d / (v0 + v1), the constant-
// acceleration time of the grid profile; where the profile reaches a cap (feed, MVC, a corner's
// braking curve) inside the segment it is the exact time of that switch, not a whole segment at
// the mean speed (which would cost up to d / (2 v) per switch: 2.5 ms at 0.05 mm and 10 mm/s).
double segment_time(const Point& p, double d, double v0, double v1) {
  const double mean_time = 2.0 * d / (v0 + v1);
  const double vc = std::max(v0, v1);
  const double x0 = v0 * v0, x1 = v1 * v1;
  double t_change = 0.0, d_change = 0.0;
  if (v1 > v0) {
    const double a = u_upper(p, x0);
    if (!(a > 0.0)) return mean_time;
    if (std::isfinite(a)) {
      t_change = (v1 - v0) / a;
      d_change = (x1 - x0) / (2.0 * a);
    }
  } else if (v1 < v0) {
    const double b = -u_lower(p, x0);
    if (!(b > 0.0)) return mean_time;
    if (std::isfinite(b)) {
      t_change = (v0 - v1) / b;
      d_change = (x0 - x1) / (2.0 * b);
    }
  }
  if (d_change > d) return mean_time;  // rounding: the bound is active over the whole segment
  return std::min(mean_time, t_change + (d - d_change) / vc);
}

}  // namespace

TimeOptimalProfile time_optimal_profile(std::span<const TimeOptimalMove> moves, const Machine& machine,
                                        const TimeOptimalOptions& options) {
  if (!(options.max_step_mm > 0.0) || !std::isfinite(options.max_step_mm))
    throw InputError("time-optimal-step", fmt::format("time-optimal reference: max_step_mm = {} must be finite and > 0",
                                                      options.max_step_mm));
  if (!(options.max_turn_rad > 0.0) || !std::isfinite(options.max_turn_rad))
    throw InputError("time-optimal-turn", fmt::format("time-optimal reference: max_turn_rad = {} must be finite and > 0",
                                                      options.max_turn_rad));
  if (options.min_intervals_per_move < 2)
    throw InputError("time-optimal-intervals",
                     fmt::format("time-optimal reference: min_intervals_per_move = {} must be >= 2",
                                 options.min_intervals_per_move));
  const auto axes = linear_axes(machine);

  // Arc-length tables of the moves of non-zero length.
  struct Used {
    std::size_t index;
    ArcLengthTable table;
  };
  std::vector<Used> used;
  double total_length = 0.0;
  double total_intervals_at_step = 0.0;
  for (std::size_t m = 0; m < moves.size(); ++m) {
    if (moves[m].curve == nullptr)
      throw InputError("time-optimal-curve", fmt::format("time-optimal reference: move {} has no curve", m + 1));
    if (!(moves[m].feed_mm_s > 0.0) || !std::isfinite(moves[m].feed_mm_s))
      throw InputError("time-optimal-feed", fmt::format("time-optimal reference: move {} has feed {} mm/s, must be > 0",
                                                        m + 1, moves[m].feed_mm_s));
    ArcLengthTable table(*moves[m].curve);
    if (!(table.length_mm() > 0.0)) continue;
    total_length += table.length_mm();
    total_intervals_at_step += std::max<double>(options.min_intervals_per_move,
                                                std::ceil(table.length_mm() / options.max_step_mm));
    used.push_back({m, std::move(table)});
  }
  TimeOptimalProfile out;
  out.length_mm = total_length;
  if (used.empty()) {
    out.move_time_s.assign(moves.size(), 0.0);
    return out;
  }
  // Coarsen the step if the grid would exceed max_points.
  double step = options.max_step_mm;
  if (total_intervals_at_step > static_cast<double>(options.max_points))
    step = std::max(step, total_length / static_cast<double>(options.max_points));

  // Grid points with their constraints.
  std::vector<Point> pts;
  double s0 = 0.0;  // arc length at the start of the current move
  Vec3 t_prev = Vec3::Zero();  // tangent at the end of the previous move
  Vec3 k_prev = Vec3::Zero();  // and its curvature vector [1/mm]
  bool prev_exact = false;
  double end_cap = kInf;  // speed cap at the end of the previous move [mm/s]
  for (std::size_t n = 0; n < used.size(); ++n) {
    const TimeOptimalMove& mv = moves[used[n].index];
    const Curve& c = *mv.curve;
    const MoveGrid g = move_grid(c, used[n].table, step, options.min_intervals_per_move, options.max_turn_rad);
    const std::size_t last = g.s.size() - 1;
    for (std::size_t j = 0; j < last; ++j) {
      Point p;
      p.s = s0 + g.s[j];
      p.move = used[n].index;
      p.s_move = g.s[j];
      Vec3 t, k;
      std::tie(t, k) = tangent_and_curvature(c.derivatives(g.u[j], 2));
      double v = speed_cap(t, k, mv.feed_mm_s, machine, axes, p.move);
      Vec3 tl = t, kl = k;
      bool corner = false;
      if (j == 0 && n > 0) {  // junction with the move before
        tl = t_prev;
        kl = k_prev;
        v = std::min(v, end_cap);
        corner = (tl - t).norm() > tolerances::time_optimal_corner_tangent;
        if (prev_exact) v = 0.0;
      } else if (g.corner[j]) {
        std::tie(tl, kl) = tangent_and_curvature(c.derivatives_left(g.u[j], 2));
        v = std::min(v, speed_cap(tl, kl, mv.feed_mm_s, machine, axes, p.move));
        corner = true;
      }
      if (corner) {
        ++out.corners;
        v = std::min(v, corner_speed(tl, t, machine, axes, options.corners));
      }
      if (j == 0 && n == 0) v = 0.0;  // start at rest
      set_rows(p, t, k, axes);
      double x_acc = acceleration_x_max(p);
      if ((j == 0 && n > 0) || g.corner[j]) {
        // The left side's centripetal limit at the same point (the previous move's end).
        Point left;
        set_rows(left, tl, kl, axes);
        x_acc = std::min(x_acc, acceleration_x_max(left));
      }
      p.x_max = std::min(v * v, x_acc);
      pts.push_back(p);
    }
    // The end of the move: its left tangent and speed cap go to the junction with the next move.
    Vec3 te, ke;
    std::tie(te, ke) = tangent_and_curvature(c.derivatives_left(c.u_max(), 2));
    end_cap = speed_cap(te, ke, mv.feed_mm_s, machine, axes, used[n].index);
    t_prev = te;
    k_prev = ke;
    prev_exact = mv.exact_stop;
    s0 += used[n].table.length_mm();
    if (n + 1 == used.size()) {
      Point p;
      p.s = s0;
      p.move = used[n].index;
      p.s_move = used[n].table.length_mm();
      p.x_max = 0.0;  // end at rest
      pts.push_back(p);
    }
  }

  // Backward pass: K[k], the largest controllable x at point k.
  const std::size_t N = pts.size() - 1;
  std::vector<double> K(N + 1);
  K[N] = pts[N].x_max;
  for (std::size_t k = N; k-- > 0;) {
    const Point& p = pts[k];
    const double d = pts[k + 1].s - p.s;
    double x = p.x_max;
    // x + 2 d u_lower(x) <= K[k+1]: for each row, x (1 - 2 d k/t) - 2 d a / t <= K[k+1].
    for (int r = 0; r < p.row_count; ++r) {
      const Row& w = p.rows[static_cast<std::size_t>(r)];
      if (w.t == 0.0) continue;
      const double slope = 1.0 - 2.0 * d * w.k / w.t;
      const double offset = -2.0 * d * w.a / w.t;
      if (slope > 0.0) x = std::min(x, (K[k + 1] - offset) / slope);
    }
    K[k] = std::max(x, 0.0);
  }
  // Forward pass: the largest admissible u that stays controllable.
  std::vector<double> xs(N + 1, 0.0);
  xs[0] = std::min(K[0], pts[0].x_max);
  for (std::size_t k = 0; k < N; ++k) {
    const double d = pts[k + 1].s - pts[k].s;
    const double up = u_upper(pts[k], xs[k]);
    const double reach = std::isfinite(up) ? xs[k] + 2.0 * d * up : kInf;
    xs[k + 1] = std::max(0.0, std::min(K[k + 1], reach));
  }

  out.s_mm.resize(N + 1);
  out.v_mm_s.resize(N + 1);
  out.mvc_mm_s.resize(N + 1);
  out.move_index.resize(N + 1);
  out.move_s_mm.resize(N + 1);
  double time = 0.0;
  out.move_time_s.assign(moves.size(), 0.0);
  for (std::size_t k = 0; k <= N; ++k) {
    out.s_mm[k] = pts[k].s;
    out.v_mm_s[k] = std::sqrt(xs[k]);
    out.mvc_mm_s[k] = std::sqrt(pts[k].x_max);
    out.move_index[k] = pts[k].move;
    out.move_s_mm[k] = pts[k].s_move;
    if (k > 0) {
      const double sum = out.v_mm_s[k - 1] + out.v_mm_s[k];
      if (!(sum > 0.0))
        throw InputError("time-optimal-stuck",
                         fmt::format("time-optimal reference: the path cannot be run near s = {} mm (move {}): every "
                                     "admissible speed there is 0",
                                     pts[k].s, pts[k].move + 1));
      const double dt = segment_time(pts[k - 1], pts[k].s - pts[k - 1].s, out.v_mm_s[k - 1], out.v_mm_s[k]);
      time += dt;
      out.move_time_s[pts[k - 1].move] += dt;  // (the segment [k-1, k] lies on the move of its start)
    }
  }
  out.total_time_s = time;
  return out;
}

}  // namespace kontur::plan
