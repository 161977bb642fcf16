#pragma once
// Curve length: the Simpson-Runge method of seed 000 (both of its schemes) and Kontur's default,
// adaptive Gauss-Kronrod (7/15) per span, plus the arc-length table that inverts it, u(s).
#include <kontur/geometry/curve.hpp>
#include <kontur/tolerances.hpp>

#include <vector>

namespace kontur {

/// A computed length with its cost and error estimate.
struct LengthResult {
  double length_mm = 0.0;          ///< the length [mm] (Simpson: with Runge's correction)
  double error_estimate_mm = 0.0;  ///< estimated absolute error [mm]
  long evaluations = 0;            ///< evaluations of the parametric speed |C'(u)|
  bool converged = false;          ///< the requested tolerance was met
  /// Simpson's whole-curve scheme: (n intervals, raw Simpson value l_n [mm]) per halving,
  /// as in the seed's tables. Empty for the other methods.
  std::vector<std::pair<long, double>> history;
};

/// The two schemes of seed 000.
enum class SimpsonScheme {
  per_span,     ///< Simpson-Runge on each span, then the sum (scheme 1)
  whole_curve,  ///< over the whole parameter range, halving the step (scheme 2)
};

/// Seed 000: composite Simpson with n = 2, 4, 8, ... intervals, stopped by Runge's rule
/// |l_2n - l_n| / 15 < relative_tolerance * |l_2n|, result l_2n + (l_2n - l_n) / 15.
/// Values of earlier halvings are reused, so each halving evaluates only the new points.
[[nodiscard]] LengthResult simpson_runge_length(const Curve& curve, SimpsonScheme scheme,
                                                double relative_tolerance = tolerances::simpson_relative,
                                                int max_halvings = tolerances::simpson_max_halvings);

/// Kontur's default: on each piece between breakpoints, the nested Gauss-Kronrod-Patterson
/// rules (7, 15, 31, 63 points, each reusing the evaluations of the one before), stopping at the
/// first level whose difference to the previous one is below relative_tolerance of the value,
/// and bisecting a panel that 63 points do not settle. relative_tolerance is raised to at least
/// tolerances::min_length_relative.
[[nodiscard]] LengthResult gauss_kronrod_length(const Curve& curve,
                                                double relative_tolerance = tolerances::length_relative);
/// The same on [u0, u1] (u0 <= u1), splitting at the curve's breakpoints inside.
[[nodiscard]] LengthResult gauss_kronrod_length(const Curve& curve, double u0, double u1,
                                                double relative_tolerance = tolerances::length_relative);

/// Length [mm] of [u0, u1] by the fixed rule of one level of the nested rules (level 0: the
/// 7-point Gauss rule; 1..3: 15, 31, 63 points), with no error control: an estimate for a short
/// interval whose speed is smooth (the arc-length table's partial intervals, the checker's bounds).
[[nodiscard]] double fixed_rule_length(const Curve& curve, double u0, double u1, int level = 0) noexcept;

/// Length [mm] of the whole curve by the default method.
[[nodiscard]] double length(const Curve& curve);

/// Arc length s(u) and its inverse u(s), from a table of the adaptive quadrature's nodes built
/// once; a query is a binary search and a few safeguarded Newton steps on one table interval. On a
/// curve of constant speed (Curve::constant_speed: a line) s(u) is linear and both are exact.
/// Keeps a reference to the curve, which must outlive the table.
class ArcLengthTable {
public:
  explicit ArcLengthTable(const Curve& curve, double relative_tolerance = tolerances::length_relative);

  /// Total length [mm].
  [[nodiscard]] double length_mm() const noexcept { return s_.back(); }
  /// Arc length [mm] from u_min to u (u clamped to the range).
  [[nodiscard]] double s_of_u(double u) const noexcept;
  /// Parameter at arc length s [mm] (s clamped to [0, length]); relative accuracy 1e-13 of the
  /// length. Allocation-free.
  [[nodiscard]] double u_of_s(double s_mm) const noexcept;
  /// The same, starting Newton from `u_hint` when it lies in the table interval of s (a good
  /// prediction, e.g. a Taylor step, saves iterations).
  [[nodiscard]] double u_of_s(double s_mm, double u_hint) const noexcept;
  /// Parameter at arc length s_to [mm], given a point (u_from, s_from) on the curve a short way
  /// before it (s_from <= s_to): when both lie in one table interval (or u_from in an earlier
  /// one: then the step starts at s_to's interval's start), Newton integrates only the step from
  /// u_from, starting at the third-order Taylor series of u(s) at u_from: usually one 7-point
  /// Gauss rule on the step (checked against a degree-7 companion that uses the step's ends;
  /// the nested rules from 15 points on when they disagree) and one Newton step with its
  /// second-order term. The residual is within tolerances::inverse_step_relative of the step.
  /// `u_hint` is the start where the series does not apply; otherwise it is u_of_s(s_to, u_hint).
  /// The stepping of a servo cycle. Allocation-free.
  [[nodiscard]] double u_after(double u_from, double s_from, double s_to, double u_hint) const noexcept;
  /// The same for a stepping that carries its error: `s_from_error` [mm] is the arc length at
  /// u_from minus s_from (what an earlier step reported), and `*s_to_error` gets the arc length
  /// at the result minus s_to (its residual and the rounding of u; 0 where the step restarted
  /// from the table). Kept apart from s, these small numbers keep their precision where s is
  /// large (ulp(900000 mm) = 1.2e-10 mm), so that the rounding of u does not add up over the
  /// millions of steps of a long move.
  [[nodiscard]] double u_after(double u_from, double s_from, double s_to, double u_hint, double s_from_error,
                               double* s_to_error) const noexcept;
  /// Number of table intervals.
  [[nodiscard]] std::size_t intervals() const noexcept { return u_.size() - 1; }
  /// Evaluations of |C'| spent building the table.
  [[nodiscard]] long build_evaluations() const noexcept { return build_evaluations_; }

private:
  const Curve* curve_;
  std::vector<double> u_;      // interval ends, u_[0] = u_min
  std::vector<double> s_;      // arc length at u_[k] [mm]
  std::vector<unsigned char> level_;  // Patterson level accepted on interval k
  double speed_ = 0.0;  // the curve's constant speed [mm per parameter unit], else 0 (the table's one interval)
  long build_evaluations_ = 0;
};

}  // namespace kontur
