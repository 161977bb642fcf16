#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <kontur/geometry/differential.hpp>
#include <kontur/geometry/length.hpp>
#include <kontur/geometry/piece_distance.hpp>
#include <kontur/tolerances.hpp>
#include <kontur/verify/checker.hpp>
#include <limits>
#include <utility>

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
    // (C' = 0 to rounding: over the bracket the curve moves, to first order, a millionth of the
    // distance to p or less; u is a stationary point, which says nothing of where the foot is:
    // halve the bracket)
    if (d[1].norm() * (b - a) <= 1e-6 * r.norm() || d[1].squaredNorm() == 0.0) {
      const double mid = 0.5 * (a + b);
      if (mid == u || mid == a || mid == b) return u;
      u = mid;
      continue;
    }
    if (f > 0.0)
      b = u;
    else
      a = u;
    double next = fp > 0.0 ? u - f / fp : 0.5 * (a + b);
    if (!(next >= a && next <= b)) next = 0.5 * (a + b);
    // A few units in the last place: Newton's step is then rounding noise (it may creep forever).
    if (std::abs(next - u) <= 1e-14 * std::max(1.0, std::abs(u))) return next;
    u = next;
  }
  return u;
}

// The bound of the piece of c between a and b, whose ends are pa = C(a) and pb = C(b).
detail::IntervalBound interval_bound(const Curve& c, double a, double b, const Vec3& pa, const Vec3& pb) {
  const double length_mm = fixed_rule_length(c, a, b);
  const double chord_mm = (pb - pa).norm();
  return {length_mm, 0.5 * std::sqrt(std::max(0.0, length_mm * length_mm - chord_mm * chord_mm))};
}

