#pragma once
// The upper level of seed 002: every non-empty knot span of a NURBS as a power-basis polynomial
// per coordinate. Rational curves are kept in homogeneous coordinates (w x, w y, w z, w), which
// are polynomials on a span; the curve point is their quotient.
#include <kontur/geometry/curve.hpp>
#include <kontur/geometry/nurbs.hpp>
#include <kontur/tolerances.hpp>

#include <Eigen/Core>
#include <array>
#include <atomic>
#include <cstddef>
#include <vector>

namespace kontur {

/// Coefficients of a polynomial of degree <= 9, ascending: c[0] + c[1] x + ... + c[9] x^9.
using PolyCoeffs = std::array<double, tolerances::max_degree + 1>;

/// Value of a polynomial (ascending coefficients, `degree` + 1 used) at x, by Horner's scheme.
[[nodiscard]] double evaluate_polynomial(const PolyCoeffs& c, int degree, double x) noexcept;
/// The same polynomial expressed in the variable (x - shift): returns d with
/// sum d_k (x - shift)^k = sum c_k x^k. Exact for dyadic values.
[[nodiscard]] PolyCoeffs shift_polynomial(const PolyCoeffs& c, int degree, double shift) noexcept;

/// The polynomial pieces of one non-empty knot span [u_start, u_end).
struct SpanPolynomial {
  double u_start = 0.0;  ///< first parameter of the span
  double u_end = 0.0;    ///< end parameter of the span
  int knot_index = 0;    ///< i with knots[i] = u_start < knots[i+1] = u_end
  int degree = 0;        ///< polynomial degree p
  bool rational = false; ///< true if the weight polynomial is not constant 1
  /// Homogeneous coefficients in the local variable t = u - u_start: coeff[k] = coefficient of
  /// t^k of (w x, w y, w z, w). For a non-rational curve w = 1.
  /// (Eigen vectors are not zeroed by value-initialisation, hence the explicit zero.)
  std::array<Eigen::Vector4d, tolerances::max_degree + 1> coeff = [] {
    std::array<Eigen::Vector4d, tolerances::max_degree + 1> zero;
    for (auto& v : zero) v.setZero();
    return zero;
  }();

  /// Coefficients of coordinate `axis` (0 = x, 1 = y, 2 = z, 3 = w) as a polynomial in
  /// (u - origin). origin = 0 gives the seed's form in the global parameter u (its Table 2);
  /// origin = u_start gives the local form, which is better conditioned.
  [[nodiscard]] PolyCoeffs coefficients(int axis, double origin) const noexcept;
  /// Point and derivatives up to `order` at u (not clamped to the span).
  [[nodiscard]] Derivatives derivatives(double u, int order) const noexcept;
};

/// The p + 1 basis functions N_{i-p,p} .. N_{i,p} that are non-zero on span `knot_index` (knots[i] <
/// knots[i+1]) as polynomials in (u - origin), by the Cox-de Boor recursion on polynomials.
[[nodiscard]] std::vector<PolyCoeffs> basis_polynomials(const std::vector<double>& knots, int degree,
                                                        int knot_index, double origin);

/// A NURBS curve converted to span polynomials: evaluates point and derivatives by Horner's
/// scheme on the span's polynomial. The fast representation used for length and stepping.
class SpanPolynomialCurve final : public Curve {
public:
  /// Converts every non-empty span of `curve`.
  explicit SpanPolynomialCurve(const NurbsCurve& curve);

  [[nodiscard]] double u_min() const noexcept override { return spans_.front().u_start; }
  [[nodiscard]] double u_max() const noexcept override { return spans_.back().u_end; }
  [[nodiscard]] Derivatives derivatives(double u, int order) const noexcept override;
  [[nodiscard]] Derivatives derivatives_left(double u, int order) const noexcept override;
  [[nodiscard]] std::vector<double> breakpoints() const override;
  /// degree(), or -1 if rational.
  [[nodiscard]] int polynomial_degree() const noexcept override { return rational_ ? -1 : degree_; }

  /// The spans, in parameter order.
  [[nodiscard]] const std::vector<SpanPolynomial>& spans() const noexcept { return spans_; }
  /// Index into spans() of the span containing u (the last span for u_max).
  [[nodiscard]] std::size_t span_index(double u) const noexcept;
  /// True if the curve is rational.
  [[nodiscard]] bool rational() const noexcept { return rational_; }
  /// Degree of the polynomials.
  [[nodiscard]] int degree() const noexcept { return degree_; }

private:
  std::vector<SpanPolynomial> spans_;
  std::vector<double> starts_;  // the spans' u_start, searched by span_index (a compact array)
  // The span span_index found last, tried first: a move of a smoothed run is evaluated many times
  // within one span of a curve of thousands. Only a hint (relaxed, any thread may replace it).
  struct LastSpan {
    mutable std::atomic<std::size_t> index{0};
    LastSpan() = default;
    LastSpan(const LastSpan& o) noexcept : index(o.index.load(std::memory_order_relaxed)) {}
    LastSpan& operator=(const LastSpan& o) noexcept {
      index.store(o.index.load(std::memory_order_relaxed), std::memory_order_relaxed);
      return *this;
    }
  } last_;
  int degree_ = 0;
  bool rational_ = false;
};

}  // namespace kontur
