#include <algorithm>
#include <cmath>
#include <kontur/geometry/corner_blend_curve.hpp>
#include <kontur/geometry/differential.hpp>
#include <kontur/geometry/golden_section.hpp>
#include <kontur/tolerances.hpp>

namespace kontur {

namespace {

// The power-basis coefficients (ascending) of the quintic with Bernstein coefficients c:
// p_j = C(5, j) sum_{i <= j} C(j, i) (-1)^(j - i) c_i.
std::array<double, 6> power_coefficients(const std::array<double, 6>& c) noexcept {
  constexpr std::array<std::array<double, 6>, 6> binomial{{{1, 0, 0, 0, 0, 0},
                                                           {1, 1, 0, 0, 0, 0},
                                                           {1, 2, 1, 0, 0, 0},
                                                           {1, 3, 3, 1, 0, 0},
                                                           {1, 4, 6, 4, 1, 0},
                                                           {1, 5, 10, 10, 5, 1}}};
  std::array<double, 6> p{};
  for (std::size_t j = 0; j < 6; ++j) {
    double sum = 0.0;
    for (std::size_t i = 0; i <= j; ++i) sum += binomial[j][i] * ((j - i) % 2 == 0 ? 1.0 : -1.0) * c[i];
    p[j] = binomial[5][j] * sum;
  }
  return p;
}

// Derivative k of the polynomial with ascending coefficients p at u (Horner's rule).
double power_derivative(const std::array<double, 6>& p, int k, double u) noexcept {
  double r = 0.0;
  for (int j = 5; j >= k; --j) {
    double f = 1.0;
    for (int q = 0; q < k; ++q) f *= j - q;
    r = r * u + f * p[static_cast<std::size_t>(j)];
  }
  return r;
}

// Rows of differences: row k holds the k-th differences of row 0 (6 - k of them).
void fill_differences(std::array<std::array<double, 6>, 4>& rows) noexcept {
  for (std::size_t k = 1; k < rows.size(); ++k)
    for (std::size_t i = 0; i + k < 6; ++i) rows[k][i] = rows[k - 1][i + 1] - rows[k - 1][i];
}

}  // namespace

CornerBlendShape corner_blend_shape(double third) noexcept {
  return {tolerances::blend_shape_second_base + tolerances::blend_shape_second_slope * third, third};
}

CornerBlendCurve::CornerBlendCurve(const Vec3& corner, const Vec3& t1, const Vec3& t2, double d_mm,
                                   const CornerBlendShape& shape) noexcept
    : corner_(corner), t1_(t1), t2_(t2), d_(d_mm), shape_(shape) {
  along1_[0] = {-d_mm, -shape.second * d_mm, -shape.third * d_mm, 0.0, 0.0, 0.0};
  along2_[0] = {0.0, 0.0, 0.0, shape.third * d_mm, shape.second * d_mm, d_mm};
  fill_differences(along1_);
  fill_differences(along2_);
  power1_ = power_coefficients(along1_[0]);
  power2_ = power_coefficients(along2_[0]);
}

Derivatives CornerBlendCurve::derivatives(double u, int order) const noexcept {
  u = std::clamp(u, 0.0, 1.0);
  constexpr std::array<double, 4> factor{1.0, 5.0, 20.0, 60.0};  // 5! / (5 - k)!
  Derivatives out;
  const int n = std::clamp(order, 0, 3);
  for (int k = 0; k <= n; ++k) {
    const auto kk = static_cast<std::size_t>(k);
    // (at u = 1 the last control point and differences: B(1) = P + d t2 and B'(1), B''(1) along t2
    // exactly, as at u = 0, where the power basis's first coefficients are the Bernstein ones)
    if (u == 1.0)
      out[k] = factor[kk] * (along1_[kk][5 - kk] * t1_ + along2_[kk][5 - kk] * t2_);
    else
      out[k] = power_derivative(power1_, k, u) * t1_ + power_derivative(power2_, k, u) * t2_;
  }
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

double unit_blend_deviation(const Vec3& t1, const Vec3& t2, const CornerBlendShape& shape) {
  const CornerBlendCurve c(Vec3::Zero(), t1, t2, 1.0, shape);
  return corner_deviation(c, -t1, Vec3::Zero(), t2);
}

}  // namespace kontur