// Closest parameter on a curve to p: the refinement forward from `u_hint` (the previous
// setpoint's parameter: setpoints advance along the move), else the nearest of 16 samples on every
// span (a NURBS with uneven weights moves very unevenly in u), refined by Newton within its span.
// Every Newton bracket lies within one span: at a breakpoint the curve may turn (a double knot) or
// stand still (repeated control points), where (C - p) . C' jumps.
// (`samples_of()` gives the move's detail::CurveSamples, computed only when the forward refinement
// does not find the setpoint on the path.)
template <class SamplesOf>
double project(const Curve& c, const std::vector<double>& bp, SamplesOf&& samples_of, const Vec3& p, double u_hint) {
  const double h = (c.u_max() - c.u_min()) * 1e-3;
  u_hint = std::clamp(u_hint, c.u_min(), c.u_max());
  const auto dist2 = [&](double u) { return (c.point(u) - p).squaredNorm(); };
  // the span holding u: bp[i] <= u < bp[i + 1] (the last span for the curve's end)
  const auto span_of = [&](double u) {
    const auto it = std::upper_bound(bp.begin(), bp.end(), u);
    const auto i = static_cast<std::size_t>(std::max<std::ptrdiff_t>(it - bp.begin() - 1, 0));
    return std::min(i, bp.size() - 2);
  };
  // Newton in [lo, hi] split at the breakpoints inside; the nearest result (the first on a tie,
  // `start` if none is nearer)
  const auto refine_spans = [&](double lo, double hi, double start) {
    double best = start, best_d = dist2(start);
    for (std::size_t i = span_of(lo); i + 1 < bp.size() && bp[i] <= hi; ++i) {
      const double a = std::max(lo, bp[i]), b = std::min(hi, bp[i + 1]);
      if (!(a <= b)) continue;
      // (from `start`, or from the start of a later span; the middle of an earlier one: at its right
      // end the derivatives are the next span's)
      const double u = refine(c, p, a, b, start < a ? a : (start > b ? 0.5 * (a + b) : start));
      const double d = dist2(u);
      if (d < best_d) {
        best_d = d;
        best = u;
      }
    }
    return best;
  };
  // forward, within the span of u_hint and the next ones up to 64 h ahead
  const double u_forward = refine_spans(u_hint, std::min(c.u_max(), u_hint + 64 * h), u_hint);
  if (dist2(u_forward) <= 1e-24) return u_forward;  // within 1e-12 mm
  const double u_local = refine_spans(std::max(c.u_min(), u_hint - h), u_hint, u_hint);
  // Every local minimum of the distance over 17 samples of every span, refined within the span: a
  // candidate each (the nearest of the whole curve may be in a span of no length, beyond a corner
  // the forward refinement does not reach, or on a branch of a loop that passes close by).
  // A sample interval of arc length L between points at distances d0 and d1 holds no point nearer
  // than (d0 + d1 - L) / 2; where that is nearer than the nearest candidate, the interval is
  // sampled 8 times finer, 3 levels deep, check_projection_search_budget times at most (a degree-9
  // Bezier of 3 um with weights 0.01..23 loops within one sample interval: a false "2.3e-6 mm off
  // the path", property seed 976). L is the 7-point Gauss rule's estimate, not a bound.
  std::vector<double> candidates = {u_forward, u_local};
  double nearest = std::min(std::sqrt(dist2(u_forward)), std::sqrt(dist2(u_local)));
  const auto add_minima = [&](const double* us, const double* ds, std::size_t n) {
    for (std::size_t k = 0; k < n; ++k) {
      if ((k > 0 && ds[k] > ds[k - 1]) || (k + 1 < n && ds[k] > ds[k + 1])) continue;
      const double lo = us[k > 0 ? k - 1 : 0], hi = us[k + 1 < n ? k + 1 : n - 1];
      // (from inside the span: at its right end the derivatives are the next span's)
      const double u = refine(c, p, lo, hi, k + 1 < n ? us[k] : 0.5 * (lo + hi));
      candidates.push_back(u);
      nearest = std::min(nearest, std::sqrt(dist2(u)));
    }
  };
  // A lower bound of the distance from p to the piece between C(a) and C(b) of arc length L: every
  // point of it is within L of both ends taken together, and within the ellipsoid of foci C(a),
  // C(b) and major axis L, so within the capsule of radius sqrt(L^2 - chord^2) / 2 around the chord.
  const auto may_hold_nearer = [&](const Vec3& ca, const Vec3& cb, double da2, double db2,
                                   const detail::IntervalBound& piece) {
    const Vec3 chord = cb - ca;
    const double chord2 = chord.squaredNorm();
    const double along = chord2 > 0.0 ? std::clamp((p - ca).dot(chord) / chord2, 0.0, 1.0) : 0.0;
    const double bound_mm = std::max(0.5 * (std::sqrt(da2) + std::sqrt(db2) - piece.length_mm),
                                     (p - (ca + along * chord)).norm() - piece.radius_mm);
    // (nearer by a share of the distance worth finding: the deviation is then right to that share)
    return bound_mm < nearest - std::max(1e-9, tolerances::check_projection_search_relative * nearest);
  };
  int budget = tolerances::check_projection_search_budget;  // finer searches left
  const auto finer = [&](auto&& self, double a, double b, int depth) -> void {
    if (budget <= 0) return;
    --budget;
    std::array<double, 9> fu{}, fd{};
    std::array<Vec3, 9> fp{};
    for (std::size_t k = 0; k < 9; ++k) {
      fu[k] = k == 8 ? b : a + (b - a) * static_cast<double>(k) / 8.0;
      fp[k] = c.point(fu[k]);
      fd[k] = (fp[k] - p).squaredNorm();
    }
    add_minima(fu.data(), fd.data(), 9);
    if (depth <= 1) return;
    for (std::size_t k = 0; k < 8; ++k)
      if (may_hold_nearer(fp[k], fp[k + 1], fd[k], fd[k + 1], interval_bound(c, fu[k], fu[k + 1], fp[k], fp[k + 1])))
        self(self, fu[k], fu[k + 1], depth - 1);
  };
  const detail::CurveSamples& samples = samples_of();
  std::array<double, 17> ds{};
  for (std::size_t i = 0; i + 1 < bp.size(); ++i) {
    const Vec3* ps = samples.point.data() + 17 * i;
    for (std::size_t k = 0; k < 17; ++k) ds[k] = (ps[k] - p).squaredNorm();
    add_minima(samples.u.data() + 17 * i, ds.data(), 17);
  }
  // Finer only where the samples leave the setpoint measurably off the path (tolerances.hpp:
  // check_projection_search_above_mm; a 100-turn arc's setpoints at 1e-12 mm cost nothing more).
  if (nearest > tolerances::check_projection_search_above_mm) {
    std::vector<std::pair<double, std::size_t>> open;  // (distance of an interval's ends, its index)
    for (std::size_t i = 0; i + 1 < bp.size(); ++i) {
      const Vec3* ps = samples.point.data() + 17 * i;
      for (std::size_t k = 0; k < 16; ++k) {
        const double d0 = (ps[k] - p).squaredNorm(), d1 = (ps[k + 1] - p).squaredNorm();
        if (may_hold_nearer(ps[k], ps[k + 1], d0, d1, samples.bound[16 * i + k]))
          open.emplace_back(std::min(d0, d1), 16 * i + k);
      }
    }
    // (the nearest intervals first: the search is bounded, tolerances::check_projection_search_budget)
    std::sort(open.begin(), open.end());
    for (const auto& entry : open) {
      const std::size_t j = entry.second;
      const double* us = samples.u.data() + 17 * (j / 16) + j % 16;
      finer(finer, us[0], us[1], 3);
    }
  }
  // Of the points within 1e-9 mm of the nearest, the first one ahead of u_hint: where the path
  // passes a place twice (a multi-turn arc, a cusp that turns back along itself), the other pass
  // may be as near, and jumping there would break the order of the setpoints along the move.
  double chosen = std::numeric_limits<double>::quiet_NaN();
  for (double u : candidates)
    if (u >= u_hint && std::sqrt(dist2(u)) <= nearest + 1e-9 && !(u >= chosen)) chosen = u;
  if (chosen == chosen) return chosen;
  // (none ahead: the local one if it is as near; else the nearest point ahead where it is within
  // the check's path tolerance, tolerances::check_resync_mm, of the nearest: a setpoint a hair past
  // the end of a closed curve, nearest to its start, stays at the end, as the motion does; else
  // the nearest)
  if (std::sqrt(dist2(u_local)) <= nearest + 1e-9) return u_local;
  double ahead = std::numeric_limits<double>::quiet_NaN(), ahead_d2 = 0.0;
  for (double u : candidates)
    if (u >= u_hint && (!(ahead == ahead) || dist2(u) < ahead_d2)) {
      ahead = u;
      ahead_d2 = dist2(u);
    }
  if (ahead == ahead && std::sqrt(ahead_d2) <= nearest + tolerances::check_resync_mm) return ahead;
  return *std::min_element(candidates.begin(), candidates.end(),
                           [&](double a, double b) { return dist2(a) < dist2(b); });
}

