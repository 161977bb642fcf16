// The constraints of a path on a machine (constraints.hpp): shared by the online planner and the
// time-optimal reference.
#include <kontur/geometry/differential.hpp>
#include <kontur/geometry/golden_section.hpp>
#include <kontur/geometry/helix_arc.hpp>
#include <kontur/geometry/line_segment.hpp>
#include <kontur/interpolate/curve_interpolator.hpp>
#include <kontur/plan/constraints.hpp>

#include <algorithm>
#include <optional>
#include <cmath>
#include <cstddef>
#include <limits>
#include <vector>

namespace kontur::plan {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

}  // namespace

LinearAxes linear_axes(const Machine& machine) noexcept {
  LinearAxes axes{};
  for (const AxisLimits& a : machine.axes) {
    const int i = linear_axis_index(a.name);
    if (i >= 0) axes[static_cast<std::size_t>(i)] = &a;
  }
  return axes;
}

int missing_axis_moved(const Vec3& tangent, const LinearAxes& axes) noexcept {
  for (std::size_t i = 0; i < 3; ++i)
    if (axes[i] == nullptr && std::abs(tangent[static_cast<Eigen::Index>(i)]) > tolerances::missing_axis_tangent)
      return static_cast<int>(i);
  return -1;
}

double velocity_cap(const Vec3& tangent, double feed_mm_s, const Machine& machine, const LinearAxes& axes) noexcept {
  if (missing_axis_moved(tangent, axes) >= 0) return 0.0;  // an axis the machine does not have cannot move
  double v = std::min(feed_mm_s, machine.max_feed_mm_s);
  for (std::size_t i = 0; i < 3; ++i) {
    const double t = std::abs(tangent[static_cast<Eigen::Index>(i)]);
    if (axes[i] != nullptr && t > 0.0) v = std::min(v, axes[i]->max_velocity / t);
  }
  return v;
}

double chord_cap(double kappa, const Machine& machine) noexcept {
  if (!(kappa > 0.0)) return kInf;
  return chord_limited_feed(1.0 / kappa, machine.chord_tolerance_mm, machine.servo_period_s);
}

std::pair<Vec3, Vec3> tangent_and_curvature(const Derivatives& d) noexcept {
  const double v2 = d[1].squaredNorm();
  if (!(v2 > 0.0)) return {Vec3::Zero(), Vec3::Zero()};
  const Vec3 t = d[1] / std::sqrt(v2);
  return {t, (d[2] - d[2].dot(t) * t) / v2};
}

int acceleration_rows(const Vec3& t, const Vec3& k, const LinearAxes& axes, std::array<AccelerationRow, 3>& rows) noexcept {
  int n = 0;
  for (std::size_t i = 0; i < 3; ++i) {
    if (axes[i] == nullptr) continue;
    const auto e = static_cast<Eigen::Index>(i);
    AccelerationRow r{std::abs(t[e]) > tolerances::time_optimal_tangent_zero ? t[e] : 0.0, k[e], axes[i]->max_acceleration};
    if (r.t < 0.0) {
      r.t = -r.t;
      r.k = -r.k;
    }
    rows[static_cast<std::size_t>(n++)] = r;
  }
  return n;
}

double corner_acceleration_cap(const Vec3& dt, const Machine& machine, const LinearAxes& axes,
                               double acceleration_share, double ignore_below) noexcept {
  double v = kInf;
  for (std::size_t i = 0; i < 3; ++i) {
    const double jump = std::abs(dt[static_cast<Eigen::Index>(i)]);
    if (axes[i] != nullptr && jump > ignore_below)
      v = std::min(v, acceleration_share * axes[i]->max_acceleration * machine.servo_period_s / jump);
  }
  return v;
}

std::size_t PathGeometry::axis_pairs_into(int i, std::span<std::array<double, 2>> out) const noexcept {
  const AxisPairs& p = pairs[static_cast<std::size_t>(i)];
  std::size_t n = 0;
  for (int j = 0; j < p.n; ++j) out[n++] = {p.t[static_cast<std::size_t>(j)], p.k[static_cast<std::size_t>(j)]};
  if (n == 0 && (tangent[i] > 0.0 || curvature[i] > 0.0)) out[n++] = {tangent[i], curvature[i]};
  return n;
}

std::vector<std::array<double, 2>> PathGeometry::axis_pairs(int i) const {
  std::array<std::array<double, 2>, tolerances::plan_acceleration_pairs> out;
  return {out.begin(), out.begin() + static_cast<std::ptrdiff_t>(axis_pairs_into(i, out))};
}

void PathGeometry::set_pairs(int i, std::vector<std::array<double, 2>> points) {
  set_pairs_in_place(i, std::span<std::array<double, 2>>(points));
}

