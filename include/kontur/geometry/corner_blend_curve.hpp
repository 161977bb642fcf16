#pragma once
// The curve that joins two lines at a corner within a tolerance (the corner blender's blend,
// program/corner_blender.hpp), and the measure the blender sizes it with.
#include <array>
#include <kontur/geometry/curve.hpp>
#include <kontur/geometry/span_polynomial.hpp>
#include <vector>

namespace kontur {

/// Where the inner control points of a corner blend lie: the second and third on each line, at
/// `second` d and `third` d from the corner (1 > second > third >= 0; the first is the blend's end,
/// at d). The default is the quintic whose control points are equally spaced (2/3, 1/3).
struct CornerBlendShape {
  double second = 2.0 / 3.0;
  double third = 1.0 / 3.0;
};

/// The shape of the one-parameter family the corner blender chooses from (`third` in
/// [tolerances::blend_shape_third_min, blend_shape_third_max], `second` = 0.57 + 0.2 `third`): within
/// 5 % of the fastest quintic of this form at turns of 2 .. 120 degrees, on machines whose jerk is
/// 10 .. 10^4 times their acceleration per second (docs/planner.md, "Corner blending").
[[nodiscard]] CornerBlendShape corner_blend_shape(double third) noexcept;

/// The blend curve of a corner P between the incoming direction t1 and the outgoing t2 (unit
/// vectors), trimmed by d [mm] on each line: the quintic Bezier with control points
/// Q_0..2 = P - d (1, s, e) t1 and Q_3..5 = P + d (e, s, 1) t2 (s, e: the shape's `second` and
/// `third`). B(0) = P - d t1 and B(1) = P + d t2 exactly (the end values of the Bernstein form), and B' and B'' lie along the line at
/// each end (the curvature is 0 there: three control points lie on each line). Its curvature
/// rises from 0 at each end: the smaller e, the more slowly (a smaller curvature change, for the
/// jerk); the larger s, the lower its peak (for the acceleration).
class CornerBlendCurve final : public Curve {
 public:
  CornerBlendCurve(const Vec3& corner, const Vec3& t1, const Vec3& t2, double d_mm,
                   const CornerBlendShape& shape = {}) noexcept;
  [[nodiscard]] double u_min() const noexcept override { return 0.0; }
  [[nodiscard]] double u_max() const noexcept override { return 1.0; }
  [[nodiscard]] Derivatives derivatives(double u, int order) const noexcept override;
  [[nodiscard]] std::vector<double> breakpoints() const override { return {0.0, 1.0}; }
  /// The programmed corner point P [mm].
  [[nodiscard]] const Vec3& corner() const noexcept { return corner_; }
  /// The trim distance d on each line [mm].
  [[nodiscard]] double trim_mm() const noexcept { return d_; }

 private:
  Vec3 corner_;
  double d_;
  SpanPolynomial span_;      // the quintic in the power basis on [0, 1] (Horner: span_polynomial.hpp)
  std::array<Vec3, 4> end_;  // B(1) and its derivatives there, from the last control points (exact)
};

/// Largest distance [mm] of `curve` from the union of the segments [before, corner] and
/// [corner, after]: dense samples (tolerances::blend_deviation_samples per curve) and a
/// golden-section search around the largest. (The checker measures blends its own way.)
[[nodiscard]] double corner_deviation(const Curve& curve, const Vec3& before, const Vec3& corner, const Vec3& after);

/// Largest distance of the blend with d = 1 mm from the two lines of the corner, for the turn
/// between unit directions t1 and t2 [mm per mm of d]. The deviation of a blend is d times this.
[[nodiscard]] double unit_blend_deviation(const Vec3& t1, const Vec3& t2, const CornerBlendShape& shape = {});

}  // namespace kontur