// One more deviation [mm] from a programmed shape with its tolerance [mm]: the largest deviation,
// the largest deviation / tolerance and the tolerance it was measured against.
void track_deviation(double deviation_mm, double tolerance_mm, double& max_mm, double& max_ratio,
                     double& worst_tolerance_mm) noexcept {
  const double ratio = tolerance_mm > 0.0 ? deviation_mm / tolerance_mm
                                          : (deviation_mm > 0.0 ? std::numeric_limits<double>::infinity() : 0.0);
  max_mm = std::max(max_mm, deviation_mm);
  if (ratio >= max_ratio) {
    max_ratio = ratio;
    worst_tolerance_mm = tolerance_mm;
  }
}

}  // namespace

// A bounding-box tree over the moves: leaves of a few moves, each box holding the move's samples
// (8 per span and the ends) grown by the longest distance between consecutive samples, which the
// curve between them cannot leave for any curve the program stage makes (lines, arcs, splines
// whose spans are sampled densely enough that a span does not turn by more than a right angle
// between samples).
struct PathIndex {
  struct Box {
    Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity());
    Vec3 hi = Vec3::Constant(-std::numeric_limits<double>::infinity());
    void add(const Vec3& p) {
      lo = lo.cwiseMin(p);
      hi = hi.cwiseMax(p);
    }
    void add(const Box& b) {
      lo = lo.cwiseMin(b.lo);
      hi = hi.cwiseMax(b.hi);
    }
    [[nodiscard]] double distance(const Vec3& p) const { return (p.cwiseMax(lo).cwiseMin(hi) - p).norm(); }
  };
  struct Node {
    Box box;
    std::size_t first = 0, count = 0;  // a leaf: order[first .. first + count)
    std::size_t left = 0, right = 0;   // an inner node (count == 0)
  };
  std::vector<Box> boxes;          // per move
  std::vector<std::size_t> order;  // moves, grouped by leaf
  std::vector<Node> nodes;         // nodes[0]: the root

  PathIndex(const std::vector<program::Move>& moves,
            const std::function<const std::vector<double>&(std::size_t)>& spans) {
    boxes.resize(moves.size());
    for (std::size_t i = 0; i < moves.size(); ++i) {
      const Curve& c = *moves[i].curve;
      const std::vector<double>& bp = spans(i);
      Box b;
      Vec3 prev = c.point(c.u_min());
      double step = 0.0;
      b.add(prev);
      for (std::size_t k = 0; k + 1 < bp.size(); ++k)
        for (int q = 1; q <= 8; ++q) {
          const Vec3 p = c.point(bp[k] + (bp[k + 1] - bp[k]) * q / 8.0);
          step = std::max(step, (p - prev).norm());
          b.add(p);
          prev = p;
        }
      b.lo.array() -= step;
      b.hi.array() += step;
      boxes[i] = b;
    }
    order.resize(moves.size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
    if (!order.empty()) build(0, order.size());
  }

  std::size_t build(std::size_t first, std::size_t count) {
    const std::size_t id = nodes.size();
    nodes.emplace_back();
    Box box, centres;
    for (std::size_t k = first; k < first + count; ++k) {
      box.add(boxes[order[k]]);
      centres.add(0.5 * (boxes[order[k]].lo + boxes[order[k]].hi));
    }
    nodes[id].box = box;
    if (count <= 4) {
      nodes[id].first = first;
      nodes[id].count = count;
      return id;
    }
    int axis = 0;
    (centres.hi - centres.lo).maxCoeff(&axis);
    const auto mid = static_cast<std::ptrdiff_t>(first + count / 2);
    const auto begin = order.begin() + static_cast<std::ptrdiff_t>(first);
    std::nth_element(begin, order.begin() + mid, begin + static_cast<std::ptrdiff_t>(count),
                     [&](std::size_t a, std::size_t b) {
                       return boxes[a].lo[axis] + boxes[a].hi[axis] < boxes[b].lo[axis] + boxes[b].hi[axis];
                     });
    const std::size_t left = build(first, count / 2);
    const std::size_t right = build(first + count / 2, count - count / 2);
    nodes[id].left = left;
    nodes[id].right = right;
    return id;
  }
};

