#include <algorithm>
#include <cmath>
#include <kontur/geometry/corner_blend_curve.hpp>
#include <kontur/geometry/differential.hpp>
#include <kontur/geometry/golden_section.hpp>
#include <kontur/tolerances.hpp>

namespace kontur {

Derivatives CornerBlendCurve::derivatives(double u, int order) const noexcept {
  u = std::clamp(u, 0.0, 1.0);
  const double u2 = u * u, u3 = u2 * u, u4 = u3 * u, u5 = u4 * u;
  const double s = d_ / 3.0;
  // 3 alpha and 3 beta and their derivatives (integer coefficients: the ends are exact).
  const double a[4] = {-3.0 + 5.0 * u - 5.0 * u4 + 3.0 * u5, 5.0 - 20.0 * u3 + 15.0 * u4, -60.0 * u2 + 60.0 * u3,
                       -120.0 * u + 180.0 * u2};
  const double b[4] = {10.0 * u3 - 10.0 * u4 + 3.0 * u5, 30.0 * u2 - 40.0 * u3 + 15.0 * u4,
                       60.0 * u - 120.0 * u2 + 60.0 * u3, 60.0 - 240.0 * u + 180.0 * u2};
  Derivatives out;
  const int n = std::clamp(order, 0, 3);
  for (int k = 0; k <= n; ++k) out[k] = s * (a[k] * t1_ + b[k] * t2_);
  out[0] += corner_;
  return out;
}

double corner_deviation(const Curve& c, const Vec3& before, const Vec3& corner, const Vec3& after) {
  auto dev = [&](double u) {
    const Vec3 p = c.point(u);
    return std::min(segment_distance(p, before, corner), segment_distance(p, corner, after));
  };
  return sampled_maximum(dev, c.u_min(), c.u_max(), tolerances::blend_deviation_samples);
}

double unit_blend_deviation(const Vec3& t1, const Vec3& t2) {
  const CornerBlendCurve c(Vec3::Zero(), t1, t2, 1.0);
  return corner_deviation(c, -t1, Vec3::Zero(), t2);
}

}  // namespace kontur
