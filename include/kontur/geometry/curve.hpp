#pragma once
// The interface every geometric curve of Kontur implements (NURBS, span polynomials, lines,
// circles, conics), so that length, u(s), planning and interpolation treat all of them alike.
#include <Eigen/Core>
#include <Eigen/Geometry>  // cross products of Vec3
#include <array>
#include <vector>

namespace kontur {

/// A point or a vector in space [mm].
using Vec3 = Eigen::Vector3d;

/// Point and derivatives of a curve at one parameter value.
/// d[0] = C(u) [mm], d[1] = C'(u), d[2] = C''(u), d[3] = C'''(u) (per parameter unit).
/// Entries above the order that was asked for are left zero.
struct Derivatives {
  std::array<Vec3, 4> d{Vec3::Zero(), Vec3::Zero(), Vec3::Zero(), Vec3::Zero()};
  [[nodiscard]] const Vec3& operator[](int k) const noexcept { return d[static_cast<std::size_t>(k)]; }
  [[nodiscard]] Vec3& operator[](int k) noexcept { return d[static_cast<std::size_t>(k)]; }
};

/// A regular parametric curve C(u), u in [u_min, u_max].
class Curve {
public:
  virtual ~Curve() = default;
  /// Start of the parameter range.
  [[nodiscard]] virtual double u_min() const noexcept = 0;
  /// End of the parameter range.
  [[nodiscard]] virtual double u_max() const noexcept = 0;
  /// Point and derivatives up to `order` (0..3) at u; u is clamped to the range. Never allocates.
  [[nodiscard]] virtual Derivatives derivatives(double u, int order) const noexcept = 0;
  /// Point and derivatives as the limit from the left at u. Differs from derivatives() only at
  /// a breakpoint where the curve is not smooth (a C0 knot): there derivatives() gives the
  /// right-hand piece and this the left-hand one, so that a piece [a, b] is integrated with its
  /// own derivative at b.
  [[nodiscard]] virtual Derivatives derivatives_left(double u, int order) const noexcept {
    return derivatives(u, order);
  }
  /// Parameter values where the curve may be less smooth (span boundaries), sorted, including
  /// u_min and u_max. Length and u(s) integrate piece by piece between them.
  [[nodiscard]] virtual std::vector<double> breakpoints() const = 0;
  /// The degree of the curve's polynomial in u between each two breakpoints where it is one (not
  /// rational), else -1 (unknown). Lets a search bound the curve between its samples (Markov's
  /// inequality: stationary_points).
  [[nodiscard]] virtual int polynomial_degree() const noexcept { return -1; }
  /// |C'(u)| [mm per parameter unit] where it is the same all along the curve and known exactly (a
  /// line: its length), else 0. Lets the arc-length table be exact and linear.
  [[nodiscard]] virtual double constant_speed() const noexcept { return 0.0; }

  /// Point C(u) [mm].
  [[nodiscard]] Vec3 point(double u) const noexcept { return derivatives(u, 0)[0]; }
  /// Parametric speed |C'(u)| [mm per parameter unit].
  [[nodiscard]] double speed(double u) const noexcept { return derivatives(u, 1)[1].norm(); }
  /// Parametric speed as the limit from the left (see derivatives_left).
  [[nodiscard]] double speed_left(double u) const noexcept { return derivatives_left(u, 1)[1].norm(); }

protected:
  Curve() = default;
  Curve(const Curve&) = default;
  Curve& operator=(const Curve&) = default;
  Curve(Curve&&) = default;
  Curve& operator=(Curve&&) = default;
};

}  // namespace kontur