Checker::~Checker() = default;

void Checker::nearest_on_path(const Vec3& p, std::size_t& m, double& u, double& d) {
  if (!index_)
    index_ = std::make_unique<PathIndex>(moves_,
                                         [this](std::size_t i) -> const std::vector<double>& { return spans_of(i); });
  const PathIndex& ix = *index_;
  std::vector<std::size_t>& stack = search_stack_;
  stack.assign(1, 0);
  while (!stack.empty()) {
    const PathIndex::Node& node = ix.nodes[stack.back()];
    stack.pop_back();
    if (!(node.box.distance(p) < d)) continue;
    if (node.count == 0) {
      // the nearer child last, so that it is searched first
      const bool left_nearer = ix.nodes[node.left].box.distance(p) <= ix.nodes[node.right].box.distance(p);
      stack.push_back(left_nearer ? node.right : node.left);
      stack.push_back(left_nearer ? node.left : node.right);
      continue;
    }
    for (std::size_t k = node.first; k < node.first + node.count; ++k) {
      const std::size_t n = ix.order[k];
      if (!(ix.boxes[n].distance(p) < d)) continue;
      const Curve& c = *moves_[n].curve;
      const double un = project_on(n, p, c.u_min());
      const double dn = (c.point(un) - p).norm();
      if (dn < d) {
        m = n;
        u = un;
        d = dn;
      }
    }
  }
}

double blend_deviation(const Curve& c, const program::ProgrammedCorner& pc) {
  const PieceDistance before(*pc.before), after(*pc.after);
  auto dev = [&](double u) { return nearer_distance(before, after, c.point(u)); };
  const int n = tolerances::check_blend_samples;
  const double u0 = c.u_min(), h = (c.u_max() - c.u_min()) / n;
  std::vector<double> f(static_cast<std::size_t>(n) + 1);
  for (int k = 0; k <= n; ++k) f[static_cast<std::size_t>(k)] = dev(u0 + h * k);
  double best = *std::max_element(f.begin(), f.end());
  // Every interior local maximum of the samples: successive parabolic interpolation through the
  // best three points, kept inside the bracket [u_{k-1}, u_{k+1}] (bisection when the parabola
  // leaves it or is flat).
  for (int k = 1; k < n; ++k) {
    const auto kk = static_cast<std::size_t>(k);
    if (!(f[kk] >= f[kk - 1] && f[kk] >= f[kk + 1])) continue;
    double a = u0 + h * (k - 1), b = u0 + h * (k + 1);
    double x = u0 + h * k, fx = f[kk];
    double w = a, fw = f[kk - 1], v = b, fv = f[kk + 1];
    for (int i = 0; i < 80 && b - a > 1e-15 * std::max(1.0, std::abs(x)); ++i) {
      const double num = (x - w) * (x - w) * (fx - fv) - (x - v) * (x - v) * (fx - fw);
      const double den = (x - w) * (fx - fv) - (x - v) * (fx - fw);
      double t = den != 0.0 ? x - 0.5 * num / den : 0.5 * (a + b);
      if (!(t > a && t < b) || t == x) t = x < 0.5 * (a + b) ? 0.5 * (x + b) : 0.5 * (a + x);
      const double ft = dev(t);
      best = std::max(best, ft);
      if (ft >= fx) {
        (t < x ? b : a) = x;
        v = w;
        fv = fw;
        w = x;
        fw = fx;
        x = t;
        fx = ft;
      } else {
        (t < x ? a : b) = t;
        v = w;
        fv = fw;
        w = t;
        fw = ft;
      }
    }
  }
  return best;
}

bool Report::passed(const Machine& machine) const noexcept {
  return finite && uniform_time && max_velocity_excess <= 1 + kRelative && max_acceleration_excess <= 1 + kRelative &&
         max_jerk_excess <= 1 + kRelative && max_path_error_mm <= 1e-6 &&
         max_chord_error_mm <= machine.chord_tolerance_mm * (1 + kRelative) && start_error_mm <= 1e-9 &&
         end_error_mm <= 1e-9 && max_extra_axis_error <= 1e-6 && max_blend_deviation_ratio <= 1 + tolerances::blend_deviation_relative &&
         max_smoothing_deviation_ratio <= 1 + tolerances::smoothing_deviation_relative;
}

