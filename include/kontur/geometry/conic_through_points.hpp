#pragma once
// Arc of a conic (ellipse, circle, parabola, hyperbola) through five points in space
// (methods.md section 5; seed 001, section 3 and program SOCADI): the relative frame with the
// corrected lambda, the coplanarity check, the coefficients by cofactors, the rotation, the
// classification, the canonical parameters, the focal frame and polar equation
// rho = p / (1 - e cos phi), the focal angles of the points, the direction and the swept focal
// angle. The arc is a ConicArc, a Curve whose parameter is the focal angle swept from r1.
#include <kontur/geometry/curve.hpp>

#include <Eigen/Core>

#include <array>
#include <string>

namespace kontur {

/// The kind of a non-degenerate conic.
enum class ConicType { ellipse, circle, parabola, hyperbola };

/// "ellipse", "circle", "parabola", "hyperbola".
[[nodiscard]] const char* to_string(ConicType type) noexcept;

/// An arc of a conic given by its focal frame and polar equation
/// rho(phi) = p / (1 - e cos phi), phi = phi_start + u, u in [0, sweep] [rad]:
/// C(u) = focus + rho (cos phi x_f + sin phi y_f). Derivatives are analytic.
class ConicArc final : public Curve {
public:
  /// @param focus_mm  the focus, origin of the focal frame [mm]
  /// @param x_axis  unit polar axis (from the focus, away from the near directrix)
  /// @param y_axis  unit vector normal x x_axis (the motion is counter-clockwise from x to y)
  /// @param focal_parameter_mm  p > 0 [mm]
  /// @param eccentricity  e >= 0
  /// @param phi_start_rad  focal angle of the start point [rad]
  /// @param sweep_rad  swept focal angle > 0 [rad]; 1 - e cos phi must stay > 0 on the arc
  /// Throws InputError ("conic-arc") when these do not describe an arc of a conic.
  ConicArc(const Vec3& focus_mm, const Vec3& x_axis, const Vec3& y_axis, double focal_parameter_mm,
           double eccentricity, double phi_start_rad, double sweep_rad);

  [[nodiscard]] double u_min() const noexcept override { return 0.0; }
  [[nodiscard]] double u_max() const noexcept override { return sweep_; }
  [[nodiscard]] Derivatives derivatives(double u, int order) const noexcept override;
  [[nodiscard]] std::vector<double> breakpoints() const override { return {0.0, sweep_}; }

  /// Focal radius rho [mm] at focal angle phi [rad].
  [[nodiscard]] double rho_mm(double phi_rad) const noexcept;
  /// Point in the focal frame (rho cos phi, rho sin phi, 0) at u [mm].
  [[nodiscard]] Vec3 focal_point(double u) const noexcept;

  /// Makes the arc start at `start_mm` and end at `end_mm` exactly: the differences from the
  /// conic's own ends (a few um at most: points rounded off the conic's plane) are spread along
  /// the arc by a quintic smooth step, which leaves the tangent and curvature at both ends as
  /// they were (issue 20, case 8: a CONIC ended 3e-5 mm off its programmed end, and the next move
  /// jumped).
  void pin_ends(const Vec3& start_mm, const Vec3& end_mm) noexcept;
  /// The correction at the start and at the end [mm] (zero unless pin_ends was called).
  [[nodiscard]] const Vec3& start_offset_mm() const noexcept { return start_offset_; }
  [[nodiscard]] const Vec3& end_offset_mm() const noexcept { return end_offset_; }

  [[nodiscard]] const Vec3& focus_mm() const noexcept { return focus_; }
  [[nodiscard]] const Vec3& x_axis() const noexcept { return x_; }
  [[nodiscard]] const Vec3& y_axis() const noexcept { return y_; }
  [[nodiscard]] double focal_parameter_mm() const noexcept { return p_; }
  [[nodiscard]] double eccentricity() const noexcept { return e_; }
  [[nodiscard]] double phi_start_rad() const noexcept { return phi0_; }
  [[nodiscard]] double sweep_rad() const noexcept { return sweep_; }

private:
  Vec3 focus_, x_, y_;
  double p_, e_, phi0_, sweep_;
  Vec3 start_offset_ = Vec3::Zero(), end_offset_ = Vec3::Zero();  // [mm] (pin_ends)
  bool pinned_ = false;
  Vec3 start_ = Vec3::Zero(), end_ = Vec3::Zero();  // the pinned ends [mm]
};

/// Options of the conic fit.
struct ConicOptions {
  /// Largest distance of r4, r5 from the plane of r1, r2, r3 [mm]; 0 means
  /// tolerances::conic_coplanar_relative times the extent of the points.
  double plane_tolerance_mm = 0.0;
};

/// The conic through r1..r5 and everything the program SOCADI reports about it.
struct ConicThroughPoints {
  std::array<Vec3, 5> points;            ///< r1..r5 in the machine frame [mm]
  double extent_mm = 0.0;                ///< largest distance between two given points [mm]

