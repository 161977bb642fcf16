#include <kontur/error.hpp>
#include <kontur/geometry/nurbs.hpp>
#include <kontur/tolerances.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace kontur {
namespace {

constexpr int kMaxOrder = tolerances::max_degree + 1;

std::string fmt_num(double v) { return fmt::format("{}", v); }

}  // namespace

std::optional<NurbsProblem> validate(const NurbsData& c) {
  const int p = c.degree;
  const auto n_points = static_cast<int>(c.points.size());
  const auto n_knots = static_cast<int>(c.knots.size());
  if (p < 1 || p > tolerances::max_degree) {
    return NurbsProblem{"degree-range", fmt::format("degree {} is outside the supported range 1..{} "
                                                    "(order 2..{})",
                                                    p, tolerances::max_degree, tolerances::max_degree + 1)};
  }
  if (n_points < p + 1) {
    return NurbsProblem{"too-few-points",
                        fmt::format("{} control points given; a curve of degree {} needs at least {} "
                                    "(degree + 1)",
                                    n_points, p, p + 1)};
  }
  for (int i = 0; i < n_points; ++i) {
    const Vec3& q = c.points[static_cast<std::size_t>(i)];
    if (!q.allFinite()) {
      return NurbsProblem{"point-not-finite",
                          fmt::format("points[{}] = ({}, {}, {}) is not finite", i, q.x(), q.y(), q.z())};
    }
  }
  if (!c.weights.empty()) {
    if (c.weights.size() != c.points.size()) {
      return NurbsProblem{"weight-count", fmt::format("{} weights given for {} control points; there must be "
                                                      "one weight per control point",
                                                      c.weights.size(), n_points)};
    }
    for (int i = 0; i < n_points; ++i) {
      const double w = c.weights[static_cast<std::size_t>(i)];
      if (!std::isfinite(w) || w <= 0.0) {
        return NurbsProblem{"weight-positive",
                            fmt::format("weights[{}] = {}: every weight must be finite and > 0", i, fmt_num(w))};
      }
    }
  }
  if (n_knots != n_points + p + 1) {
    return NurbsProblem{"knot-count", fmt::format("{} knots given, {} needed ({} control points + degree {} + 1)",
                                                  n_knots, n_points + p + 1, n_points, p)};
  }
  for (int i = 0; i < n_knots; ++i) {
    const double k = c.knots[static_cast<std::size_t>(i)];
    if (!std::isfinite(k)) return NurbsProblem{"knot-not-finite", fmt::format("knots[{}] = {} is not finite", i, k)};
    if (i > 0 && k < c.knots[static_cast<std::size_t>(i - 1)]) {
      return NurbsProblem{"knots-decreasing",
                          fmt::format("knots[{}] = {} is less than knots[{}] = {}: knots must be non-decreasing", i,
                                      fmt_num(k), i - 1, fmt_num(c.knots[static_cast<std::size_t>(i - 1)]))};
    }
  }
  const double a = c.knots[static_cast<std::size_t>(p)];
  const double b = c.knots[static_cast<std::size_t>(n_knots - p - 1)];
  if (!(b > a)) {
    return NurbsProblem{"empty-range", fmt::format("the parameter range [knots[{}], knots[{}]] = [{}, {}] has zero "
                                                   "length",
                                                   p, n_knots - p - 1, fmt_num(a), fmt_num(b))};
  }
  // Clamped ends: the first p + 1 knots equal, and the last p + 1.
  for (int i = 0; i <= p; ++i) {
    const double front = c.knots[static_cast<std::size_t>(i)];
    const double back = c.knots[static_cast<std::size_t>(n_knots - 1 - i)];
    if (front != c.knots[0]) {
      return NurbsProblem{"end-multiplicity",
                          fmt::format("knots[{}] = {} differs from knots[0] = {}: the first degree + 1 = {} knots "
                                      "must be equal (clamped curve)",
                                      i, fmt_num(front), fmt_num(c.knots[0]), p + 1)};
    }
    if (back != c.knots.back()) {
      return NurbsProblem{"end-multiplicity",
                          fmt::format("knots[{}] = {} differs from knots[{}] = {}: the last degree + 1 = {} knots "
                                      "must be equal (clamped curve)",
                                      n_knots - 1 - i, fmt_num(back), n_knots - 1, fmt_num(c.knots.back()), p + 1)};
    }
  }
  // Inner knots: multiplicity at most p, and none equal to an end knot (that would raise the
  // end multiplicity above p + 1).
  for (int i = p + 1; i < n_knots - p - 1;) {
    int j = i;
    while (j + 1 < n_knots - p - 1 && c.knots[static_cast<std::size_t>(j + 1)] == c.knots[static_cast<std::size_t>(i)]) ++j;
    const int mult = j - i + 1;
    const double k = c.knots[static_cast<std::size_t>(i)];
    if (k == c.knots[0] || k == c.knots.back()) {
      return NurbsProblem{"end-multiplicity",
                          fmt::format("knots[{}] = {} repeats an end knot: the end knots must appear exactly "
                                      "degree + 1 = {} times",
                                      i, fmt_num(k), p + 1)};
    }
    if (mult > p) {
      return NurbsProblem{"inner-multiplicity",
                          fmt::format("inner knot {} appears {} times (knots[{}..{}]); at most degree = {} times "
                                      "is allowed",
                                      fmt_num(k), mult, i, j, p)};
    }
    i = j + 1;
  }
  return std::nullopt;
}

