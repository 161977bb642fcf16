#include <kontur/error.hpp>
#include <kontur/geometry/helix_arc.hpp>
#include <kontur/geometry/length.hpp>

#include <Eigen/Geometry>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace kontur {

HelixArc::HelixArc(const CircleFrame& frame, double radius_mm, double sweep_rad, double rise_mm,
                   double radius_change_mm)
    : frame_(frame), radius_(radius_mm), sweep_(sweep_rad), rise_(rise_mm), radius_change_(radius_change_mm) {
  if (!(std::isfinite(radius_mm) && radius_mm > 0.0))
    throw InputError("arc-radius", fmt::format("arc radius {} mm: must be finite and > 0", radius_mm));
  if (!(std::isfinite(sweep_rad) && sweep_rad > 0.0))
    throw InputError("arc-sweep", fmt::format("arc sweep {} rad: must be finite and > 0", sweep_rad));
  if (!(std::isfinite(radius_change_mm) && std::abs(radius_change_mm) < radius_mm))
    throw InputError("arc-radius-change",
                     fmt::format("arc radius change {} mm: must be finite and smaller than the radius {} mm",
                                 radius_change_mm, radius_mm));
  if (!std::isfinite(rise_mm)) throw InputError("arc-rise", fmt::format("helix rise {} mm: must be finite", rise_mm));
  const double err = std::max({std::abs(frame.e1.norm() - 1.0), std::abs(frame.e2.norm() - 1.0),
                               std::abs(frame.normal.norm() - 1.0), std::abs(frame.e1.dot(frame.e2)),
                               (frame.e1.cross(frame.e2) - frame.normal).norm()});
  if (!(err <= 1e-9) || !frame.centre.allFinite())
    throw InputError("arc-frame", fmt::format("arc frame is not orthonormal and right-handed (defect {})", err));
}

Derivatives HelixArc::derivatives(double u, int order) const noexcept {
  u = std::clamp(u, 0.0, 1.0);
  const double phi = sweep_ * u, c = std::cos(phi), s = std::sin(phi);
  const Vec3 radial = c * frame_.e1 + s * frame_.e2;   // d/dphi: tangent = -s e1 + c e2
  const Vec3 tangent = -s * frame_.e1 + c * frame_.e2;
  Derivatives d;
  const double r = radius_ + radius_change_ * u, dr = radius_change_, w = sweep_;
  d[0] = frame_.centre + r * radial + (rise_ * u) * frame_.normal;
  if (order >= 1) d[1] = dr * radial + r * w * tangent + rise_ * frame_.normal;
  if (order >= 2) d[2] = 2.0 * dr * w * tangent - r * w * w * radial;
  if (order >= 3) d[3] = -3.0 * dr * w * w * radial - r * w * w * w * tangent;
  return d;
}

double HelixArc::length_mm() const noexcept {
  if (radius_change_ == 0.0) return std::hypot(radius_ * sweep_, rise_);
  return gauss_kronrod_length(*this).length_mm;
}

Vec3 HelixArc::point_at_angle(double phi_rad) const noexcept { return point(phi_rad / sweep_); }

}  // namespace kontur
