#pragma once
// A circular arc in any plane of space, optionally with a linear rise along the plane's normal
// (a helix), as a Curve: C(u) = centre + r(u) (cos(phi) e1 + sin(phi) e2) + rise u n, phi = sweep u,
// r(u) = R + dR u, u in [0, 1]. dR (normally 0) lets a G2/G3 arc whose programmed end lies up to the
// radius tolerance off its circle end exactly there (a slight spiral, as LinuxCNC does). It is the geometry of G2/G3 arcs and helices and of the circle through three
// points; the frame (centre, e1, e2, n) is the relative frame of the seed monograph.
#include <kontur/geometry/curve.hpp>

namespace kontur {

/// Frame of a circle: origin at the centre, e1 towards the start point, n the plane's normal,
/// e2 = n x e1 (right-handed); the motion is counter-clockwise about n for a positive sweep.
struct CircleFrame {
  Vec3 centre = Vec3::Zero();    ///< centre [mm]
  Vec3 e1 = Vec3::UnitX();       ///< unit vector from the centre to the start point
  Vec3 e2 = Vec3::UnitY();       ///< unit vector, n x e1
  Vec3 normal = Vec3::UnitZ();   ///< unit normal of the plane
};

class HelixArc final : public Curve {
public:
  /// @param frame  orthonormal frame (checked to 1e-9; throws InputError otherwise)
  /// @param radius_mm  radius R > 0 [mm]
  /// @param sweep_rad  swept angle [rad], > 0 (counter-clockwise about frame.normal); may exceed 2 pi
  /// @param rise_mm  displacement along frame.normal from start to end [mm] (0 for a plane arc)
  /// @param radius_change_mm  end radius minus start radius [mm] (0 for a circle; |dR| < R)
  HelixArc(const CircleFrame& frame, double radius_mm, double sweep_rad, double rise_mm = 0.0,
           double radius_change_mm = 0.0);

  [[nodiscard]] double u_min() const noexcept override { return 0.0; }
  [[nodiscard]] double u_max() const noexcept override { return 1.0; }
  [[nodiscard]] Derivatives derivatives(double u, int order) const noexcept override;
  [[nodiscard]] std::vector<double> breakpoints() const override { return {0.0, 1.0}; }

  [[nodiscard]] const CircleFrame& frame() const noexcept { return frame_; }
  [[nodiscard]] double radius_mm() const noexcept { return radius_; }
  [[nodiscard]] double sweep_rad() const noexcept { return sweep_; }
  [[nodiscard]] double rise_mm() const noexcept { return rise_; }
  /// End radius minus start radius [mm].
  [[nodiscard]] double radius_change_mm() const noexcept { return radius_change_; }
  /// Length [mm]: exactly sqrt((R sweep)^2 + rise^2) when dR = 0, else by adaptive Gauss-Kronrod.
  [[nodiscard]] double length_mm() const noexcept;
  /// Point at angle phi [rad] from the start (and the matching rise).
  [[nodiscard]] Vec3 point_at_angle(double phi_rad) const noexcept;
  /// Distance [mm] from p to the part of the arc between the parameters u0 <= u1. On a circle (no
  /// rise, no change of radius) exactly: from p's angle about the centre, the foot on the circle
  /// where that angle lies within the part, else the nearer end; on a slight spiral
  /// (tolerances::arc_slight_spiral_slope) the same way, to its point at p's angle (at most 4.5e-4
  /// of the distance above it). On a helix or another spiral, the nearest of the local minima in
  /// each turn about p's angle (on a helix within the window where the squared distance is convex,
  /// a spiral's turn in tolerances::arc_distance_spiral_parts parts), each by Newton's method on
  /// (C(u) - p) . C'(u) = 0 kept inside a sign bracket, the turns in the order of their axial
  /// distance from p until it passes the nearest found; always the distance to a point of the part.
  [[nodiscard]] double distance_mm(const Vec3& p, double u0, double u1) const noexcept;
  /// A lower bound [mm] of p's distance from the part between u0 <= u1, without trigonometry: its
  /// distance from the ring that holds the part's points (about the axis, radii between the
  /// part's end radii, heights between its end heights); on a circle the distance to the foot
  /// where p's angle lies within the part.
  [[nodiscard]] double distance_lower_bound_mm(const Vec3& p, double u0, double u1) const noexcept;

private:
  CircleFrame frame_;
  double radius_, sweep_, rise_, radius_change_;
};

/// A curve that is an arc: a HelixArc, or a CurvePiece of one (or of a piece of one), and the range
/// [u0, u1] of the arc's parameter it covers (arc null: some other curve).
struct ArcSpan {
  const HelixArc* arc = nullptr;
  double u0 = 0.0, u1 = 1.0;
};
[[nodiscard]] ArcSpan arc_span(const Curve& curve) noexcept;

}  // namespace kontur