NurbsCurve::NurbsCurve(NurbsData data) : data_(std::move(data)) {
  if (auto problem = validate(data_)) throw InputError(problem->rule, problem->message);
  weights_ = data_.weights.empty() ? std::vector<double>(data_.points.size(), 1.0) : data_.weights;
  rational_ = std::any_of(weights_.begin(), weights_.end(), [&](double w) { return w != weights_.front(); });
}

double NurbsCurve::u_min() const noexcept { return data_.knots[static_cast<std::size_t>(data_.degree)]; }
double NurbsCurve::u_max() const noexcept { return data_.knots[data_.knots.size() - 1 - static_cast<std::size_t>(data_.degree)]; }

int NurbsCurve::find_span(double u) const noexcept {
  const auto& U = data_.knots;
  const int p = data_.degree;
  const int n = static_cast<int>(data_.points.size()) - 1;
  if (u >= U[static_cast<std::size_t>(n + 1)]) {
    int i = n;  // last non-empty span
    while (i > p && U[static_cast<std::size_t>(i)] == U[static_cast<std::size_t>(i + 1)]) --i;
    return i;
  }
  if (u <= U[static_cast<std::size_t>(p)]) {
    int i = p;
    while (i < n && U[static_cast<std::size_t>(i)] == U[static_cast<std::size_t>(i + 1)]) ++i;
    return i;
  }
  // Largest i in [p, n] with U[i] <= u < U[i+1].
  const auto first = U.begin() + p;
  const auto last = U.begin() + n + 1;
  const auto it = std::upper_bound(first, last, u);
  return static_cast<int>(it - U.begin()) - 1;
}

std::vector<double> NurbsCurve::breakpoints() const {
  std::vector<double> b;
  const auto& U = data_.knots;
  for (std::size_t i = static_cast<std::size_t>(data_.degree); i < U.size() - static_cast<std::size_t>(data_.degree); ++i) {
    if (b.empty() || U[i] > b.back()) b.push_back(U[i]);
  }
  return b;
}

double NurbsCurve::extent() const noexcept {
  Vec3 lo = data_.points.front(), hi = data_.points.front();
  for (const auto& q : data_.points) {
    lo = lo.cwiseMin(q);
    hi = hi.cwiseMax(q);
  }
  return (hi - lo).norm();
}

int NurbsCurve::find_span_left(double u) const noexcept {
  int i = find_span(u);
  while (i > data_.degree && u == data_.knots[static_cast<std::size_t>(i)]) --i;
  // Skip empty spans (repeated knots) down to the one that ends at u.
  while (i > data_.degree && data_.knots[static_cast<std::size_t>(i)] == data_.knots[static_cast<std::size_t>(i + 1)]) --i;
  return i;
}

Derivatives NurbsCurve::derivatives(double u, int order) const noexcept {
  u = std::clamp(u, u_min(), u_max());
  return evaluate(u, find_span(u), order);
}

Derivatives NurbsCurve::derivatives_left(double u, int order) const noexcept {
  u = std::clamp(u, u_min(), u_max());
  return evaluate(u, find_span_left(u), order);
}

