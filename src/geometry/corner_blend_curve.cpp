#include <algorithm>
#include <cmath>
#include <kontur/geometry/corner_blend_curve.hpp>
#include <kontur/geometry/differential.hpp>
#include <kontur/geometry/golden_section.hpp>
#include <kontur/tolerances.hpp>

namespace kontur {

namespace {

// The six Bernstein polynomials of degree 5 on [0, 1] in the power basis: the B-spline basis of
// the knots 0 (six times) and 1 (six times).
const std::vector<PolyCoeffs>& bernstein_quintics() {
  static const std::vector<PolyCoeffs> basis =
      basis_polynomials({0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0}, 5, 5, 0.0);
  return basis;
}

}  // namespace

CornerBlendShape corner_blend_shape(double third) noexcept {
  return {tolerances::blend_shape_second_base + tolerances::blend_shape_second_slope * third, third};
}

CornerBlendCurve::CornerBlendCurve(const Vec3& corner, const Vec3& t1, const Vec3& t2, double d_mm,
                                   const CornerBlendShape& shape) noexcept
    : corner_(corner), d_(d_mm) {
  // The control points from P (relative: the coefficients do not carry P's magnitude, so a blend
  // of a micrometre far from the origin keeps its derivatives to the rounding of its own size).
  const std::array<Vec3, 6> q{Vec3(-d_mm * t1), Vec3(-shape.second * d_mm * t1), Vec3(-shape.third * d_mm * t1),
                              Vec3(shape.third * d_mm * t2), Vec3(shape.second * d_mm * t2), Vec3(d_mm * t2)};
  span_.u_start = 0.0;
  span_.u_end = 1.0;
  span_.degree = 5;
  const std::vector<PolyCoeffs>& basis = bernstein_quintics();
  for (std::size_t k = 0; k <= 5; ++k) {
    Vec3 c = Vec3::Zero();
    for (std::size_t i = 0; i <= 5; ++i) c += basis[i][k] * q[i];
    span_.coeff[k] << c, k == 0 ? 1.0 : 0.0;
  }
  span_.coeff[0].head<3>() += corner;
  // At u = 1 the last control point and its differences (5! / (5 - k)! times the k-th).
  end_[0] = corner + q[5];
  end_[1] = 5.0 * (q[5] - q[4]);
  end_[2] = 20.0 * (q[5] - 2.0 * q[4] + q[3]);
  end_[3] = 60.0 * (q[5] - 3.0 * q[4] + 3.0 * q[3] - q[2]);
}

Derivatives CornerBlendCurve::derivatives(double u, int order) const noexcept {
  u = std::clamp(u, 0.0, 1.0);
  if (u < 1.0) return span_.derivatives(u, std::clamp(order, 0, 3));
  Derivatives out;
  for (int k = 0; k <= std::clamp(order, 0, 3); ++k) out[k] = end_[static_cast<std::size_t>(k)];
  return out;
}

double corner_deviation(const Curve& c, const Vec3& before, const Vec3& corner, const Vec3& after) {
  auto dev = [&](double u) {
    const Vec3 p = c.point(u);
    return std::min(segment_distance(p, before, corner), segment_distance(p, corner, after));
  };
  return sampled_maximum(dev, c.u_min(), c.u_max(), tolerances::blend_deviation_samples);
}

double unit_blend_deviation(const Vec3& t1, const Vec3& t2, const CornerBlendShape& shape) {
  const CornerBlendCurve c(Vec3::Zero(), t1, t2, 1.0, shape);
  return corner_deviation(c, -t1, Vec3::Zero(), t2);
}

}  // namespace kontur
