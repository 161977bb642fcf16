#pragma once
// The curve that joins the end of one curve to the start of another within a tolerance where
// they meet at a corner or with a jump of curvature (the corner blender's blend of a junction
// with an arc, program/corner_blender.hpp), and the measure the blender sizes it with.
#include <kontur/geometry/curve.hpp>
#include <kontur/tolerances.hpp>
#include <array>
#include <vector>

namespace kontur {

/// Point, unit tangent and curvature vector [1/mm] of a curve at one end of a transition.
struct CurveEnd {
  Vec3 point = Vec3::Zero();      ///< [mm]
  Vec3 tangent = Vec3::UnitX();   ///< unit
  Vec3 curvature = Vec3::Zero();  ///< curvature vector K = dT/ds [1/mm]
};

/// The quintic Hermite curve B(u), u in [0, 1], from `from` to `to` that takes each end's point,
/// tangent and curvature: B' = lambda t and B'' = lambda^2 K at both ends, lambda the chord
/// |to - from| [mm] times `tangent_scale`. Curvature-continuous with the two curves it joins (G2),
/// so the speed need not drop for a jump of acceleration where it starts and ends; the scale shapes
/// how its curvature runs between them (the corner blender chooses it: a larger one lets the
/// curvature rise more slowly from each end).
class TransitionCurve final : public Curve {
 public:
  TransitionCurve(const CurveEnd& from, const CurveEnd& to, double tangent_scale = 1.0) noexcept;
  [[nodiscard]] double u_min() const noexcept override { return 0.0; }
  [[nodiscard]] double u_max() const noexcept override { return 1.0; }
  [[nodiscard]] Derivatives derivatives(double u, int order) const noexcept override;
  [[nodiscard]] std::vector<double> breakpoints() const override { return {0.0, 1.0}; }
  [[nodiscard]] int polynomial_degree() const noexcept override { return 5; }

 private:
  std::array<Vec3, 6> c_;  // monomial coefficients in u [mm]
};

/// Point, unit tangent and curvature vector from a curve's derivatives (order 2 at least).
[[nodiscard]] CurveEnd curve_end(const Derivatives& d);
/// The end of `curve` at u: point, unit tangent and curvature vector (the limit from the left
/// when `left`).
[[nodiscard]] CurveEnd curve_end(const Curve& curve, double u, bool left);

/// Largest distance [mm] of `curve` from the union of the pieces `a` and `b` (each point's by
/// PieceDistance): `samples` + 1 samples and a golden-section search around the largest
/// (sampled_maximum).
[[nodiscard]] double curves_deviation(const Curve& curve, const Curve& a, const Curve& b,
                                      int samples = tolerances::blend_arc_deviation_samples);

}  // namespace kontur