void PathGeometry::set_pairs_in_place(int i, std::span<std::array<double, 2>> points) {
  // The front of pairs no other dominates, by |t| rising (so |K| falling).
  std::sort(points.begin(), points.end(), [](const auto& a, const auto& b) { return a[0] > b[0] || (a[0] == b[0] && a[1] > b[1]); });
  // by |t| falling, |K| rising: kept in place (a subsequence of the sorted points)
  std::size_t kept = 0;
  for (std::size_t r = 0; r < points.size(); ++r)
    if (kept == 0 || points[r][1] > points[kept - 1][1]) points[kept++] = points[r];
  std::span<std::array<double, 2>> front = points.first(kept);
  // Too many: merge the neighbours whose componentwise maximum adds the least area.
  while (front.size() > static_cast<std::size_t>(tolerances::plan_acceleration_pairs)) {
    std::size_t best = 0;
    double best_area = std::numeric_limits<double>::infinity();
    for (std::size_t j = 0; j + 1 < front.size(); ++j) {
      const double area = (front[j][0] - front[j + 1][0]) * (front[j + 1][1] - front[j][1]);
      if (area < best_area) {
        best_area = area;
        best = j;
      }
    }
    front[best] = {front[best][0], front[best + 1][1]};
    std::copy(front.begin() + static_cast<std::ptrdiff_t>(best) + 2, front.end(),
              front.begin() + static_cast<std::ptrdiff_t>(best) + 1);
    front = front.first(front.size() - 1);
  }
  AxisPairs& p = pairs[static_cast<std::size_t>(i)];
  p.n = static_cast<int>(front.size());
  for (std::size_t j = 0; j < front.size(); ++j) {
    p.t[j] = front[j][0];
    p.k[j] = front[j][1];
  }
}

void PathGeometry::drop_curvature() noexcept {
  curvature = curvature_rate = curvature_low = curvature_rate_low = Vec3::Zero();
  max_kappa = kappa_low = 0.0;
  for (AxisPairs& p : pairs) p.n = 0;  // the maxima: max |t_i| with no curvature
}

void PathGeometry::merge(const PathGeometry& o) {
  std::array<std::array<double, 2>, 2 * tolerances::plan_acceleration_pairs> both;
  for (int i = 0; i < 3; ++i) {
    const std::size_t n = axis_pairs_into(i, both);
    const std::size_t m = o.axis_pairs_into(i, std::span(both).subspan(n));
    set_pairs_in_place(i, std::span(both).first(n + m));
  }
  tangent = tangent.cwiseMax(o.tangent);
  curvature = curvature.cwiseMax(o.curvature);
  curvature_rate = curvature_rate.cwiseMax(o.curvature_rate);
  max_kappa = std::max(max_kappa, o.max_kappa);
  curvature_low = curvature_low.cwiseMin(o.curvature_low);
  curvature_rate_low = curvature_rate_low.cwiseMin(o.curvature_rate_low);
  kappa_low = std::min(kappa_low, o.kappa_low);
  for (std::size_t e = 0; e < extra_rate.size(); ++e) extra_rate[e] = std::max(extra_rate[e], o.extra_rate[e]);
}

std::pair<Vec3, Vec3> curvature_vector_and_rate(const Derivatives& d) noexcept {
  // With r1 = C', r2 = C'', r3 = C''', q = |r1|^2 and p = r1.r2: K = r2/q - p r1/q^2 = dt/ds, and
  // dK/ds = (dK/du) / |r1| with dK/du = r3/q - 2 p r2/q^2 - ((r3.r1 + r2.r2) r1 + p r2)/q^2
  // + 4 p^2 r1/q^3.
  const Vec3 &r1 = d[1], &r2 = d[2], &r3 = d[3];
  const double q = r1.squaredNorm();
  if (!(q > 0.0)) return {Vec3::Zero(), Vec3::Zero()};
  const double p = r1.dot(r2);
  const Vec3 k = curvature_vector(d);
  const Vec3 dk_du = r3 / q - 2.0 * p * r2 / (q * q) - ((r3.dot(r1) + r2.squaredNorm()) * r1 + p * r2) / (q * q) +
                     4.0 * p * p * r1 / (q * q * q);
  return {k, dk_du / std::sqrt(q)};
}

namespace {

// unit tangent, curvature vector and its rate at a regular point of a curve
struct LocalGeometry {
  Vec3 tangent, curvature, rate;
};

// path_geometry's sample buffers, kept between calls (it runs for every piece of every move: their
// allocations were a tenth of a run of dense lines)
struct GeometryScratch {
  std::vector<Derivatives> ds;
  std::vector<double> us, kappa, rate, turn;
  std::vector<LocalGeometry> locals, peaks;
  std::vector<std::array<double, 2>> pairs;
};

}  // namespace