std::vector<std::string> Report::failures(const Machine& machine) const {
  std::vector<std::string> f;
  if (!finite) f.push_back("a setpoint is NaN or infinite");
  if (!uniform_time) f.push_back("the setpoints are not one servo period apart");
  auto limit = [&](const char* what, double r, double excess, char axis) {
    if (excess > 1 + kRelative) f.push_back(fmt::format("{} of axis {} at {:.6f} times its limit", what, axis, r));
  };
  limit("velocity", max_velocity_ratio, max_velocity_excess, worst_velocity_axis);
  limit("acceleration", max_acceleration_ratio, max_acceleration_excess, worst_acceleration_axis);
  limit("jerk", max_jerk_ratio, max_jerk_excess, worst_jerk_axis);
  if (max_path_error_mm > 1e-6) f.push_back(fmt::format("a setpoint is {:.3g} mm off the path", max_path_error_mm));
  if (max_chord_error_mm > machine.chord_tolerance_mm * (1 + kRelative))
    f.push_back(fmt::format("a chord is {:.3g} mm off the path (tolerance {} mm)", max_chord_error_mm,
                            machine.chord_tolerance_mm));
  if (start_error_mm > 1e-9) f.push_back(fmt::format("the first setpoint is {:.3g} mm from the start", start_error_mm));
  if (end_error_mm > 1e-9)
    f.push_back(end_error_line > 0
                    ? fmt::format("the move of line {} ends {:.3g} mm from where the next one starts", end_error_line,
                                  end_error_mm)
                    : fmt::format("the last setpoint is {:.3g} mm from the end", end_error_mm));
  if (max_extra_axis_error > 1e-6)
    f.push_back(fmt::format("axis {} of a setpoint is {:.3g} {} from where its move puts it", worst_extra_axis,
                            max_extra_axis_error, extra_axis_index(worst_extra_axis) < 3 ? "deg" : "mm"));
  if (max_blend_deviation_ratio > 1 + tolerances::blend_deviation_relative)
    f.push_back(fmt::format("a corner blend is {:.6g} mm from the programmed corner (tolerance {} mm)",
                            max_blend_deviation_mm, blend_tolerance_mm));
  if (max_smoothing_deviation_ratio > 1 + tolerances::smoothing_deviation_relative)
    f.push_back(fmt::format("a setpoint of a smoothed run is {:.6g} mm from the programmed lines (tolerance {} mm)",
                            max_smoothing_deviation_mm, smoothing_tolerance_mm));
  return f;
}

Checker::Checker(const std::vector<program::Move>& moves, const Machine& machine, const AxisLayout& layout,
                 Observer observer)
    : moves_(moves),
      machine_(machine),
      layout_(layout),
      observer_(std::move(observer)),
      period_(machine.servo_period_s) {
  // The axes of the layout with their limits, in the machine's order (the worst axis is the first
  // with the largest ratio).
  for (const AxisLimits& ax : machine.axes)
    if (const int i = layout_.index_of(ax.name); i >= 0) axes_.push_back({&ax, i});
  for (AxisVector& p : previous_) p = AxisVector::Zero(layout_.size());
  sm_.position = sm_.velocity = sm_.acceleration = sm_.jerk = AxisVector::Zero(layout_.size());
}

const std::vector<double>& Checker::spans_of(std::size_t i) {
  if (breakpoints_.size() <= i) breakpoints_.resize(i + 1);
  if (breakpoints_[i].empty()) breakpoints_[i] = moves_[i].curve->breakpoints();
  return breakpoints_[i];
}

const detail::CurveSamples& Checker::samples_of(std::size_t i) {
  for (const detail::CurveSamples& s : samples_)
    if (s.move == i) return s;
  detail::CurveSamples& s = samples_[samples_next_];
  samples_next_ = (samples_next_ + 1) % samples_.size();
  const Curve& c = *moves_[i].curve;
  const std::vector<double>& bp = spans_of(i);
  s.move = i;
  s.u.clear();
  s.point.clear();
  s.bound.clear();
  for (std::size_t j = 0; j + 1 < bp.size(); ++j)
    for (std::size_t k = 0; k < 17; ++k) {
      const double u = k == 16 ? bp[j + 1] : bp[j] + (bp[j + 1] - bp[j]) * static_cast<double>(k) / 16.0;
      s.u.push_back(u);
      // (the span's end as its own limit: at a breakpoint the next span may start elsewhere only in
      // its derivatives; the point is the same)
      s.point.push_back(c.point(u));
      if (k > 0) s.bound.push_back(interval_bound(c, s.u[s.u.size() - 2], u, s.point[s.point.size() - 2], s.point.back()));
    }
  return s;
}

double Checker::project_on(std::size_t n, const Vec3& p, double u_hint) {
  return project(*moves_[n].curve, spans_of(n), [&]() -> const detail::CurveSamples& { return samples_of(n); }, p, u_hint);
}

