#include <kontur/geometry/differential.hpp>
#include <kontur/geometry/golden_section.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace kontur {

Vec3 unit_tangent(const Derivatives& d) noexcept {
  const double n = d[1].norm();
  return n > 0.0 ? Vec3(d[1] / n) : Vec3::Zero();
}

Vec3 curvature_vector(const Derivatives& d) noexcept {
  const Vec3 &r1 = d[1], &r2 = d[2];
  const double q = r1.squaredNorm();
  if (!(q > 0.0)) return Vec3::Zero();
  return r2 / q - r1.dot(r2) * r1 / (q * q);
}

double curvature(const Derivatives& d) noexcept {
  const double v = d[1].norm();
  if (!(v > 0.0)) return 0.0;
  return d[1].cross(d[2]).norm() / (v * v * v);
}

double chord_error(double radius_mm, double step_mm) noexcept {
  if (!std::isfinite(radius_mm)) return 0.0;
  const double half = 0.5 * step_mm;
  if (half >= radius_mm) return radius_mm;
  // R - sqrt(R^2 - L^2/4), written without cancellation: (L^2/4) / (R + sqrt(R^2 - L^2/4)).
  return half * half / (radius_mm + std::sqrt(radius_mm * radius_mm - half * half));
}

double max_chord_for_error(double radius_mm, double tolerance_mm) noexcept {
  if (!std::isfinite(radius_mm)) return std::numeric_limits<double>::infinity();
  if (tolerance_mm >= radius_mm) return 2.0 * radius_mm;
  // 2 sqrt(R^2 - (R - delta)^2) = 2 sqrt(delta (2R - delta)).
  return 2.0 * std::sqrt(tolerance_mm * (2.0 * radius_mm - tolerance_mm));
}

double chord_error(const Curve& curve, double u0, double u1, int samples) noexcept {
  const Vec3 a = curve.point(u0), b = curve.point(u1);
  const Vec3 ab = b - a;
  const double len2 = ab.squaredNorm();
  double worst = 0.0;
  samples = std::max(samples, 1);
  for (int i = 1; i <= samples; ++i) {
    const double u = u0 + (u1 - u0) * i / (samples + 1.0);
    const Vec3 q = curve.point(u) - a;
    const double t = len2 > 0.0 ? std::clamp(q.dot(ab) / len2, 0.0, 1.0) : 0.0;
    worst = std::max(worst, (q - t * ab).norm());
  }
  return worst;
}

double polyline_distance(const std::vector<Vec3>& v, const Vec3& p, long first, long last) noexcept {
  const long lines = static_cast<long>(v.size()) - 1;
  first = std::max(first, 0L);
  last = std::min(last, lines - 1);
  double d2 = std::numeric_limits<double>::infinity();  // (the root of the least square: the same bits)
  for (long k = first; k <= last; ++k)
    d2 = std::min(d2, segment_distance_squared(p, v[static_cast<std::size_t>(k)], v[static_cast<std::size_t>(k + 1)]));
  return std::sqrt(d2);
}

}  // namespace kontur