PathGeometry path_geometry(const Curve& c, double u0, double u1, int samples, double speed_floor) {
  samples = std::max(samples, 1);
  if (dynamic_cast<const LineSegment*>(&c) != nullptr) {
    // A line: every sample is the same (its derivatives are constants), so is every bound, each
    // pair and the lows; what the sampling below finds at once (a tenth of a run of dense lines).
    const Derivatives d = c.derivatives(u0, 3);
    const Vec3 t = unit_tangent(d);
    if (d[1].norm() > speed_floor && !t.isZero()) {
      const auto [kv, kr] = curvature_vector_and_rate(d);
      PathGeometry g;
      g.tangent = t.cwiseAbs().cwiseMin(Vec3::Ones());
      g.curvature = g.curvature_low = kv.cwiseAbs();
      g.curvature_rate = g.curvature_rate_low = kr.cwiseAbs();
      g.max_kappa = g.kappa_low = kv.norm();
      for (int i = 0; i < 3; ++i) {
        std::array<std::array<double, 2>, 1> one{{{std::min(1.0, std::abs(t[i])), std::abs(kv[i])}}};
        g.set_pairs_in_place(i, one);
      }
      return g;
    }
  }
  // Sample until the tangent turns by at most 0.2 rad between samples (a helix of many turns is
  // one span); then a component's peak lies at most about 1 % of its range above the samples.
  // On an arc also its angle (a steep helix turns its tangent less than its angle).
  const ArcSpan arc = arc_span(c);
  thread_local GeometryScratch scratch;
  // (an end point's rounding leaves a change of radius of a few ulps: 8.9e-16 mm on an arc of
  // 2.54 mm in arc-terminal; up to arc_radius_change_exact of the radius it counts as a
  // circle whose magnitudes vary by that share, which the bounds add twice)
  const double radius_change = arc.arc != nullptr ? std::abs(arc.arc->radius_change_mm()) / arc.arc->radius_mm() : 0.0;
  const bool circular = arc.arc != nullptr && radius_change <= tolerances::arc_radius_change_exact;
  for (;;) {
    PathGeometry hi, lo;
    lo.tangent = lo.curvature = lo.curvature_rate = Vec3::Constant(kInf);
    lo.max_kappa = kInf;
    double max_turn = 0.0;
    Vec3 t_before = Vec3::Zero();
    // The span's own polynomial at its right end (the next span may differ there).
    const auto n = static_cast<std::size_t>(samples) + 1;
    std::vector<Derivatives>& ds = scratch.ds;
    std::vector<double>& us = scratch.us;
    ds.resize(n);
    us.resize(n);
    for (std::size_t k = 0; k < n; ++k) {
      us[k] = k + 1 == n ? u1 : u0 + (u1 - u0) * static_cast<double>(k) / samples;
      ds[k] = k + 1 == n ? c.derivatives_left(us[k], 3) : c.derivatives(us[k], 3);
    }
    // At a stationary point (C' = 0 up to rounding: at most speed_floor) the tangent and curvature
    // are noise; the path stops there (split_move), and the samples beside it bound the stretch.
    // (Not relative to this stretch's own samples: a large weight makes |C'| a millionth of its
    // peak on a regular, tightly turning part of the same span.)
    const auto regular = [&](const Derivatives& d) {
      return d[1].norm() > speed_floor && !unit_tangent(d).isZero();
    };
    // unit tangent, curvature vector and its rate at a regular point, widening a bound
    using Local = LocalGeometry;
    const auto local = [](const Derivatives& d) {
      const auto [kv, kr] = curvature_vector_and_rate(d);
      return Local{unit_tangent(d), kv, kr};
    };
    std::vector<Local>& peaks = scratch.peaks;  // refined peaks of |K| or |dK/ds| between samples
    peaks.clear();
    const auto add = [](const Local& l, PathGeometry& g, bool smallest) {
      const Vec3 at = l.tangent.cwiseAbs(), ak = l.curvature.cwiseAbs(), ar = l.rate.cwiseAbs();
      if (smallest) {
        g.tangent = g.tangent.cwiseMin(at);
        g.curvature = g.curvature.cwiseMin(ak);
        g.curvature_rate = g.curvature_rate.cwiseMin(ar);
        g.max_kappa = std::min(g.max_kappa, l.curvature.norm());
      } else {
        g.tangent = g.tangent.cwiseMax(at);
        g.curvature = g.curvature.cwiseMax(ak);
        g.curvature_rate = g.curvature_rate.cwiseMax(ar);
        g.max_kappa = std::max(g.max_kappa, l.curvature.norm());
      }
    };
    // |K| and |dK/ds| of each regular sample (-1: not regular)
    std::vector<double>& kappa = scratch.kappa;
    std::vector<double>& rate = scratch.rate;
    kappa.assign(n, -1.0);
    rate.assign(n, -1.0);
    std::vector<Local>& locals = scratch.locals;  // of the regular samples
    locals.resize(n);
    for (std::size_t k = 0; k < n; ++k) {
      if (!regular(ds[k])) continue;
      const Local l = local(ds[k]);
      locals[k] = l;
      if (!t_before.isZero()) max_turn = std::max(max_turn, (l.tangent - t_before).norm());
      t_before = l.tangent;
      add(l, hi, false);
      add(l, lo, true);
      kappa[k] = l.curvature.norm();
      rate[k] = l.rate.norm();
    }
    const double step_angle = circular ? std::abs(arc.arc->sweep_rad()) * (u1 - u0) / samples : 0.0;  // [rad]
    if ((max_turn > 0.2 || step_angle > 0.2) && samples < 4096) {
      samples *= 4;
      continue;
    }
    if (!std::isfinite(lo.max_kappa)) {
      // No regular point: the stretch lies where |C'| is rounding-sized against the span's peak
      // (beside a stationary point), yet the tool may still move along it (a repeated control
      // point with weights 100 and 0.43 left 1.8e-9 mm there; with a zero tangent bound the stop
      // ran at the jerk of the wrong axis, 5.5 times Y's). Every axis whose coordinate changes
      // over the samples may carry the whole tangent; the curvature is noise, as at the stop.
      Vec3 low = ds[0][0], high = ds[0][0];
      for (const Derivatives& d : ds) {
        low = low.cwiseMin(d[0]);
        high = high.cwiseMax(d[0]);
      }
      for (int i = 0; i < 3; ++i) hi.tangent[i] = high[i] > low[i] ? 1.0 : 0.0;
      return hi;
    }
    // A narrow peak of |K| or |dK/ds| between samples (a large weight bends a small part of a
    // span): each sample that is a local maximum standing out of a neighbour by more than
    // tolerances::plan_peak_refine_ratio is refined by Brent's method between its neighbours
    // (not the rounding noise of a straight stretch: tolerances::plan_peak_refine_floor).
    for (std::vector<double>* f : {&kappa, &rate}) {
      const std::vector<double>& v = *f;
      for (std::size_t k = 0; k < n; ++k) {
        if (v[k] < 0.0) continue;
        const double left = k > 0 ? v[k - 1] : -1.0, right = k + 1 < n ? v[k + 1] : -1.0;
        if (v[k] < left || v[k] < right) continue;
        const double low = std::min(left < 0.0 ? kInf : left, right < 0.0 ? kInf : right);
        if (!(v[k] > tolerances::plan_peak_refine_ratio * low) || !(v[k] > tolerances::plan_peak_refine_floor)) continue;
        const bool of_rate = f == &rate;
        // (the maximum of the value: the minimum of its negative; -1 at a point that is not regular)
        const auto negative_value = [&](double u) {
          const Derivatives d = c.derivatives(u, 3);
          if (!regular(d)) return 1.0;
          const Local l = local(d);
          return -(of_rate ? l.rate.norm() : l.curvature.norm());
        };
        const double ua = us[k > 0 ? k - 1 : k], ub = us[k + 1 < n ? k + 1 : k];
        const auto [u_peak, f_peak] = brent_minimum(negative_value, ua, ub, tolerances::plan_peak_refine_u * (ub - ua),
                                                    tolerances::plan_peak_refine_evaluations);
        if (f_peak <= 0.0) {
          const Local l = local(c.derivatives(u_peak, 3));
          add(l, hi, false);
          peaks.push_back(l);
        }
      }
    }
    // Constant quantities (a line's tangent, a circle's curvature) are exact; the others are
    // raised by a share of their range between the samples. On a circle or a helix (an arc
    // without change of radius) every component of the tangent, the curvature vector and its rate
    // is a constant plus a sinusoid of the angle, of amplitude at most the quantity's magnitude:
    // between samples d phi apart it rises above the larger of them by at most that magnitude
    // times 1 - cos(d phi / 2), which replaces the margin (5 % of a full circle's range of K_i
    // cost 2.5 % of its speed; this bound is 0.5 % of K at most, d phi <= 0.2 rad).
    const double m = circular ? 0.0 : tolerances::plan_sample_margin;
    const double arc_rise = 1.0 - std::cos(0.5 * step_angle) + (circular ? 2.0 * radius_change : 0.0);
    // (the sinusoids lie in the arc's plane: on axis i their amplitude is at most sqrt(e1_i^2 + e2_i^2)
    // of the quantity's magnitude, 0 along the normal of a plane of two axes)
    const Vec3 amplitude =
        circular ? Vec3((arc.arc->frame().e1.cwiseAbs2() + arc.arc->frame().e2.cwiseAbs2()).cwiseSqrt()) : Vec3::Zero();
    const Vec3 arc_raise = arc_rise * amplitude;
    double rate_norm = 0.0;  // the largest sampled |dK/ds| [1/mm^2]
    for (const double r : rate) rate_norm = std::max(rate_norm, r);
    const Vec3 hi_t_raw = hi.tangent, hi_k_raw = hi.curvature;
    // A component also peaks between samples above both, by up to 1 - cos(phi / 2) <= phi^2 / 8 of
    // its amplitude (phi the largest turn between samples), where its range over the samples is
    // small: seed 21228, a degree-2 NURBS with weight 0.071, ran X at 1.00026 times its velocity.
    const double between = max_turn * max_turn / 8.0;
    hi.tangent = (hi.tangent + m * (hi.tangent - lo.tangent) + between * hi.tangent + arc_raise)
                     .cwiseMin(Vec3::Ones());
    hi.curvature += m * (hi.curvature - lo.curvature) + hi.max_kappa * arc_raise;
    hi.curvature_rate += m * (hi.curvature_rate - lo.curvature_rate) + rate_norm * arc_raise;
    hi.max_kappa += m * (hi.max_kappa - lo.max_kappa);
    hi.curvature_low = lo.curvature;
    hi.curvature_rate_low = lo.curvature_rate;
    hi.kappa_low = lo.max_kappa;
    // The pairs (PathGeometry::pairs): one per interval between regular samples, bounding both
    // ends; a tangent component rises between them by at most 1 - cos(phi / 2) <= phi^2 / 8 above
    // the chord of its values (phi the turn between the samples, at most about 0.2 rad here),
    // and by the margin of its own change; a curvature component, turning with the normal, by
    // |K| phi^2 / 8 and the margin of its change (a narrow peak of |K| is refined above). A sample
    // with no regular neighbour and each refined peak: a pair of its own, raised by the margins of
    // the ranges.
    // (the turn phi between regular neighbours k and k + 1, the same for every axis)
    std::vector<double>& turn = scratch.turn;
    turn.assign(n, 0.0);
    for (std::size_t k = 0; k + 1 < n; ++k)
      if (kappa[k] >= 0.0 && kappa[k + 1] >= 0.0)
        turn[k] = 2.0 * std::asin(std::min(1.0, 0.5 * (locals[k].tangent - locals[k + 1].tangent).norm()));
    for (int i = 0; i < 3; ++i) {
      const double raise_t = m * (hi_t_raw[i] - lo.tangent[i]) + arc_raise[i],
                   raise_k = m * (hi_k_raw[i] - lo.curvature[i]) + hi.max_kappa * arc_raise[i];
      std::vector<std::array<double, 2>>& pairs = scratch.pairs;
      pairs.clear();
      const auto alone = [&](const Local& l) {
        pairs.push_back({std::min(1.0, std::abs(l.tangent[i]) + raise_t), std::abs(l.curvature[i]) + raise_k});
      };
      for (std::size_t k = 0; k < n; ++k) {
        if (kappa[k] < 0.0) continue;
        const bool left = k > 0 && kappa[k - 1] >= 0.0, right = k + 1 < n && kappa[k + 1] >= 0.0;
        if (!left && !right) alone(locals[k]);
        if (!right) continue;
        const Local &a = locals[k], &b = locals[k + 1];
        const double phi = turn[k];
        const double ta = std::abs(a.tangent[i]), tb = std::abs(b.tangent[i]);
        const double ka = std::abs(a.curvature[i]), kb = std::abs(b.curvature[i]);
        const double kappa_ab = std::max(kappa[k], kappa[k + 1]);
        pairs.push_back({std::min(1.0, std::max(ta, tb) + phi * phi / 8.0 + m * std::abs(ta - tb) + arc_raise[i]),
                         std::max(ka, kb) + kappa_ab * (phi * phi / 8.0 + arc_raise[i]) + m * std::abs(ka - kb)});
      }
      for (const Local& l : peaks) alone(l);
      hi.set_pairs_in_place(i, pairs);
    }
    return hi;
  }
}