const std::vector<double>& Checker::corners_of(std::size_t i) {
  if (corners_.size() <= i) corners_.resize(i + 1);
  if (!corners_[i]) {
    const Curve& c = *moves_[i].curve;
    std::vector<double> out = stationary_points(c, tolerances::plan_stationary_speed_relative,
                                                tolerances::plan_stationary_search_samples);
    const std::vector<double>& bp = spans_of(i);
    for (std::size_t k = 1; k + 1 < bp.size(); ++k) {
      const Vec3 before = unit_tangent(c.derivatives_left(bp[k], 1)), after = unit_tangent(c.derivatives(bp[k], 1));
      if (!before.isZero() && !after.isZero() && (after - before).norm() > tolerances::check_corner_tangent_jump)
        out.push_back(bp[k]);
    }
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
    corners_[i] = std::move(out);
  }
  return *corners_[i];
}

std::size_t Checker::match(const Sample& s, const Vec3& p, double& u, double& d) {
  const std::size_t k = static_cast<std::size_t>(r_.samples - 1);
  if (s.move != program::no_move && s.move < moves_.size()) {
    // The planner's setpoint names its move.
    const std::size_t m = s.move;
    const Curve& c = *moves_[m].curve;
    u = project_on(m, p, m == m_prev_ && k > 0 ? u_prev_ : c.u_min());
    d = (c.point(u) - p).norm();
    return m;
  }
  // The source line selects the move (searching forward: a program may pass the same place
  // twice); among consecutive moves of the same line (canned cycles), or where lines are not
  // known, the nearest of the next few wins.
  std::size_t m = m_;
  if (moves_[m].source_line != s.source_line) {
    for (std::size_t n = m + 1; n < moves_.size(); ++n)
      if (moves_[n].source_line == s.source_line) {
        m = n;
        break;
      }
  }
  const Curve* c = moves_[m].curve.get();
  u = project_on(m, p, m == m_prev_ && k > 0 ? u_prev_ : c->u_min());
  d = (c->point(u) - p).norm();
  // A setpoint whose line is no move's (a dwell) stays where the motion stopped; one on a known
  // line looks among the following moves of the same line only.
  const bool line_known = s.source_line != 0;
  const bool on_line = moves_[m].source_line == s.source_line;
  for (std::size_t n = m + 1; n < moves_.size() && n <= m + 8 && (on_line || !line_known); ++n) {
    if (on_line && moves_[n].source_line != s.source_line) break;
    const Curve& cn = *moves_[n].curve;
    const double un = project_on(n, p, cn.u_min());
    const double dn = (cn.point(un) - p).norm();
    if (dn < d || (dn <= d && un > cn.u_min())) {
      m = n;
      u = un;
      d = dn;
    }
  }
  // Off the moves the line suggests (another planner's blends, block 0, a path that comes back to
  // a point it passed): the nearest point of the whole path.
  if (d > tolerances::check_resync_mm) nearest_on_path(p, m, u, d);
  return m;
}

double Checker::extra_axis_error(const AxisVector& position, std::size_t m, double u, char& axis) {
  const program::Move& mv = moves_[m];
  const ExtraAxes x = layout_.extra(position);
  ExtraAxes want = mv.extra_start;
  if (program::moves_extra_axes(mv)) {
    double f = 0.0;  // where along the move, 0 .. 1
    if (mv.tool_still) {
      // the nearest point of the straight line between start and end, over the layout's extra axes
      double num = 0.0, den = 0.0;
      for (int e = 0; e < extra_axis_count; ++e) {
        if (layout_.index_of(extra_axis_letters[e]) < 0) continue;
        const auto i = static_cast<std::size_t>(e);
        const double d = mv.extra_end[i] - mv.extra_start[i];
        num += (x[i] - mv.extra_start[i]) * d;
        den += d * d;
      }
      f = den > 0.0 ? std::clamp(num / den, 0.0, 1.0) : 0.0;
    } else {
      if (tables_.size() <= m) tables_.resize(m + 1);
      if (!tables_[m]) tables_[m] = std::make_unique<ArcLengthTable>(*mv.curve);
      const double len = tables_[m]->length_mm();
      f = len > 0.0 ? std::clamp(tables_[m]->s_of_u(u) / len, 0.0, 1.0) : 0.0;
    }
    want = extra_between(mv.extra_start, mv.extra_end, f);
  }
  double worst = 0.0;
  for (int e = 0; e < extra_axis_count; ++e) {
    if (layout_.index_of(extra_axis_letters[e]) < 0) continue;
    const auto i = static_cast<std::size_t>(e);
    const double err = std::abs(x[i] - want[i]);
    if (err > worst) {
      worst = err;
      axis = extra_axis_letters[e];
    }
  }
  return worst;
}

