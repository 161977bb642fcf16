#include <kontur/interpolate/forward_difference.hpp>

#include <cmath>

namespace kontur {
namespace {

constexpr int kN = tolerances::max_degree + 1;

// Stirling numbers of the second kind times j!: the j-th forward difference of m^k at m = 0.
struct DifferenceTable {
  double v[kN][kN]{};  // v[k][j] = Delta^j (m^k) at 0 = j! S(k, j)
  constexpr DifferenceTable() {
    double S[kN][kN]{};
    S[0][0] = 1.0;
    for (int k = 1; k < kN; ++k)
      for (int j = 1; j <= k; ++j) S[k][j] = j * S[k - 1][j] + S[k - 1][j - 1];
    for (int k = 0; k < kN; ++k) {
      double f = 1.0;
      for (int j = 0; j < kN; ++j) {
        if (j > 0) f *= j;
        v[k][j] = f * S[k][j];
      }
    }
  }
};
constexpr DifferenceTable kDiff{};

}  // namespace

PolyCoeffs initial_differences(const PolyCoeffs& c, int degree, double a, double h) noexcept {
  // q(m) = P(a + h m) = sum_k d_k (h m)^k with d the coefficients of P about a.
  const PolyCoeffs d = shift_polynomial(c, degree, a);
  PolyCoeffs b{};
  double hk = 1.0;
  for (int k = 0; k <= degree; ++k) {
    b[static_cast<std::size_t>(k)] = d[static_cast<std::size_t>(k)] * hk;
    hk *= h;
  }
  PolyCoeffs D{};
  for (int j = 0; j <= degree; ++j) {
    double s = 0.0;
    for (int k = degree; k >= j; --k) s += b[static_cast<std::size_t>(k)] * kDiff.v[k][j];
    D[static_cast<std::size_t>(j)] = s;
  }
  return D;
}

ForwardDifferenceStepper::ForwardDifferenceStepper(const SpanPolynomialCurve& curve, double h, Summation summation)
    : curve_(&curve), h_(h), summation_(summation), p_(curve.degree()), dims_(curve.rational() ? 4 : 3) {
  const double range = curve.u_max() - curve.u_min();
  cycles_ = static_cast<long>(std::floor(range / h_));
  while (cycles_ > 0 && curve.u_min() + static_cast<double>(cycles_) * h_ > curve.u_max()) --cycles_;
  reset();
}

double ForwardDifferenceStepper::u() const noexcept { return curve_->u_min() + static_cast<double>(n_) * h_; }

void ForwardDifferenceStepper::reset() noexcept {
  n_ = 0;
  anchor(0);
}

void ForwardDifferenceStepper::anchor(std::size_t span_index) noexcept {
  const auto& spans = curve_->spans();
  span_ = span_index;
  const SpanPolynomial& s = spans[span_index];
  const double a = u() - s.u_start;
  for (auto& v : hi_) v.setZero();
  for (auto& v : lo_) v.setZero();
  for (int axis = 0; axis < dims_; ++axis) {
    PolyCoeffs c{};
    for (int k = 0; k <= p_; ++k) c[static_cast<std::size_t>(k)] = s.coeff[static_cast<std::size_t>(k)][axis];
    const PolyCoeffs D = initial_differences(c, p_, a, h_);
    for (int k = 0; k <= p_; ++k) hi_[static_cast<std::size_t>(k)][axis] = D[static_cast<std::size_t>(k)];
  }
  // First cycle that falls into a later span: the smallest n with u_n >= u_end.
  if (span_index + 1 >= spans.size()) {
    next_anchor_n_ = cycles_ + 1;
    return;
  }
  const double u0 = curve_->u_min();
  long m = static_cast<long>(std::ceil((s.u_end - u0) / h_));
  while (m > 0 && u0 + static_cast<double>(m - 1) * h_ >= s.u_end) --m;
  while (u0 + static_cast<double>(m) * h_ < s.u_end) ++m;
  next_anchor_n_ = m;
}

template <bool kCompensated>
void ForwardDifferenceStepper::add_differences() noexcept {
  for (int k = 0; k < p_; ++k) {
    const auto kk = static_cast<std::size_t>(k);
    if constexpr (!kCompensated) {
      hi_[kk] += hi_[kk + 1];
    } else {
      // TwoSum of the high parts, then fold in the low parts and renormalise (Fast2Sum).
      const Eigen::Vector4d s = hi_[kk] + hi_[kk + 1];
      const Eigen::Vector4d bb = s - hi_[kk];
      const Eigen::Vector4d e = (hi_[kk] - (s - bb)) + (hi_[kk + 1] - bb);
      const Eigen::Vector4d l = lo_[kk] + lo_[kk + 1] + e;
      const Eigen::Vector4d r = s + l;
      lo_[kk] = l - (r - s);
      hi_[kk] = r;
    }
  }
}

bool ForwardDifferenceStepper::step() noexcept {
  if (n_ >= cycles_) return false;
  ++n_;
  if (n_ >= next_anchor_n_) {
    // Re-anchor exactly: find the span of u_n (spans shorter than h may be skipped).
    anchor(curve_->span_index(u()));
  } else if (summation_ == Summation::plain) {
    add_differences<false>();
  } else {
    add_differences<true>();
  }
  return true;
}

Vec3 ForwardDifferenceStepper::point() const noexcept {
  const Eigen::Vector4d q = hi_[0] + lo_[0];
  if (dims_ == 4) return q.head<3>() / q[3];
  return q.head<3>();
}

PolyCoeffs ForwardDifferenceStepper::differences(int axis) const noexcept {
  PolyCoeffs d{};
  for (int k = 0; k <= p_; ++k) d[static_cast<std::size_t>(k)] = hi_[static_cast<std::size_t>(k)][axis];
  return d;
}

}  // namespace kontur