double speed_cap(const PathGeometry& g, double feed_mm_s, const Machine& machine, double centripetal_share,
                 double curvature_rate_share) noexcept {
  const LinearAxes axes = linear_axes(machine);
  // A move of extra axes alone (the tool point stands) runs at its feed [deg/s] or [mm/s] within the
  // axes' own velocities: the machine's max feed is a tool path speed.
  const bool tool_still = g.tangent.isZero();
  double v = tool_still ? feed_mm_s : velocity_cap(g.tangent, feed_mm_s, machine, axes);
  for (const AxisLimits& axis : machine.axes)  // the extra axes, linear in the distance
    if (const int e = extra_axis_index(axis.name); e >= 0 && g.extra_rate[static_cast<std::size_t>(e)] > 0.0)
      v = std::min(v, axis.max_velocity / g.extra_rate[static_cast<std::size_t>(e)]);
  for (std::size_t i = 0; i < 3; ++i) {
    const AxisLimits* axis = axes[i];
    if (axis == nullptr) continue;  // not moved (else velocity_cap is zero): it bounds nothing
    const auto e = static_cast<Eigen::Index>(i);
    if (g.curvature[e] > 0.0) v = std::min(v, std::sqrt(centripetal_share * axis->max_acceleration / g.curvature[e]));
    if (g.curvature_rate[e] > 0.0)
      v = std::min(v, std::cbrt(curvature_rate_share * axis->max_jerk / g.curvature_rate[e]));
  }
  return std::min(v, chord_cap(g.max_kappa, machine));
}

