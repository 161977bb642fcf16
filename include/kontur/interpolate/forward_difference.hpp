#pragma once
// The lower level of seed 002: real-time evaluation of span polynomials by forward differences,
// p additions per coordinate per servo cycle, re-anchored exactly at every span boundary.
#include <kontur/geometry/span_polynomial.hpp>


namespace kontur {

/// Initial value and forward differences D0 = q(0), D1 = q(1) - q(0), ..., Dp of
/// q(m) = P(a + h m), where P has ascending coefficients `c` of degree `degree` in its variable.
/// (For the seed's cubic: D1 = a(3n^2 + 3n + 1) + b(2n + 1) + c, D2 = a(6n + 6) + 2b, D3 = 6a.)
[[nodiscard]] PolyCoeffs initial_differences(const PolyCoeffs& c, int degree, double a, double h) noexcept;

/// How the stepper adds its differences.
enum class Summation {
  plain,        ///< one floating-point addition per difference: the seed's p additions
  compensated,  ///< each difference kept as an unevaluated sum of two doubles (error-free
                ///< transformation): about 4 times the flops, drift at the rounding level
};

/// Steps a curve's span polynomials at a constant parameter step h: u_n = u_min + n h.
/// Construction and re-anchoring (at each span change) compute the differences; step() only adds.
/// Allocation-free after construction; step() is noexcept.
class ForwardDifferenceStepper {
public:
  /// @param curve  span polynomials (must outlive the stepper)
  /// @param h  parameter step per cycle, > 0
  /// @param summation  plain (seed) or compensated
  ForwardDifferenceStepper(const SpanPolynomialCurve& curve, double h, Summation summation = Summation::plain);

  /// Back to n = 0.
  void reset() noexcept;
  /// Advances one cycle: returns false (and stays) when u_{n+1} would pass u_max.
  bool step() noexcept;
  /// Cycle number n.
  [[nodiscard]] long n() const noexcept { return n_; }
  /// Parameter u_n = u_min + n h.
  [[nodiscard]] double u() const noexcept;
  /// Number of cycles in the whole curve: the largest n with u_n <= u_max.
  [[nodiscard]] long cycles() const noexcept { return cycles_; }
  /// Current point [mm] (homogeneous coordinates divided by w for a rational curve).
  [[nodiscard]] Vec3 point() const noexcept;
  /// Current value and differences D0..Dp of coordinate `axis` (0..3; 3 = w); entries above
  /// degree() are zero.
  [[nodiscard]] PolyCoeffs differences(int axis) const noexcept;
  /// Degree p of the polynomials (number of differences).
  [[nodiscard]] int degree() const noexcept { return p_; }
  /// Index of the current span.
  [[nodiscard]] std::size_t span() const noexcept { return span_; }

private:
  void anchor(std::size_t span_index) noexcept;
  template <bool kCompensated>
  void add_differences() noexcept;

  const SpanPolynomialCurve* curve_;
  double h_;
  Summation summation_;
  int p_;
  int dims_;  // 3, or 4 for rational curves
  long n_ = 0;
  long cycles_ = 0;
  long next_anchor_n_ = 0;  // first n of the next span
  std::size_t span_ = 0;
  // Differences by order: hi_[k] = (D_k x, D_k y, D_k z, D_k w); lo_[k] their low parts
  // (compensated summation only). One vector addition per order and cycle.
  std::array<Eigen::Vector4d, tolerances::max_degree + 1> hi_;
  std::array<Eigen::Vector4d, tolerances::max_degree + 1> lo_;
};

}  // namespace kontur
