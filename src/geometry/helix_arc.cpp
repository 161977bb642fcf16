#include <kontur/error.hpp>
#include <kontur/geometry/curve_piece.hpp>
#include <kontur/geometry/helix_arc.hpp>
#include <kontur/geometry/length.hpp>
#include <kontur/tolerances.hpp>

#include <Eigen/Geometry>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

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

double HelixArc::distance_mm(const Vec3& p, double u0, double u1) const noexcept {
  u0 = std::clamp(u0, 0.0, 1.0);
  u1 = std::clamp(u1, u0, 1.0);
  const Vec3 q = p - frame_.centre;
  const double x = q.dot(frame_.e1), y = q.dot(frame_.e2);
  const double a0 = sweep_ * u0, a1 = sweep_ * u1;
  const double two_pi = 2.0 * std::acos(-1.0);
  // p's angle counted from the part's start, in [0, 2 pi)
  double from_start = std::fmod(std::atan2(y, x) - a0, two_pi);
  if (from_start < 0.0) from_start += two_pi;
  const bool within = from_start <= a1 - a0 || a1 - a0 >= two_pi;
  // On a circle, and on a slight spiral (an arc whose programmed end lay off its circle: its
  // radius changes by at most tolerances::arc_slight_spiral_slope of the radius per radian), the
  // distance to the point at p's angle: exact on the circle, on the spiral above the distance to
  // the foot by a factor of at most 1 / cos(atan(slope)) (1 + 4.5e-4 at the largest slope), so still
  // the distance to a point of the part. (Newton's method on such arcs, each trimmed by the blends
  // at its ends, took three fifths of the run of rgh.)
  if (rise_ == 0.0 && std::abs(radius_change_) <= tolerances::arc_slight_spiral_slope * radius_ * std::abs(sweep_)) {
    // (the distance to the circle's points grows with the angle from p's on either side)
    if (within)
      return std::hypot(std::hypot(x, y) - (radius_ + radius_change_ * (a0 + from_start) / sweep_), q.dot(frame_.normal));
    return std::min((point(u0) - p).norm(), (point(u1) - p).norm());
  }
  // On a spiral, from the parameter of p's angle, or the end nearer in angle; on a helix (a part
  // may wind more than once), from the nearest of 8 points a turn.
  double u = within ? std::min(u0 + from_start / sweep_, u1) : (from_start - (a1 - a0) < two_pi - from_start ? u1 : u0);
  if (rise_ != 0.0) {
    const int n = 8 * std::max(1, static_cast<int>(std::ceil((a1 - a0) / two_pi)));
    double nearest = std::numeric_limits<double>::infinity();
    for (int k = 0; k <= n; ++k) {
      const double v = k == n ? u1 : u0 + (u1 - u0) * k / n;
      const double dk = (point(v) - p).squaredNorm();
      if (dk < nearest) {
        nearest = dk;
        u = v;
      }
    }
  }
  double best_mm = std::numeric_limits<double>::infinity();
  for (int i = 0; i < 8; ++i) {
    const Derivatives d = derivatives(u, 2);
    const Vec3 r = d[0] - p;
    best_mm = std::min(best_mm, r.norm());
    const double f = r.dot(d[1]), fp = d[1].squaredNorm() + r.dot(d[2]);
    if (!(fp > 0.0)) break;
    const double next = std::clamp(u - f / fp, u0, u1);
    // (a step of less than 1e-13 mm along the arc: the foot)
    if (std::abs(next - u) * d[1].norm() <= 1e-13) break;
    u = next;
  }
  return best_mm;
}

ArcSpan arc_span(const Curve& curve) noexcept {
  if (const auto* arc = dynamic_cast<const HelixArc*>(&curve)) return {arc, 0.0, 1.0};
  // A piece of a piece (an arc blended at both ends: the blender trims the trimmed arc again) has
  // its whole's parameter, and the outermost piece's range.
  const auto* piece = dynamic_cast<const CurvePiece*>(&curve);
  if (piece == nullptr) return {};
  const double u0 = piece->u_min(), u1 = piece->u_max();
  const Curve* whole = piece->whole().get();
  while (const auto* inner = dynamic_cast<const CurvePiece*>(whole)) whole = inner->whole().get();
  if (const auto* arc = dynamic_cast<const HelixArc*>(whole)) return {arc, u0, u1};
  return {};
}

}  // namespace kontur