namespace {

// The path acceleration [mm/s^2] that keeps every linear axis within its limits at speeds up to
// v (infinity where none bounds it): |t_i| a + |K_i| v^2 <= A_i at each of the stretch's pairs
// (PathGeometry::pairs), and the cross term 3 K_i v a <= plan_cross_jerk_share J_i.
double linear_path_acceleration_at(const PathGeometry& g, double v, const Machine& machine) noexcept {
  double acceleration = kInf;
  for (const AxisLimits& axis : machine.axes) {
    const int i = linear_axis_index(axis.name);
    if (i < 0 || !(g.tangent[i] > 0.0)) continue;
    const double k = g.curvature[i];
    double a = kInf;
    const PathGeometry::AxisPairs& p = g.pairs[static_cast<std::size_t>(i)];
    if (p.n == 0) a = (axis.max_acceleration - k * v * v) / g.tangent[i];
    for (std::size_t q = 0; q < static_cast<std::size_t>(p.n); ++q)
      if (p.t[q] > 0.0) a = std::min(a, (axis.max_acceleration - p.k[q] * v * v) / p.t[q]);
    if (k > 0.0 && v > 0.0) a = std::min(a, tolerances::plan_cross_jerk_share * axis.max_jerk / (3.0 * k * v));
    acceleration = std::min(acceleration, a);
  }
  return acceleration;
}

// The path acceleration [mm/s^2] the extra axes allow at any speed (they move linearly with the
// distance: their acceleration is r_e times the path's; infinity where none moves).
double extra_axes_path_acceleration(const PathGeometry& g, const Machine& machine) noexcept {
  double acceleration = kInf;
  for (const AxisLimits& axis : machine.axes) {
    const int e = extra_axis_index(axis.name);
    if (e < 0) continue;
    const double r = g.extra_rate[static_cast<std::size_t>(e)];
    if (r > 0.0) acceleration = std::min(acceleration, axis.max_acceleration / r);
  }
  return acceleration;
}

// The path jerk [mm/s^3] left at speeds up to v when the cross term 3 K_i v a is at most
// `cross[i]` [mm/s^3] (infinity where no axis bounds it): |t_i| j + cross_i + K'_i v^3 <=
// (1 - junction share) J_i, and the extra axes' jerk r_e times the path's.
double path_jerk_at(const PathGeometry& g, double v, const Vec3& cross, const Machine& machine,
                    double junction_share) noexcept {
  double jerk = kInf;
  for (const AxisLimits& axis : machine.axes) {
    const int i = linear_axis_index(axis.name);
    if (i < 0 || !(g.tangent[i] > 0.0)) continue;
    const double j = (1.0 - junction_share) * axis.max_jerk - cross[i] - g.curvature_rate[i] * v * v * v;
    jerk = std::min(jerk, j / g.tangent[i]);
  }
  for (const AxisLimits& axis : machine.axes) {
    const int e = extra_axis_index(axis.name);
    if (e < 0) continue;
    const double r = g.extra_rate[static_cast<std::size_t>(e)];
    if (r > 0.0) jerk = std::min(jerk, (1.0 - junction_share) * axis.max_jerk / r);
  }
  return jerk;
}

// The speed [mm/s] at which the centripetal part at each pair the acceleration is bounded at
// (linear_path_acceleration_at) reaches its axis's limit (infinity where no pair bounds it); at
// sqrt((1 + c) / 2) of it, the middle of the centripetal share c and 1, each pair leaves the path
// at least half the acceleration the share means to. speed_cap bounds only the sampled maximum by
// the share; a pair's curvature is raised for what may lie between the samples, and on an axis far
// slower than the others (XY_slowZ.ini: Z has 1/300 of X's acceleration) that raise alone exceeded
// the axis's limit at the cap the maximum allows: no acceleration was left at the cap, and the
// first axis's was taken instead (helix_slowdown ran X at 1.10 times its limit).
double pair_centripetal_speed(const PathGeometry& g, const Machine& machine) noexcept {
  double v = kInf;
  for (const AxisLimits& axis : machine.axes) {
    const int i = linear_axis_index(axis.name);
    if (i < 0 || !(g.tangent[i] > 0.0)) continue;
    const PathGeometry::AxisPairs& p = g.pairs[static_cast<std::size_t>(i)];
    double k = 0.0;
    for (std::size_t q = 0; q < static_cast<std::size_t>(p.n); ++q) k = std::max(k, p.k[q]);
    if (k > 0.0) v = std::min(v, std::sqrt(axis.max_acceleration / k));
  }
  return v;
}

// Path acceleration and jerk at speeds up to v (see path_limits).
PathLimits limits_at_cap(const PathGeometry& g, double v, const Machine& machine, double junction_share) noexcept {
  PathLimits l;
  l.max_velocity = v;
  // (the cross term as the linear axes bound the acceleration; the extra axes may lower it further)
  const double linear = linear_path_acceleration_at(g, v, machine);
  Vec3 cross;
  for (int i = 0; i < 3; ++i) cross[i] = 3.0 * g.curvature[i] * v * linear;
  l.max_jerk = path_jerk_at(g, v, cross, machine, junction_share);
  l.max_acceleration = std::min(linear, extra_axes_path_acceleration(g, machine));
  return l;
}

// A stretch along no axis the machine limits (or of speed 0): the first axis's acceleration and
// jerk. (An axis does not bound the acceleration to zero or below at the cap:
// pair_centripetal_speed leaves every pair some.)
PathLimits with_first_axis_fallback(PathLimits l, const Machine& machine) noexcept {
  if (!std::isfinite(l.max_acceleration) || !(l.max_acceleration > 0.0))
    l.max_acceleration = machine.axes.front().max_acceleration;
  if (!std::isfinite(l.max_jerk) || !(l.max_jerk > 0.0)) l.max_jerk = machine.axes.front().max_jerk;
  return l;
}

}  // namespace

