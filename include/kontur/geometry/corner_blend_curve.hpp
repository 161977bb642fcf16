#pragma once
// The curve that joins two lines at a corner within a tolerance (the corner blender's blend,
// program/corner_blender.hpp), and the measure the blender sizes it with.
#include <kontur/geometry/curve.hpp>
#include <vector>

namespace kontur {

/// The blend curve of a corner P between the incoming direction t1 and the outgoing t2 (unit
/// vectors), trimmed by d [mm] on each line: B(u) = P + d (alpha(u) t1 + beta(u) t2), u in [0, 1],
/// with alpha = (-3 + 5u - 5u^4 + 3u^5) / 3 and beta = (10u^3 - 10u^4 + 3u^5) / 3: the quintic
/// Bezier with Q_k = P - d (1 - k/3) t1 (k = 0..2) and Q_k = P + d (k - 2) / 3 t2 (k = 3..5).
/// B(0) = P - d t1, B(1) = P + d t2, B' = 5d/3 t1 and 5d/3 t2 there, B'' = 0 at both ends (exactly:
/// the polynomials have integer coefficients).
class CornerBlendCurve final : public Curve {
 public:
  CornerBlendCurve(const Vec3& corner, const Vec3& t1, const Vec3& t2, double d_mm) noexcept
      : corner_(corner), t1_(t1), t2_(t2), d_(d_mm) {}
  [[nodiscard]] double u_min() const noexcept override { return 0.0; }
  [[nodiscard]] double u_max() const noexcept override { return 1.0; }
  [[nodiscard]] Derivatives derivatives(double u, int order) const noexcept override;
  [[nodiscard]] std::vector<double> breakpoints() const override { return {0.0, 1.0}; }
  /// The programmed corner point P [mm].
  [[nodiscard]] const Vec3& corner() const noexcept { return corner_; }
  /// The trim distance d on each line [mm].
  [[nodiscard]] double trim_mm() const noexcept { return d_; }

 private:
  Vec3 corner_, t1_, t2_;
  double d_;
};

/// Largest distance [mm] of `curve` from the union of the segments [before, corner] and
/// [corner, after]: dense samples (tolerances::blend_deviation_samples per curve) and a
/// golden-section search around the largest. (The checker measures blends its own way.)
[[nodiscard]] double corner_deviation(const Curve& curve, const Vec3& before, const Vec3& corner, const Vec3& after);

/// Largest distance of the blend with d = 1 mm from the two lines of the corner, for the turn
/// between unit directions t1 and t2 [mm per mm of d]. The deviation of a blend is d times this.
[[nodiscard]] double unit_blend_deviation(const Vec3& t1, const Vec3& t2);

}  // namespace kontur