Derivatives NurbsCurve::evaluate(double u, int span, int order) const noexcept {
  const int p = data_.degree;
  const auto& U = data_.knots;
  order = std::clamp(order, 0, tolerances::max_derivative);
  const int nd = std::min(order, p);

  // Basis functions and their derivatives (Piegl & Tiller, algorithm A2.3), fixed-size scratch.
  double ndu[kMaxOrder][kMaxOrder];
  double left[kMaxOrder], right[kMaxOrder];
  double ders[4][kMaxOrder] = {};
  ndu[0][0] = 1.0;
  for (int j = 1; j <= p; ++j) {
    left[j] = u - U[static_cast<std::size_t>(span + 1 - j)];
    right[j] = U[static_cast<std::size_t>(span + j)] - u;
    double saved = 0.0;
    for (int r = 0; r < j; ++r) {
      ndu[j][r] = right[r + 1] + left[j - r];
      const double temp = ndu[r][j - 1] / ndu[j][r];
      ndu[r][j] = saved + right[r + 1] * temp;
      saved = left[j - r] * temp;
    }
    ndu[j][j] = saved;
  }
  for (int j = 0; j <= p; ++j) ders[0][j] = ndu[j][p];
  double a[2][kMaxOrder];
  for (int r = 0; r <= p; ++r) {
    int s1 = 0, s2 = 1;
    a[0][0] = 1.0;
    for (int k = 1; k <= nd; ++k) {
      double d = 0.0;
      const int rk = r - k, pk = p - k;
      if (r >= k) {
        a[s2][0] = a[s1][0] / ndu[pk + 1][rk];
        d = a[s2][0] * ndu[rk][pk];
      }
      const int j1 = (rk >= -1) ? 1 : -rk;
      const int j2 = (r - 1 <= pk) ? k - 1 : p - r;
      for (int j = j1; j <= j2; ++j) {
        a[s2][j] = (a[s1][j] - a[s1][j - 1]) / ndu[pk + 1][rk + j];
        d += a[s2][j] * ndu[rk + j][pk];
      }
      if (r <= pk) {
        a[s2][k] = -a[s1][k - 1] / ndu[pk + 1][r];
        d += a[s2][k] * ndu[r][pk];
      }
      ders[k][r] = d;
      std::swap(s1, s2);
    }
  }
  double factor = p;
  for (int k = 1; k <= nd; ++k) {
    for (int j = 0; j <= p; ++j) ders[k][j] *= factor;
    factor *= (p - k);
  }

  // Homogeneous derivatives A^(k) = sum N^(k) w P, w^(k) = sum N^(k) w.
  Vec3 A[4] = {Vec3::Zero(), Vec3::Zero(), Vec3::Zero(), Vec3::Zero()};
  double W[4] = {0.0, 0.0, 0.0, 0.0};
  for (int j = 0; j <= p; ++j) {
    const auto idx = static_cast<std::size_t>(span - p + j);
    const double w = weights_[idx];
    const Vec3& P = data_.points[idx];
    for (int k = 0; k <= nd; ++k) {
      A[k] += (ders[k][j] * w) * P;
      W[k] += ders[k][j] * w;
    }
  }
  // Rational derivatives (A4.2): C^(k) = (A^(k) - sum_{i=1..k} binom(k,i) w^(i) C^(k-i)) / w.
  Derivatives out;
  if (!rational_) {
    // Equal weights cancel: the weight's derivatives are zero in exact arithmetic, so the
    // quotient rule would only add rounding noise (e.g. a non-zero third derivative of a
    // quadratic).
    for (int k = 0; k <= nd; ++k) out[k] = A[k] / W[0];
    return out;
  }
  static constexpr double binom[4][4] = {{1, 0, 0, 0}, {1, 1, 0, 0}, {1, 2, 1, 0}, {1, 3, 3, 1}};
  for (int k = 0; k <= order; ++k) {
    Vec3 v = (k <= nd) ? A[k] : Vec3::Zero();
    for (int i = 1; i <= k; ++i) v -= binom[k][i] * W[i] * out[k - i];
    out[k] = v / W[0];
  }
  return out;
}

}  // namespace kontur