PathLimits path_limits(const PathGeometry& g, double length_mm, double feed_mm_s, const Machine& machine,
                       const ShareChoice& choice) noexcept {
  const double junction_jerk_share = choice.junction_jerk_share, change_weight = choice.change_weight,
               change_from_mm_s = choice.change_from_mm_s;
  const bool alone = choice.alone, at_a_low = choice.at_a_low;
  const bool curved = !g.curvature.isZero();
  const double pair_speed = pair_centripetal_speed(g, machine);  // [mm/s]
  // The shares the stretch may take (each list rises: those allowed are a prefix of it): on a line
  // only the first; above the chain's largest only where the changes at the ends are weighed or at
  // a low; and the path's own jerk keeps at least plan_path_jerk_share_min of every axis's.
  const bool largest = change_weight > 0.0 || at_a_low;
  const auto centripetal_allowed = [&](double share) {
    return share == tolerances::plan_centripetal_shares[0] ||
           (curved && (share <= tolerances::plan_chain_centripetal_share_max || largest));
  };
  const auto rate_allowed = [&](double rate_share) {
    return rate_share == tolerances::plan_curvature_rate_jerk_shares[0] ||
           (curved &&
            rate_share <= 1.0 - junction_jerk_share - tolerances::plan_cross_jerk_share -
                              tolerances::plan_path_jerk_share_min &&
            (rate_share <= tolerances::plan_chain_curvature_rate_share_max || largest));
  };
  // (the cap at a pair of shares [mm/s]: the pairs' bound is sqrt((1 + c) / 2) of their speed)
  const auto cap_at = [&](double share, double rate_share) {
    return std::min(speed_cap(g, feed_mm_s, machine, share, rate_share), std::sqrt(0.5 * (1.0 + share)) * pair_speed);
  };
  if (!(change_weight > 0.0)) {
    // The length alone decides (no change weighed: inside a chain): the largest cap, which the
    // largest shares allowed give, as the cap grows with each share (a search of the 16 pairs was
    // a tenth of a run of dense lines, whose pieces are all inside chains).
    double share = tolerances::plan_centripetal_shares[0], rate_share = tolerances::plan_curvature_rate_jerk_shares[0];
    for (const double c : tolerances::plan_centripetal_shares) {
      if (!centripetal_allowed(c)) break;
      share = c;
    }
    for (const double r : tolerances::plan_curvature_rate_jerk_shares) {
      if (!rate_allowed(r)) break;
      rate_share = r;
    }
    return path_limits_at(g, cap_at(share, rate_share), machine, junction_jerk_share);
  }
  double best_v = 0.0, best_time = kInf;  // [mm/s], [s]
  std::optional<PathLimits> best;        // its limits (none where every cap is zero)
  for (const double share : tolerances::plan_centripetal_shares) {
    if (!centripetal_allowed(share)) break;
    for (const double rate_share : tolerances::plan_curvature_rate_jerk_shares) {
      if (!rate_allowed(rate_share)) break;
      const double v = cap_at(share, rate_share);
      // Time estimate: the length at the cap, plus 2 change_weight times the time a change
      // between the junctions' speed and the cap loses against running its distance at the cap
      // (jerk-limited: half its duration from rest, (v - from) / 2v of it from `from`; by speed
      // bands, as the look-ahead and the chain profile speed a curved piece up below its cap,
      // where the piece runs alone in its chain or at the smallest curvature-change share:
      // plan/banded_profile.hpp, where the last band's small acceleration near a high cap costs
      // far less than its duration. At a larger curvature-change share the cap rises at the cost
      // of jerk, and the braking into the next piece across a smooth junction, which is not
      // weighed, costs more than the bands' estimate saves: by the bands there too, arc-terminal
      // ran 1.7 % slower on the default machine. Each change has the piece's length, half of it
      // where both ends are weighed.)
      double time = v > 0.0 ? length_mm / v : kInf;
      std::optional<PathLimits> l;
      if (v > 0.0) {
        l = limits_at_cap(g, v, machine, junction_jerk_share);
        const double from = std::clamp(change_from_mm_s, 0.0, v);  // [mm/s]
        double lost = std::isfinite(l->max_acceleration) && l->max_acceleration > 0.0
                          ? velocity_change_time(from, v, l->max_acceleration, l->max_jerk) * (v - from) / (2.0 * v)
                          : 0.0;  // [s]
        if (curved && lost > 0.0 && (alone || rate_share == tolerances::plan_curvature_rate_jerk_shares[0]))
          if (const AccelerationBands b = acceleration_bands(g, *l, machine, junction_jerk_share); b.n > 0)
            lost = std::min(lost, banded_change_time_lost(from, v, b, length_mm / std::max(1.0, 2.0 * change_weight)));
        time += 2.0 * change_weight * lost;
      }
      if (time < best_time || best_time == kInf) {
        best_time = time;
        best_v = v;
        best = l;
      }
    }
  }
  return best ? with_first_axis_fallback(*best, machine) : path_limits_at(g, best_v, machine, junction_jerk_share);
}