namespace kontur {

double peak_parametric_speed(const Curve& curve, double u0, double u1, int samples) {
  samples = std::max(samples, 1);
  double peak = 0.0;
  for (int k = 0; k <= samples; ++k) {
    const double u = k == samples ? u1 : u0 + (u1 - u0) * k / samples;
    peak = std::max(peak, (k == samples ? curve.derivatives_left(u, 1) : curve.derivatives(u, 1))[1].norm());
  }
  return peak;
}

std::vector<double> stationary_points(const Curve& curve, double relative, int samples) {
  std::vector<double> out;
  const std::vector<double> bp = curve.breakpoints();
  samples = std::max(samples, 2);
  // |C'|^2 [mm^2 per parameter unit^2] on each span's grid; at a span's right end its own
  // polynomial (the next span may differ there)
  const auto speed2 = [&](double u, bool left) {
    return (left ? curve.derivatives_left(u, 1) : curve.derivatives(u, 1))[1].squaredNorm();
  };
  // A polynomial curve of degree 3 at most has a constant third derivative on each span: from
  // the derivatives at a span's middle m, with h its half width, |C''| <= |C''(m)| + |C'''| h =: b
  // on the span, and |C'(m)| - b h <= |C'| <= |C'(m)| + b h. Where every span's lower bound
  // exceeds `relative` times the largest upper bound, no sample can come within the limit below
  // (a smoothed run, whose |C'| hardly changes): none, without the grid.
  if (const int p = curve.polynomial_degree(); p >= 1 && p <= 3 && bp.size() >= 2) {
    double lowest = std::numeric_limits<double>::infinity(), highest = 0.0;  // [mm per parameter unit]
    for (std::size_t s = 0; s + 1 < bp.size() && lowest > 0.0; ++s) {
      const double h = 0.5 * (bp[s + 1] - bp[s]);
      const Derivatives d = curve.derivatives(bp[s] + h, 3);
      const double b = d[2].norm() + d[3].norm() * h, speed = d[1].norm();
      // (a bound that is not a number proves nothing: the grid decides)
      lowest = speed - b * h > 0.0 ? std::min(lowest, speed - b * h) : 0.0;
      highest = std::max(highest, speed + b * h);
    }
    if (lowest > 0.0 && std::isfinite(highest) && lowest > relative * highest) return out;
  }
  const std::size_t n = static_cast<std::size_t>(samples) + 1;
  std::vector<double> us(n * (bp.size() - 1)), f(us.size());
  for (std::size_t s = 0; s + 1 < bp.size(); ++s)
    for (std::size_t k = 0; k < n; ++k) {
      const std::size_t i = s * n + k;
      us[i] = k + 1 == n ? bp[s + 1] : bp[s] + (bp[s + 1] - bp[s]) * static_cast<double>(k) / samples;
      f[i] = speed2(us[i], k + 1 == n);
    }
  const double peak = us.empty() ? 0.0 : *std::max_element(f.begin(), f.end());
  if (!(peak > 0.0)) return out;  // a point: no tangent anywhere
  const double limit = relative * relative * peak;
  const auto add = [&](double u) {
    if (out.empty() || u > out.back()) out.push_back(u);
  };
  // Where |C'|^2 is a polynomial of degree d = 2 (p - 1) on each span (a curve of degree p, not
  // rational) and d^2 < N = samples, Markov's inequality (|f'| <= 2 d^2 / (b - a) max f on a span
  // [a, b]) bounds it between the grid points: max f <= M / (1 - d^2 / N) (M the span's largest
  // sample), and within a grid step of sample k, f >= f_k - 2 d^2 / N max f. A grid minimum above
  // limit by that much has no stationary point beside it and is not refined (on a smoothed run
  // |C'|^2 is nearly constant and flat to rounding: its grid minima cost 60 evaluations each).
  const int p = curve.polynomial_degree();
  const double d2 = p >= 1 ? 4.0 * (p - 1) * (p - 1) : -1.0;
  const double N = static_cast<double>(samples);
  const double markov = d2 >= 0.0 && d2 < N ? (2.0 * d2 / N) / (1.0 - d2 / N) : -1.0;  // -1: no bound
  for (std::size_t s = 0; s + 1 < bp.size(); ++s) {
    const double* fs = &f[s * n];
    const double* ut = &us[s * n];
    if (fs[0] <= limit) add(ut[0]);
    const double span_peak = markov >= 0.0 ? *std::max_element(fs, fs + n) : 0.0;  // (for the bound only)
    for (std::size_t k = 1; k + 1 < n; ++k) {
      if (!(fs[k] <= fs[k - 1] && fs[k] < fs[k + 1])) continue;
      if (markov >= 0.0 && fs[k] - markov * span_peak > limit) continue;
      // the minimum of |C'|^2 in [u_{k-1}, u_{k+1}]
      const auto [u_min, f_min] =
          golden_section_minimum([&](double u) { return speed2(u, false); }, ut[k - 1], ut[k + 1], 100);
      if (f_min <= limit) add(u_min);
    }
    if (fs[n - 1] <= limit) add(ut[n - 1]);
  }
  return out;
}

}  // namespace kontur
