#include <algorithm>
#include <cmath>
#include <kontur/geometry/differential.hpp>
#include <kontur/geometry/golden_section.hpp>
#include <kontur/geometry/helix_arc.hpp>
#include <kontur/geometry/line_segment.hpp>
#include <kontur/geometry/transition_curve.hpp>
#include <kontur/tolerances.hpp>
#include <limits>

namespace kontur {

TransitionCurve::TransitionCurve(const CurveEnd& from, const CurveEnd& to) noexcept {
  const double lambda = (to.point - from.point).norm();
  const Vec3 p = to.point - from.point;
  const Vec3 v0 = lambda * from.tangent, v1 = lambda * to.tangent;
  const Vec3 a0 = lambda * lambda * from.curvature, a1 = lambda * lambda * to.curvature;
  // The quintic Hermite basis: B(0), B'(0), B''(0), B(1), B'(1), B''(1) as given.
  c_[0] = from.point;
  c_[1] = v0;
  c_[2] = 0.5 * a0;
  c_[3] = 10.0 * p - 6.0 * v0 - 4.0 * v1 - 1.5 * a0 + 0.5 * a1;
  c_[4] = -15.0 * p + 8.0 * v0 + 7.0 * v1 + 1.5 * a0 - a1;
  c_[5] = 6.0 * p - 3.0 * v0 - 3.0 * v1 - 0.5 * a0 + 0.5 * a1;
}

Derivatives TransitionCurve::derivatives(double u, int order) const noexcept {
  u = std::clamp(u, 0.0, 1.0);
  Derivatives out;
  const int n = std::clamp(order, 0, 3);
  for (int k = 0; k <= n; ++k) {
    // the k-th derivative by Horner's scheme on its falling-factorial coefficients
    Vec3 acc = Vec3::Zero();
    for (int i = 5; i >= k; --i) {
      double f = 1.0;
      for (int m = 0; m < k; ++m) f *= static_cast<double>(i - m);
      acc = acc * u + f * c_[static_cast<std::size_t>(i)];
    }
    out[k] = acc;
  }
  return out;
}

CurveEnd curve_end(const Curve& curve, double u, bool left) {
  const Derivatives d = left ? curve.derivatives_left(u, 2) : curve.derivatives(u, 2);
  CurveEnd e;
  e.point = d[0];
  const double q = d[1].squaredNorm();
  e.tangent = q > 0.0 ? Vec3(d[1] / std::sqrt(q)) : Vec3::Zero();
  e.curvature = q > 0.0 ? curvature_vector(d) : Vec3::Zero();
  return e;
}

namespace {

// A short curve (a line, or an arc of less than a turn) to measure distances to: its ends, and the
// parameter of the last foot found (the next point's search starts there).
struct Target {
  explicit Target(const Curve& c)
      : curve(c), line(dynamic_cast<const LineSegment*>(&c)), arc(arc_span(c)), start(c.point(c.u_min())),
        end(c.point(c.u_max())), u(c.u_min()) {}
  // Distance [mm] from p: a line's exactly, an arc's by HelixArc::distance_mm; else Newton on
  // (C(u) - p) . C'(u) = 0 from the last foot, kept in the range, and the ends (the foot of a point
  // beyond them).
  double distance(const Vec3& p) {
    if (line != nullptr) return segment_distance(p, line->start(), line->end());
    if (arc.arc != nullptr) return arc.arc->distance_mm(p, arc.u0, arc.u1);
    const double lo = curve.u_min(), hi = curve.u_max();
    double at_u = std::numeric_limits<double>::infinity();
    for (int i = 0; i < 30; ++i) {
      const Derivatives d = curve.derivatives(u, 2);
      const Vec3 r = d[0] - p;
      at_u = r.norm();
      const double f = r.dot(d[1]), fp = d[1].squaredNorm() + r.dot(d[2]);
      if (!(fp > 0.0)) break;
      const double next = std::clamp(u - f / fp, lo, hi);
      if (std::abs(next - u) <= 1e-15 * std::max(1.0, std::abs(u))) break;
      u = next;
    }
    return std::min({at_u, (start - p).norm(), (end - p).norm()});
  }
  const Curve& curve;
  const LineSegment* line;
  ArcSpan arc;
  Vec3 start, end;
  double u;
};

}  // namespace

double curves_deviation(const Curve& curve, const Curve& a, const Curve& b, int samples) {
  Target ta(a), tb(b);
  const auto dev = [&](double u) {
    const Vec3 p = curve.point(u);
    return std::min(ta.distance(p), tb.distance(p));
  };
  const int n = std::max(samples, 2);
  const double u0 = curve.u_min(), h = (curve.u_max() - curve.u_min()) / n;
  double best = 0.0;
  int best_k = 0;
  for (int k = 0; k <= n; ++k) {
    const double v = dev(u0 + h * k);
    if (v > best) {
      best = v;
      best_k = k;
    }
  }
  const double lo = std::max(curve.u_min(), u0 + h * (best_k - 1)), hi = std::min(curve.u_max(), u0 + h * (best_k + 1));
  // (the feet start again from the largest sample's neighbourhood)
  ta.u = a.u_min();
  tb.u = b.u_min();
  dev(lo);
  const double negative_peak = golden_section_minimum([&](double u) { return -dev(u); }, lo, hi, 60).second;
  return std::max(best, -negative_peak);
}

}  // namespace kontur