PathLimits path_limits_at(const PathGeometry& g, double cap_mm_s, const Machine& machine,
                          double junction_jerk_share) noexcept {
  return with_first_axis_fallback(limits_at_cap(g, cap_mm_s, machine, junction_jerk_share), machine);
}

AccelerationBands acceleration_bands(const PathGeometry& g, const PathLimits& at_cap, const Machine& machine,
                                     double junction_jerk_share) noexcept {
  const double cap = at_cap.max_velocity;
  if (g.curvature.isZero() || !(cap > 0.0) || !std::isfinite(cap)) return {};
  const double extra = extra_axes_path_acceleration(g, machine);
  if (!(std::min(linear_path_acceleration_at(g, cap, machine), extra) == at_cap.max_acceleration))
    return {};  // path_limits' fallback: no axis bounds it
  AccelerationBands b;
  Vec3 cross = Vec3::Zero();  // the largest cross term 3 K_i v a over the bands [mm/s^3]
  for (const double f : tolerances::plan_acceleration_band_tops) {
    const bool last = !(f < 1.0);
    const double top = last ? cap : f * cap;
    const double linear = linear_path_acceleration_at(g, top, machine);
    double a = last ? at_cap.max_acceleration : std::min(linear, extra);
    if (!(a > 0.0) || !std::isfinite(a) || !std::isfinite(linear)) return {};
    if (b.n > 0) a = std::min(a, b.acceleration[static_cast<std::size_t>(b.n - 1)]);
    for (int i = 0; i < 3; ++i) cross[i] = std::max(cross[i], 3.0 * g.curvature[i] * top * linear);
    b.top_mm_s[static_cast<std::size_t>(b.n)] = top;
    b.acceleration[static_cast<std::size_t>(b.n)] = a;
    ++b.n;
    if (last) break;
  }
  if (!(b.acceleration[0] > at_cap.max_acceleration * (1.0 + 1e-9))) return {};  // nothing to gain
  b.max_jerk = std::min(at_cap.max_jerk, path_jerk_at(g, cap, cross, machine, junction_jerk_share));
  if (!(b.max_jerk > 0.0) || !std::isfinite(b.max_jerk)) return {};
  return b;
}

PathLimits move_limits(const MoveGeometry& move, const Machine& machine, int samples) {
  const Curve& c = *move.curve;
  const std::vector<double> bp = c.breakpoints();
  PathGeometry g;
  for (std::size_t k = 0; k + 1 < bp.size(); ++k) g.merge(path_geometry(c, bp[k], bp[k + 1], samples));
  return path_limits(g, move.length_mm, move.feed_mm_s, machine);
}