void Checker::add(const Sample& s) {
  const std::size_t k = static_cast<std::size_t>(r_.samples++);
  if (!measuring_) return;
  const bool finite = std::isfinite(s.t_s) && s.position.allFinite() && s.position.size() == layout_.size();
  if (!finite) {
    r_.finite = false;
    measuring_ = false;
    return;
  }
  const double T = period_;
  if (k > 0 && std::abs((s.t_s - t_previous_) - T) > 1e-9 * T + 4e-16 * std::abs(s.t_s)) r_.uniform_time = false;
  t_previous_ = s.t_s;
  if (moves_.empty()) return;  // nothing to measure against (finish() says so)
  const Vec3 p = layout_.tool(s.position);
  if (k == 0) {
    const Curve& first = *moves_.front().curve;
    r_.start_error_mm = (p - first.point(first.u_min())).norm();
  }
  last_point_ = p;
  // Finite differences on each axis: velocity, acceleration and jerk ending at k.
  const AxisVector& p0 = s.position;
  const AxisVector &p1 = previous_[0], &p2 = previous_[1], &p3 = previous_[2];
  sm_.velocity.setZero();
  sm_.acceleration.setZero();
  sm_.jerk.setZero();
  if (k >= 1) sm_.velocity = (p0 - p1) / T;
  if (k >= 2) sm_.acceleration = (p0 - 2 * p1 + p2) / (T * T);
  if (k >= 3) sm_.jerk = (p0 - 3 * p1 + 3 * p2 - p3) / (T * T * T);
  sm_.velocity_ratio = sm_.acceleration_ratio = sm_.jerk_ratio = 0.0;
  for (Axis& ax : axes_) {
    const int i = ax.index;
    // one unit in the last place of the largest position of the difference [mm] or [deg]
    double x_max = std::abs(p0[i]);
    if (k >= 1) x_max = std::max(x_max, std::abs(p1[i]));
    if (k >= 2) x_max = std::max(x_max, std::abs(p2[i]));
    if (k >= 3) x_max = std::max(x_max, std::abs(p3[i]));
    const double ulp = std::nextafter(x_max, std::numeric_limits<double>::infinity()) - x_max;
    constexpr double rounding = tolerances::check_position_rounding_ulps;
    // a backward difference d [mm] over Tn = T^n against the limit: its ratio, and the ratio less
    // the `ulps` that rounding the positions alone can make of it (the sum of the difference's
    // weights times check_position_rounding_ulps)
    const auto measure = [&](double d, double Tn, double ulps, double limit, double& max_ratio, double& max_excess) {
      const double ratio = d / Tn / limit;
      max_ratio = std::max(max_ratio, ratio);
      max_excess = std::max(max_excess, std::max(0.0, d - ulps * ulp) / Tn / limit);
      return ratio;
    };
    if (k >= 1)
      sm_.velocity_ratio = std::max(sm_.velocity_ratio, measure(std::abs(p0[i] - p1[i]), T, 2.0 * rounding,
                                                                ax.limits->max_velocity, ax.max_v, ax.excess_v));
    if (k >= 2)
      sm_.acceleration_ratio = std::max(sm_.acceleration_ratio, measure(std::abs(p0[i] - 2 * p1[i] + p2[i]), T * T, 4.0 * rounding,
                                                                        ax.limits->max_acceleration, ax.max_a, ax.excess_a));
    if (k >= 3)
      sm_.jerk_ratio = std::max(sm_.jerk_ratio, measure(std::abs(p0[i] - 3 * p1[i] + 3 * p2[i] - p3[i]), T * T * T, 8.0 * rounding,
                                                        ax.limits->max_jerk, ax.max_j, ax.excess_j));
  }
  double u = 0.0, d = 0.0;
  const std::size_t m = match(s, p, u, d);
  const Curve& c = *moves_[m].curve;
  r_.max_path_error_mm = std::max(r_.max_path_error_mm, d);
  if (layout_.has_extra()) {
    char axis = ' ';
    const double e = extra_axis_error(s.position, m, u, axis);
    if (e > r_.max_extra_axis_error) {
      r_.max_extra_axis_error = e;
      r_.worst_extra_axis = axis;
    }
    last_extra_ = layout_.extra(s.position);
  }
  if (const auto& pl = moves_[m].lines) {
    // A smoothed line: the distance from the programmed lines around it (the nearest of the
    // tolerances::check_smoothing_lines lines on each side; the true distance is no larger).
    const auto own = static_cast<long>(pl->line);
    track_deviation(polyline_distance(*pl->vertices, p, own - tolerances::check_smoothing_lines,
                                      own + tolerances::check_smoothing_lines),
                    pl->tolerance_mm, r_.max_smoothing_deviation_mm, r_.max_smoothing_deviation_ratio,
                    r_.smoothing_tolerance_mm);
  }
  double chord = 0.0;
  if (k > 0 && m == m_prev_ && u > u_prev_) {
    // The bow of the path between the two setpoints from their chord. Where the move has a corner
    // in between (a cusp, a tangent jump at a breakpoint), the two sides are measured from their
    // own chords through it, as two moves would be.
    const auto bow = [&](double u0, double u1, const Vec3& a, const Vec3& b) {
      const Vec3 ab = b - a;
      const double len2 = ab.squaredNorm();
      double worst = 0.0;
      for (int q = 1; q < 8; ++q) {
        const Vec3 pq = c.point(u0 + (u1 - u0) * q / 8.0) - a;
        const double t = len2 > 0.0 ? std::clamp(pq.dot(ab) / len2, 0.0, 1.0) : 0.0;
        worst = std::max(worst, (pq - t * ab).norm());
      }
      return worst;
    };
    const std::vector<double>& corners = corners_of(m);
    double ua = u_prev_;
    Vec3 a = previous_point_;
    for (auto it = std::upper_bound(corners.begin(), corners.end(), u_prev_); it != corners.end() && *it < u; ++it) {
      const Vec3 corner = c.point(*it);
      chord = std::max(chord, bow(ua, *it, a, corner));
      ua = *it;
      a = corner;
    }
    chord = std::max(chord, bow(ua, u, a, p));
    r_.max_chord_error_mm = std::max(r_.max_chord_error_mm, chord);
  }
  if (r_.blocks.size() <= m) r_.blocks.resize(m + 1);
  BlockStats& b = r_.blocks[m];
  if (b.samples++ == 0) {
    b.first_sample = static_cast<long>(k);
    b.t_first_s = s.t_s;
    b.first_point = p;
  }
  b.last_sample = static_cast<long>(k);
  b.t_last_s = s.t_s;
  b.max_path_error_mm = std::max(b.max_path_error_mm, d);
  b.max_chord_error_mm = std::max(b.max_chord_error_mm, chord);
  b.max_velocity_ratio = std::max(b.max_velocity_ratio, sm_.velocity_ratio);
  b.max_acceleration_ratio = std::max(b.max_acceleration_ratio, sm_.acceleration_ratio);
  b.max_jerk_ratio = std::max(b.max_jerk_ratio, sm_.jerk_ratio);
  if (observer_) {
    sm_.index = k;
    sm_.t_s = s.t_s;
    sm_.position = p0;
    sm_.path_error_mm = d;
    sm_.chord_error_mm = chord;
    sm_.move = m;
    observer_(sm_);
  }
  previous_[2] = previous_[1];
  previous_[1] = previous_[0];
  previous_[0] = p0;
  previous_point_ = p;
  u_prev_ = u;
  m_prev_ = m;
  m_ = m;
}

