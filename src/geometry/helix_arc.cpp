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
#include <vector>

namespace kontur {

namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();
}  // namespace

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
  // The nearest point [mm] of [lo, hi] (parameters) where f < 0 at lo and f > 0 at hi: Newton's
  // method keeps that bracket around the root (a local minimum), bisecting where a step leaves it.
  const auto root_within = [&](double lo, double hi) {
    double best = kInf, u = 0.5 * (lo + hi);
    for (int i = 0; i < tolerances::arc_distance_iterations; ++i) {
      const Derivatives d = derivatives(u, 2);
      const Vec3 r = d[0] - p;
      best = std::min(best, r.norm());
      const double f = r.dot(d[1]), fp = d[1].squaredNorm() + r.dot(d[2]);
      (f < 0.0 ? lo : hi) = u;
      double next = fp > 0.0 ? u - f / fp : lo;
      if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
      // (a step of less than 1e-13 mm along the arc: the foot)
      if (f == 0.0 || std::abs(next - u) * d[1].norm() <= 1e-13) break;
      u = next;
    }
    return best;
  };
  // The distance has a local minimum in each turn about p's angle theta. On a helix or circle
  // (constant radius R) only within psi* = acos(-c^2 / (rho R)) of theta (c the rise per radian,
  // rho p's distance from the axis), where the squared distance is convex: f changes sign at most
  // once there. A spiral's turn, theta -+ pi, is cut in tolerances::arc_distance_spiral_parts
  // (fewer on a shorter part; its farthest point need not lie opposite theta), each change of
  // sign from - to + searched.
  // The turns are searched in the order of their axial distance from p, which bounds their points'
  // distance from below, until that bound passes the nearest found. (Newton's method from the
  // nearest of 8 samples a turn stepped onto another turn: on a helix of 2.4 turns it returned
  // 2.26 mm where the nearest point lay 0.396 mm away.)
  const double c = rise_ / sweep_;        // [mm/rad]
  const double z = q.dot(frame_.normal);  // p's height over the centre [mm]
  const double rho = std::hypot(x, y);    // [mm]
  const double pi = 0.5 * two_pi;
  const bool helix = radius_change_ == 0.0;
  const double half = helix && rho > 0.0 ? std::acos(std::max(-1.0, -c * c / (rho * radius_))) : pi;
  // p's angle from the arc's start, the turn about it that holds a0 [rad]
  const double theta = a0 + from_start - (from_start > pi ? two_pi : 0.0);
  struct Turn {
    double lo, hi, bound;  // [rad], the axial distance from p at the nearer end [mm]
  };
  std::vector<Turn> turns;
  for (double centre = theta; centre - half < a1; centre += two_pi) {
    const double lo = std::max(a0, centre - half), hi = std::min(a1, centre + half);
    if (!(lo <= hi)) continue;
    // (the height c phi is monotone: nearest to z at z's angle, clamped)
    const double at = c != 0.0 ? std::clamp(z / c, lo, hi) : lo;
    turns.push_back({lo, hi, std::abs(z - c * at)});
  }
  std::sort(turns.begin(), turns.end(), [](const Turn& a, const Turn& b) { return a.bound < b.bound; });
  double best_mm = std::min((point(u0) - p).norm(), (point(u1) - p).norm());
  for (const Turn& t : turns) {
    if (t.bound >= best_mm) break;
    // (f(u) = (C(u) - p).C'(u), half the derivative of the squared distance along the parameter)
    double v_before = 0.0, f_before = 0.0;
    const int parts =
        helix ? 1 : std::max(1, static_cast<int>(std::ceil(tolerances::arc_distance_spiral_parts * (t.hi - t.lo) / two_pi)));
    for (int k = 0; k <= parts; ++k) {
      const double v = k == parts ? t.hi / sweep_ : (t.lo + (t.hi - t.lo) * k / parts) / sweep_;
      const Derivatives d = derivatives(v, 1);
      const double f = (d[0] - p).dot(d[1]);
      best_mm = std::min(best_mm, (d[0] - p).norm());
      if (k > 0 && f_before < 0.0 && f > 0.0) best_mm = std::min(best_mm, root_within(v_before, v));
      v_before = v;
      f_before = f;
    }
  }
  return best_mm;
}

double HelixArc::distance_lower_bound_mm(const Vec3& p, double u0, double u1) const noexcept {
  u0 = std::clamp(u0, 0.0, 1.0);
  u1 = std::clamp(u1, u0, 1.0);
  const Vec3 q = p - frame_.centre;
  const double x = q.dot(frame_.e1), y = q.dot(frame_.e2), z = q.dot(frame_.normal);
  const double rho = std::sqrt(x * x + y * y);  // [mm] p's distance from the axis
  // (a point of the part at radius r and height h lies at least |rho - r| across the axis and
  // |z - h| along it from p; r and h change linearly with u)
  const double r0 = radius_ + radius_change_ * u0, r1 = radius_ + radius_change_ * u1;
  const double h0 = rise_ * u0, h1 = rise_ * u1;
  const double across = std::max({0.0, std::min(r0, r1) - rho, rho - std::max(r0, r1)});
  const double along = std::max({0.0, std::min(h0, h1) - z, z - std::max(h0, h1)});
  return std::sqrt(across * across + along * along);
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