namespace {

// Share of an axis's acceleration that the velocity step of a corner (v |dt_i| / T, as setpoints a
// period apart see it) may take: plan_corner_acceleration_share, less where the moves on both
// sides can still be near their full acceleration within a period of the junction (they end at
// zero acceleration, but a jerk J brings it to J T within one period T): none once J T reaches
// plan_corner_step_jerk_ramp of A. A reversal on a machine with A = 735 mm/s^2 and J = 1e8 mm/s^3
// took 1.078 times its acceleration (issue 20, case 6); such a corner is now a stop.
double corner_step_share(const AxisLimits& axis, double period_s) noexcept {
  const double ramp = axis.max_jerk * period_s / axis.max_acceleration;
  return std::clamp(tolerances::plan_corner_step_jerk_ramp - ramp, 0.0, tolerances::plan_corner_acceleration_share);
}

}  // namespace

double junction_limit(const Derivatives& end_in, const Derivatives& start_out, const Machine& machine,
                      double jerk_share) noexcept {
  const Vec3 dt = unit_tangent(start_out) - unit_tangent(end_in);
  const Vec3 k_in = curvature_vector(end_in), k_out = curvature_vector(start_out);
  const Vec3 dk = k_out - k_in;
  double v = kInf;
  const double T = machine.servo_period_s;
  for (const AxisLimits& axis : machine.axes) {
    const int i = linear_axis_index(axis.name);
    if (i < 0) continue;  // rotary axes do not carry the path
    const double b = std::abs(dt[i]) > tolerances::plan_junction_smooth ? std::abs(dt[i]) / (T * T) : 0.0;
    const double a = std::abs(dk[i]) > tolerances::plan_junction_smooth ? std::abs(dk[i]) / T : 0.0;
    const double c = jerk_share * axis.max_jerk;
    // a v^2 + b v <= c, solved without cancellation
    if (a > 0.0) v = std::min(v, 2.0 * c / (b + std::sqrt(b * b + 4.0 * a * c)));
    else if (b > 0.0) v = std::min(v, c / b);
    // the acceleration spike of a corner, v |dt_i| / T, within its share of the axis's acceleration,
    // and the centripetal acceleration of the curves on either side there within the rest (a
    // curve's cap may take up to the largest of plan_centripetal_shares, above that rest)
    if (b > 0.0) {
      const double step_share = corner_step_share(axis, T);
      v = std::min(v, step_share * axis.max_acceleration * T / std::abs(dt[i]));
      const double k = std::max(std::abs(k_in[i]), std::abs(k_out[i]));  // [1/mm]
      if (k > 0.0) v = std::min(v, std::sqrt((1.0 - step_share) * axis.max_acceleration / k));
    }
  }
  return v;
}

Junction junction(const Derivatives& end_in, const Derivatives& start_out, const Machine& machine) noexcept {
  const Vec3 dt = unit_tangent(start_out) - unit_tangent(end_in);
  const Vec3 dk = curvature_vector(start_out) - curvature_vector(end_in);
  const double corner = dt.cwiseAbs().maxCoeff();
  if (corner <= tolerances::plan_junction_smooth && dk.cwiseAbs().maxCoeff() <= tolerances::plan_junction_smooth)
    return {kInf, 0.0};
  const double share = corner < tolerances::plan_small_corner ? tolerances::plan_smooth_junction_jerk_share
                                                              : tolerances::plan_corner_jerk_share;
  return {junction_limit(end_in, start_out, machine, share), share};
}

Junction extra_axes_junction(const ExtraAxes& rate_in, const ExtraAxes& rate_out, const Machine& machine) noexcept {
  double corner = 0.0;
  for (std::size_t e = 0; e < rate_in.size(); ++e) corner = std::max(corner, std::abs(rate_out[e] - rate_in[e]));
  if (corner <= tolerances::plan_junction_smooth) return {kInf, 0.0};
  const double share = corner < tolerances::plan_small_corner ? tolerances::plan_smooth_junction_jerk_share
                                                              : tolerances::plan_corner_jerk_share;
  const double T = machine.servo_period_s;
  double v = kInf;
  for (const AxisLimits& axis : machine.axes) {
    const int e = extra_axis_index(axis.name);
    if (e < 0) continue;
    const double jump = std::abs(rate_out[static_cast<std::size_t>(e)] - rate_in[static_cast<std::size_t>(e)]);
    if (!(jump > tolerances::plan_junction_smooth)) continue;
    // v |dr| / T^2 <= share J (the jerk of the velocity step) and v |dr| / T within its share of A
    v = std::min({v, share * axis.max_jerk * T * T / jump, corner_step_share(axis, T) * axis.max_acceleration * T / jump});
  }
  return {v, share};
}

Junction tighter(const Junction& a, const Junction& b) noexcept {
  return {std::min(a.velocity, b.velocity), std::max(a.jerk_share, b.jerk_share)};
}

double curve_speed_cap(const Curve& curve, double feed_mm_s, const Machine& machine) {
  const PathGeometry g = path_geometry(curve, curve.u_min(), curve.u_max());
  // (the largest shares inside a chain, where a blend runs: at about one speed, so the path
  // acceleration needs little)
  return speed_cap(g, feed_mm_s, machine, tolerances::plan_chain_centripetal_share_max,
                   tolerances::plan_chain_curvature_rate_share_max);
}

}  // namespace kontur::plan