  // ---- relative frame (seed (3.18)-(3.31), with lambda's sign corrected)
  double lambda = 0.0;                   ///< -((r3-r1).(r2-r1)) / |r2-r1|^2
  /// Relative -> machine: origin r1, X along r2 - r1, Y along (r3 - r1) + lambda (r2 - r1),
  /// Z along (r2 - r1) x (r3 - r1).
  Eigen::Matrix4d relative_to_machine = Eigen::Matrix4d::Identity();
  Eigen::Matrix4d machine_to_relative = Eigen::Matrix4d::Identity();  ///< its inverse
  std::array<Vec3, 5> relative_points;   ///< r1..r5 in the relative frame [mm]; z = distance from the plane
  double plane_distance_mm = 0.0;        ///< max |z| of r4, r5 [mm]
  double plane_tolerance_mm = 0.0;       ///< the tolerance it was checked against [mm]

  // ---- equation in the relative frame: A x^2 + B xy + C y^2 + D x + E y = 0 (F = 0, r1 the origin)
  /// A, B, C, D, E by cofactors (x, y in mm), normalised so that the largest of |A| s^2, |B| s^2,
  /// |C| s^2, |D| s, |E| s is 1 (s the extent [mm]).
  std::array<double, 5> coefficients{};
  /// Seed's rotation theta with cot 2 theta = (A - C) / B, in [0, pi/2) [rad] (0 when B = 0).
  double rotation_rad = 0.0;
  /// A', C', D', E' after the rotation (B' = 0).
  std::array<double, 4> rotated_coefficients{};

  // ---- classification and canonical parameters
  ConicType type = ConicType::ellipse;
  double eccentricity = 0.0;             ///< e (0 circle, < 1 ellipse, 1 parabola, > 1 hyperbola)
  double focal_parameter_mm = 0.0;       ///< p = b^2 / a (parabola: distance from focus to directrix) [mm]
  double a_mm = 0.0;                     ///< semi-major (hyperbola: semi-transverse) axis [mm]; 0 for a parabola
  double b_mm = 0.0;                     ///< semi-minor (hyperbola: semi-conjugate) axis [mm]; 0 for a parabola
  double c_mm = 0.0;                     ///< focal distance, centre to focus [mm]; 0 for a parabola
  Vec3 centre = Vec3::Zero();            ///< centre [mm] (ellipse, circle, hyperbola); the vertex for a parabola
  Vec3 vertex = Vec3::Zero();            ///< vertex nearest to the focus used [mm]
  std::array<Vec3, 2> foci;              ///< foci [mm]; a parabola has one (both entries equal)
  /// Angle of the focal axis (direction from the used focus's vertex towards the focus) in the
  /// relative frame, from X towards Y, in (-pi, pi] [rad].
  double axis_angle_rad = 0.0;
  /// Hyperbola: the branch of the five points in the seed's rotated frame, +1 the right (upper)
  /// branch, -1 the left (lower) one; 0 for the other types. Decided once, from r1.
  int branch = 0;

  // ---- focal frame and polar equation rho = p / (1 - e cos phi)
  Vec3 focus = Vec3::Zero();             ///< origin of the focal frame [mm]
  Eigen::Matrix4d focal_to_machine = Eigen::Matrix4d::Identity();
  Eigen::Matrix4d machine_to_focal = Eigen::Matrix4d::Identity();
  std::array<Vec3, 5> focal_points;      ///< r1..r5 in the focal frame [mm]
  std::array<double, 5> focal_angles_rad{};  ///< theta_0j = atan2(y', x') in (0, 2 pi] [rad]
  std::array<double, 5> swept_angles_rad{};  ///< theta_1j, focal angle from r1 to rj, in [0, 2 pi) [rad]
  double theta15_rad = 0.0;              ///< swept focal angle of the arc [rad]

  /// The arc as a Curve (parameter: focal angle swept from r1, u in [0, theta15]).
  [[nodiscard]] ConicArc curve() const;
};

/// Fits the conic through r1..r5 [mm], in order along one arc. Throws InputError for: a
/// non-finite coordinate ("point-finite"), coincident points ("points-coincident"), three
/// collinear points ("points-collinear"), r4 or r5 off the plane ("points-not-coplanar", with the
/// distance and the tolerance), a degenerate conic ("conic-degenerate", naming the kind), points
/// on two branches of a hyperbola ("hyperbola-branches") or not in order along one arc
/// ("points-order").
[[nodiscard]] ConicThroughPoints conic_through_points(const std::array<Vec3, 5>& points,
                                                      const ConicOptions& options = {});

}  // namespace kontur