Report Checker::finish() {
  Report r = std::move(r_);
  r_ = Report{};
  if (!r.finite || r.samples == 0 || moves_.empty()) {
    Report bare;
    bare.samples = r.samples;
    bare.finite = r.finite;
    return bare;
  }
  r.blocks.resize(moves_.size());
  for (std::size_t i = 0; i < moves_.size(); ++i) r.blocks[i].source_line = moves_[i].source_line;
  const Curve& last = *moves_.back().curve;
  r.end_error_mm = (last_point_ - last.point(last.u_max())).norm();
  // Every block end: where each move ends, the next one starts (else the setpoints jump there).
  for (std::size_t i = 0; i + 1 < moves_.size(); ++i) {
    const Curve& a = *moves_[i].curve;
    const Curve& b = *moves_[i + 1].curve;
    const double gap = (b.point(b.u_min()) - a.point(a.u_max())).norm();
    if (gap > r.end_error_mm) {
      r.end_error_mm = gap;
      r.end_error_line = moves_[i].source_line;
    }
  }
  if (layout_.has_extra() && r.worst_extra_axis == ' ')  // measured, and exact: name the first
    for (int e = extra_axis_count - 1; e >= 0; --e)
      if (layout_.index_of(extra_axis_letters[e]) >= 0) r.worst_extra_axis = extra_axis_letters[e];
  for (int e = 0; e < extra_axis_count; ++e)  // the extra axes end where the last move puts them
    if (layout_.index_of(extra_axis_letters[e]) >= 0)
      r.end_error_mm = std::max(r.end_error_mm, std::abs(last_extra_[static_cast<std::size_t>(e)] -
                                                         moves_.back().extra_end[static_cast<std::size_t>(e)]));
  // Corner blends: each within the tolerance of the programmed lines it replaces.
  for (const program::Move& pm : moves_) {
    if (pm.lines) ++r.smoothed_lines;
    if (!pm.corner) continue;
    ++r.blends;
    track_deviation(blend_deviation(*pm.curve, *pm.corner), pm.corner->tolerance_mm, r.max_blend_deviation_mm,
                    r.max_blend_deviation_ratio, r.blend_tolerance_mm);
  }
  // The worst axis: the first in the machine's order with the largest ratio.
  for (const Axis& ax : axes_) {
    r.max_velocity_excess = std::max(r.max_velocity_excess, ax.excess_v);
    r.max_acceleration_excess = std::max(r.max_acceleration_excess, ax.excess_a);
    r.max_jerk_excess = std::max(r.max_jerk_excess, ax.excess_j);
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

Report check(const std::vector<Sample>& samples, const std::vector<program::Move>& moves, const Machine& machine,
             const Observer& observer) {
  Checker c(moves, machine, AxisLayout::xyz(), observer);
  for (const Sample& s : samples) c.add(s);
  return c.finish();
}

}  // namespace kontur::verify
