#pragma once
// Every numerical tolerance of Kontur, in one place, with what it means and how it relates to
// the others. Lengths are in [mm] unless stated; "relative" means relative to the quantity's
// own scale (a curve's extent, a length, a parameter range).

namespace kontur::tolerances {

// ---- geometry of curves
/// Maximum supported NURBS degree (order 10).
inline constexpr int max_degree = 9;
/// Largest derivative order evaluated by Curve::derivatives (point, first, second, third).
inline constexpr int max_derivative = 3;
/// Two knots closer than this, relative to the parameter range, count as equal when the end
/// multiplicities of a clamped knot vector are checked.
inline constexpr double knot_equal_relative = 1e-12;

// ---- curve length
/// Default relative accuracy of Kontur's adaptive Gauss-Kronrod length.
inline constexpr double length_relative = 1e-13;
/// Smallest relative accuracy a length may be asked for: a panel's error estimate never goes
/// below 50 machine epsilons of its value (rounding of the sum), so a smaller request could
/// never be met. Requests below it are raised to it.
inline constexpr double min_length_relative = 2e-14;
/// Default relative accuracy asked of the Simpson-Runge method (seed 000).
inline constexpr double simpson_relative = 1e-10;
/// Largest number of interval halvings of the Simpson-Runge method (2^24 intervals).
inline constexpr int simpson_max_halvings = 24;
/// Deepest bisection of an adaptive Gauss-Kronrod interval.
inline constexpr int gauss_kronrod_max_depth = 40;
/// Relative accuracy of the inverse u(s) of the arc-length table.
inline constexpr double inverse_length_relative = 1e-13;
/// Largest number of Newton iterations of u(s); each falls back to bisection when it leaves the
/// bracket, so the iteration always ends.
inline constexpr int inverse_length_max_iterations = 60;

// ---- forward differences (seed 002)
/// Drift of the forward-difference stepper after 10^6 steps, relative to the curve's extent,
/// that the tests and the documentation guarantee.
inline constexpr double forward_difference_drift_relative = 1e-9;

}  // namespace kontur::tolerances
