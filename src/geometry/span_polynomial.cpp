#include <kontur/geometry/span_polynomial.hpp>

#include <algorithm>

namespace kontur {

double evaluate_polynomial(const PolyCoeffs& c, int degree, double x) noexcept {
  double v = c[static_cast<std::size_t>(degree)];
  for (int k = degree - 1; k >= 0; --k) v = v * x + c[static_cast<std::size_t>(k)];
  return v;
}

PolyCoeffs shift_polynomial(const PolyCoeffs& c, int degree, double shift) noexcept {
  // Repeated synthetic division by (x - shift) (Taylor shift): d_k = P^(k)(shift) / k!.
  PolyCoeffs d = c;
  for (int k = 0; k < degree; ++k) {
    for (int j = degree - 1; j >= k; --j) d[static_cast<std::size_t>(j)] += shift * d[static_cast<std::size_t>(j + 1)];
  }
  return d;
}

std::vector<PolyCoeffs> basis_polynomials(const std::vector<double>& U, int p, int i, double origin) {
  // N[j] holds N_{i-k+j, k} during step k; the variable is x = u - origin, so
  // (u - u_j) = x + (origin - u_j) and (u_j - u) = (u_j - origin) - x.
  std::vector<PolyCoeffs> N(static_cast<std::size_t>(p + 1), PolyCoeffs{});
  N[0][0] = 1.0;
  auto knot = [&](int idx) { return U[static_cast<std::size_t>(idx)]; };
  for (int k = 1; k <= p; ++k) {
    std::vector<PolyCoeffs> next(static_cast<std::size_t>(p + 1), PolyCoeffs{});
    for (int j = 0; j <= k; ++j) {
      const int fn = i - k + j;  // index of the new basis function N_{fn, k}
      PolyCoeffs& out = next[static_cast<std::size_t>(j)];
      // Left term: (u - u_fn) / (u_{fn+k} - u_fn) * N_{fn, k-1}   (N_{fn,k-1} is N[j-1])
      if (j >= 1) {
        const double den = knot(fn + k) - knot(fn);
        if (den != 0.0) {
          const PolyCoeffs& src = N[static_cast<std::size_t>(j - 1)];
          const double c0 = (origin - knot(fn)) / den, c1 = 1.0 / den;
          for (int e = k - 1; e >= 0; --e) {
            out[static_cast<std::size_t>(e + 1)] += c1 * src[static_cast<std::size_t>(e)];
            out[static_cast<std::size_t>(e)] += c0 * src[static_cast<std::size_t>(e)];
          }
        }
      }
      // Right term: (u_{fn+k+1} - u) / (u_{fn+k+1} - u_{fn+1}) * N_{fn+1, k-1}   (N[j])
      if (j <= k - 1) {
        const double den = knot(fn + k + 1) - knot(fn + 1);
        if (den != 0.0) {
          const PolyCoeffs& src = N[static_cast<std::size_t>(j)];
          const double c0 = (knot(fn + k + 1) - origin) / den, c1 = -1.0 / den;
          for (int e = k - 1; e >= 0; --e) {
            out[static_cast<std::size_t>(e + 1)] += c1 * src[static_cast<std::size_t>(e)];
            out[static_cast<std::size_t>(e)] += c0 * src[static_cast<std::size_t>(e)];
          }
        }
      }
    }
    N = std::move(next);
  }
  return N;
}

PolyCoeffs SpanPolynomial::coefficients(int axis, double origin) const noexcept {
  PolyCoeffs c{};
  for (int k = 0; k <= degree; ++k) c[static_cast<std::size_t>(k)] = coeff[static_cast<std::size_t>(k)][axis];
  // Local variable t = u - u_start; wanted: x = u - origin = t + (u_start - origin), so
  // t = x - (u_start - origin).
  return shift_polynomial(c, degree, -(u_start - origin));
}

namespace {

// Horner's scheme for the value and the first `Order` derivatives at once (h[k]: the k-th
// derivative over k!); the higher ones are not computed (what a caller does not ask for).
template <int Order>
void horner(const std::array<Eigen::Vector4d, tolerances::max_degree + 1>& coeff, int degree, double t,
            Eigen::Vector4d (&h)[4]) noexcept {
  h[0] = coeff[static_cast<std::size_t>(degree)];
  for (int k = 1; k < 4; ++k) h[k].setZero();
  for (int k = degree - 1; k >= 0; --k) {
    if constexpr (Order >= 3) h[3] = h[3] * t + h[2];
    if constexpr (Order >= 2) h[2] = h[2] * t + h[1];
    if constexpr (Order >= 1) h[1] = h[1] * t + h[0];
    h[0] = h[0] * t + coeff[static_cast<std::size_t>(k)];
  }
}

}  // namespace

Derivatives SpanPolynomial::derivatives(double u, int order) const noexcept {
  order = std::clamp(order, 0, tolerances::max_derivative);
  const double t = u - u_start;
  Eigen::Vector4d h[4];
  switch (order) {
    case 0: horner<0>(coeff, degree, t, h); break;
    case 1: horner<1>(coeff, degree, t, h); break;
    case 2: horner<2>(coeff, degree, t, h); break;
    default: horner<3>(coeff, degree, t, h); break;
  }
  h[2] *= 2.0;
  h[3] *= 6.0;
  Derivatives out;
  if (!rational) {
    for (int k = 0; k <= order; ++k) out[k] = h[k].head<3>();
    return out;
  }
  static constexpr double binom[4][4] = {{1, 0, 0, 0}, {1, 1, 0, 0}, {1, 2, 1, 0}, {1, 3, 3, 1}};
  for (int k = 0; k <= order; ++k) {
    Vec3 v = h[k].head<3>();
    for (int i = 1; i <= k; ++i) v -= binom[k][i] * h[i][3] * out[k - i];
    out[k] = v / h[0][3];
  }
  return out;
}

SpanPolynomialCurve::SpanPolynomialCurve(const NurbsCurve& curve) : degree_(curve.degree()), rational_(curve.rational()) {
  const auto& U = curve.knots();
  const int p = curve.degree();
  const int n = static_cast<int>(curve.points().size()) - 1;
  for (int i = p; i <= n; ++i) {
    const double a = U[static_cast<std::size_t>(i)], b = U[static_cast<std::size_t>(i + 1)];
    if (!(b > a)) continue;
    SpanPolynomial s;
    s.u_start = a;
    s.u_end = b;
    s.knot_index = i;
    s.degree = p;
    s.rational = rational_;
    const auto N = basis_polynomials(U, p, i, a);
    for (int j = 0; j <= p; ++j) {
      const auto idx = static_cast<std::size_t>(i - p + j);
      const double w = rational_ ? curve.weights()[idx] : 1.0;
      Eigen::Vector4d hp;
      hp << w * curve.points()[idx], w;
      for (int k = 0; k <= p; ++k) s.coeff[static_cast<std::size_t>(k)] += N[static_cast<std::size_t>(j)][static_cast<std::size_t>(k)] * hp;
    }
    spans_.push_back(s);
    starts_.push_back(a);
  }
}

std::size_t SpanPolynomialCurve::span_index(double u) const noexcept {
  // (the same index as the search: the last span whose start is at most u, else the first)
  const std::size_t last = last_.index.load(std::memory_order_relaxed);
  if (last < starts_.size() && starts_[last] <= u && (last + 1 == starts_.size() || u < starts_[last + 1]))
    return last;
  const auto it = std::upper_bound(starts_.begin(), starts_.end(), u);
  const std::size_t i = it == starts_.begin() ? 0 : static_cast<std::size_t>(it - starts_.begin()) - 1;
  last_.index.store(i, std::memory_order_relaxed);
  return i;
}

Derivatives SpanPolynomialCurve::derivatives(double u, int order) const noexcept {
  u = std::clamp(u, u_min(), u_max());
  return spans_[span_index(u)].derivatives(u, order);
}

Derivatives SpanPolynomialCurve::derivatives_left(double u, int order) const noexcept {
  u = std::clamp(u, u_min(), u_max());
  std::size_t i = span_index(u);
  if (i > 0 && u == spans_[i].u_start) --i;
  return spans_[i].derivatives(u, order);
}

std::vector<double> SpanPolynomialCurve::breakpoints() const {
  std::vector<double> b;
  b.reserve(spans_.size() + 1);
  for (const auto& s : spans_) b.push_back(s.u_start);
  b.push_back(spans_.back().u_end);
  return b;
}

}  // namespace kontur
