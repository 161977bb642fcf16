#include <algorithm>
#include <cmath>
#include <kontur/geometry/differential.hpp>
#include <kontur/geometry/golden_section.hpp>
#include <kontur/geometry/piece_distance.hpp>
#include <kontur/geometry/transition_curve.hpp>
#include <kontur/tolerances.hpp>

namespace kontur {

TransitionCurve::TransitionCurve(const CurveEnd& from, const CurveEnd& to, double tangent_scale) noexcept {
  const double lambda = tangent_scale * (to.point - from.point).norm();
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
  return curve_end(left ? curve.derivatives_left(u, 2) : curve.derivatives(u, 2));
}

CurveEnd curve_end(const Derivatives& d) {
  CurveEnd e;
  e.point = d[0];
  const double q = d[1].squaredNorm();
  e.tangent = q > 0.0 ? Vec3(d[1] / std::sqrt(q)) : Vec3::Zero();
  e.curvature = q > 0.0 ? curvature_vector(d) : Vec3::Zero();
  return e;
}

double curves_deviation(const Curve& curve, const Curve& a, const Curve& b, int samples) {
  const PieceDistance to_a(a), to_b(b);
  return sampled_maximum(
      [&](double u) {
        return nearer_distance(to_a, to_b, curve.point(u));
      },
      curve.u_min(), curve.u_max(), samples);
}

}  // namespace kontur
