#pragma once
// NURBS and B-spline curves of degree 1..9 in 3-D with clamped, arbitrary (non-uniform) knot
// vectors and optional weights. Evaluation of the point and the first three derivatives by span
// finding and the basis-function derivative algorithm (Piegl & Tiller A2.1, A2.3, A4.2), without
// allocation.
#include <kontur/geometry/curve.hpp>

#include <optional>
#include <string>
#include <vector>

namespace kontur {

/// The definition of a curve as a user gives it: degree, knots, control points, weights.
struct NurbsData {
  int degree = 3;                 ///< polynomial degree p (order p + 1), 1..9
  std::vector<double> knots;      ///< knot vector, points + degree + 1 values, clamped
  std::vector<Vec3> points;       ///< control points [mm]
  std::vector<double> weights;    ///< weights > 0, one per point; empty = all 1 (B-spline)
};

/// A broken rule of a curve definition.
struct NurbsProblem {
  std::string rule;     ///< stable short name ("knot-count", "knots-decreasing", ...)
  std::string message;  ///< what is wrong, naming the field, index and value
};

/// Checks every rule of a curve definition: degree 1..9; at least degree + 1 points;
/// knot count = points + degree + 1; knots finite and non-decreasing; end multiplicity
/// = degree + 1; inner multiplicity <= degree; weights (if given) one per point, finite, > 0;
/// points finite; a parameter range of non-zero length. Returns the first problem found.
[[nodiscard]] std::optional<NurbsProblem> validate(const NurbsData& data);

/// A validated NURBS curve.
class NurbsCurve final : public Curve {
public:
  /// Validates `data`; throws InputError naming the rule and the value if it is invalid.
  explicit NurbsCurve(NurbsData data);

  [[nodiscard]] double u_min() const noexcept override;
  [[nodiscard]] double u_max() const noexcept override;
  [[nodiscard]] Derivatives derivatives(double u, int order) const noexcept override;
  [[nodiscard]] Derivatives derivatives_left(double u, int order) const noexcept override;
  /// Distinct knots (span boundaries) from u_min to u_max.
  [[nodiscard]] std::vector<double> breakpoints() const override;

  /// Degree p.
  [[nodiscard]] int degree() const noexcept { return data_.degree; }
  /// Knot vector.
  [[nodiscard]] const std::vector<double>& knots() const noexcept { return data_.knots; }
  /// Control points [mm].
  [[nodiscard]] const std::vector<Vec3>& points() const noexcept { return data_.points; }
  /// Weights (all 1 for a B-spline).
  [[nodiscard]] const std::vector<double>& weights() const noexcept { return weights_; }
  /// True if the weights are not all equal (the curve is not a polynomial on a span).
  [[nodiscard]] bool rational() const noexcept { return rational_; }
  /// The definition the curve was built from.
  [[nodiscard]] const NurbsData& data() const noexcept { return data_; }
  /// Index i of the knot span [u_i, u_{i+1}) containing u (the last non-empty span for u_max).
  [[nodiscard]] int find_span(double u) const noexcept;
  /// Like find_span, but at an inner knot the span that ends there (the limit from the left).
  [[nodiscard]] int find_span_left(double u) const noexcept;
  /// Diagonal of the control points' bounding box [mm]: the curve's scale for relative errors.
  [[nodiscard]] double extent() const noexcept;

private:
  [[nodiscard]] Derivatives evaluate(double u, int span, int order) const noexcept;

  NurbsData data_;
  std::vector<double> weights_;
  bool rational_ = false;
};

}  // namespace kontur
