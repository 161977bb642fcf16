// Cutter radius compensation (cutter_compensation.hpp): offsets of lines and arcs in the active
// plane, corner arcs and intersections, entry and exit moves.
#include "cutter_compensation.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <kontur/error.hpp>
#include <kontur/geometry/helix_arc.hpp>
#include <kontur/geometry/line_segment.hpp>
#include <kontur/tolerances.hpp>
#include <numbers>
#include <variant>

namespace kontur::gcode::detail {
namespace {

constexpr double kPi = std::numbers::pi;

std::string num(double v) { return fmt::format("{:.6g}", v); }

// The angle `phi` moved by whole turns next to `near` (within pi of it).
double unwrap_near(double phi, double near) {
  while (phi - near > kPi) phi -= 2.0 * kPi;
  while (near - phi > kPi) phi += 2.0 * kPi;
  return phi;
}

}  // namespace

Vec3 CutterCompensation::Element::point(double phi) const {
  const double r = r0 + dr * phi;
  return frame.centre + rise * phi * frame.normal + r * (std::cos(phi) * frame.e1 + std::sin(phi) * frame.e2);
}

Vec3 CutterCompensation::Element::tangent(double phi) const {
  if (!arc) return (b - a).normalized();
  const double r = r0 + dr * phi;
  const Vec3 rho = std::cos(phi) * frame.e1 + std::sin(phi) * frame.e2;
  const Vec3 d = dr * rho + r * (-std::sin(phi) * frame.e1 + std::cos(phi) * frame.e2) + rise * frame.normal;
  return d.normalized();
}

void CutterCompensation::fail(const Block& b, const char* rule, const std::string& message) const {
  throw InputError(rule, fmt::format("{}:{}:{}: {}", b.location.file ? *b.location.file : std::string("?"),
                                     b.location.line, b.location.column, message));
}

void CutterCompensation::set_plane(Plane plane) {
  n_ = plane == Plane::xy ? Vec3::UnitZ() : plane == Plane::zx ? Vec3::UnitY() : Vec3::UnitX();
}

CutterCompensation::Element CutterCompensation::offset(const Block& b, double side, double r) const {
  Element e;
  e.block = b;
  if (const auto* line = std::get_if<LineSegment>(&b.geometry)) {
    const Vec3 d = in_plane(line->end() - line->start());
    const Vec3 o = side * r * left(d.normalized());
    e.a = line->start() + o;
    e.b = line->end() + o;
    e.vertex_end = line->end();
    return e;
  }
  const auto* arc = std::get_if<HelixArc>(&b.geometry);
  if (arc == nullptr) fail(b, "cutter-compensation", "internal: a block without a line or an arc under compensation");
  const CircleFrame& f = arc->frame();
  const double along = f.normal.dot(n_);
  if (std::abs(std::abs(along) - 1.0) > 1e-9)
    fail(b, "cutter-compensation",
         fmt::format("{}: an arc outside the plane of the cutter compensation (G41 / G42 offset in the plane "
                     "selected when it was turned on)",
                     to_string(b.type)));
  const double sweep = arc->sweep_rad();
  e.arc = true;
  e.frame = f;
  // The offset moves a point by side r left(t) = -side r (n . normal) rho: the radius changes.
  e.r0 = arc->radius_mm() - side * r * along;
  e.dr = arc->radius_change_mm() / sweep;
  e.rise = arc->rise_mm() / sweep;
  e.phi0 = 0.0;
  e.phi1 = sweep;
  if (!(e.r0 > tolerances::cutter_comp_min_radius_mm) || !(e.r0 + e.dr * sweep > tolerances::cutter_comp_min_radius_mm))
    fail(b, "cutter-gouge",
         fmt::format("{} of radius {} mm: the cutter of radius {} mm on the {} cannot follow it (the arc is "
                     "concave and not larger than the cutter: it would gouge)",
                     to_string(b.type), num(arc->radius_mm()), num(r), side > 0 ? "left (G41)" : "right (G42)"));
  e.vertex_end = arc->point(arc->u_max());
  return e;
}

void CutterCompensation::join(Element& next, std::optional<Element>& corner) {
  Element& prev = *held_;
  const Vec3 V = prev.vertex_end;
  const Vec3 t1 = in_plane(prev.tangent(prev.phi1)).normalized(), t2 = in_plane(next.tangent(next.phi0)).normalized();
  const Vec3 a1 = prev.end(), b0 = next.start();
  if (in_plane(b0 - a1).norm() <= tolerances::cutter_comp_same_point_mm) return;  // tangent: the offsets meet
  const double cross = n_.dot(t1.cross(t2));
  if (side_ * cross <= 0.0) {
    // Convex (or a reversal): an arc of the cutter radius around the programmed corner, from the end
    // of the one offset to the start of the other (at the level where the next move starts).
    Element c;
    c.block = next.block;
    c.block.type = BlockType::arc;
    c.arc = true;
    const Vec3 centre = V - n_ * n_.dot(V) + n_ * n_.dot(b0);
    const Vec3 from = in_plane(a1 - centre), to = in_plane(b0 - centre);
    c.frame.centre = centre;
    c.frame.normal = -side_ * n_;
    c.frame.e1 = from.normalized();
    c.frame.e2 = c.frame.normal.cross(c.frame.e1);
    double sweep = std::atan2(to.dot(c.frame.e2), to.dot(c.frame.e1));
    if (sweep <= 0.0) sweep += 2.0 * kPi;
    c.r0 = from.norm();
    c.dr = (to.norm() - from.norm()) / sweep;
    c.phi0 = 0.0;
    c.phi1 = sweep;
    c.vertex_end = V;
    corner = c;
    return;
  }
  // Concave: both offsets end where they cross, the one nearest the corner.
  const Vec3 e1 = std::abs(n_.x()) > 0.5 ? Vec3::UnitY() : Vec3::UnitX();
  const Vec3 e2 = n_.cross(e1);
  auto p2 = [&](const Vec3& p) { return std::array<double, 2>{p.dot(e1), p.dot(e2)}; };
  const auto mid = p2(0.5 * (a1 + b0));
  std::vector<std::array<double, 2>> hits;
  auto circle_of = [&](const Element& el, double phi, std::array<double, 2>& c, double& r) {
    c = p2(el.frame.centre);
    r = el.r0 + el.dr * phi;
  };
  if (!prev.arc && !next.arc) {
    const auto p = p2(prev.a), q = p2(prev.b), s = p2(next.a), t = p2(next.b);
    const double dx1 = q[0] - p[0], dy1 = q[1] - p[1], dx2 = t[0] - s[0], dy2 = t[1] - s[1];
    const double den = dx1 * dy2 - dy1 * dx2;
    if (den != 0.0) {
      const double u = ((s[0] - p[0]) * dy2 - (s[1] - p[1]) * dx2) / den;
      hits.push_back({p[0] + u * dx1, p[1] + u * dy1});
    }
  } else if (prev.arc != next.arc) {
    const Element& ln = prev.arc ? next : prev;
    const Element& ar = prev.arc ? prev : next;
    std::array<double, 2> c{};
    double r = 0.0;
    circle_of(ar, prev.arc ? ar.phi1 : ar.phi0, c, r);
    const auto p = p2(ln.a), q = p2(ln.b);
    const double dx = q[0] - p[0], dy = q[1] - p[1];
    const double fx = p[0] - c[0], fy = p[1] - c[1];
    const double A = dx * dx + dy * dy, B = 2.0 * (fx * dx + fy * dy), C = fx * fx + fy * fy - r * r;
    const double disc = B * B - 4.0 * A * C;
    if (A > 0.0 && disc >= 0.0) {
      const double sq = std::sqrt(disc);
      for (const double u : {(-B - sq) / (2.0 * A), (-B + sq) / (2.0 * A)}) hits.push_back({p[0] + u * dx, p[1] + u * dy});
    }
  } else {
    std::array<double, 2> c1{}, c2{};
    double r1 = 0.0, r2 = 0.0;
    circle_of(prev, prev.phi1, c1, r1);
    circle_of(next, next.phi0, c2, r2);
    const double dx = c2[0] - c1[0], dy = c2[1] - c1[1], d = std::hypot(dx, dy);
    if (d > 0.0 && d <= r1 + r2 && d >= std::abs(r1 - r2)) {
      const double a = (r1 * r1 - r2 * r2 + d * d) / (2.0 * d), h = std::sqrt(std::max(0.0, r1 * r1 - a * a));
      const double mx = c1[0] + a * dx / d, my = c1[1] + a * dy / d;
      hits.push_back({mx + h * dy / d, my - h * dx / d});
      hits.push_back({mx - h * dy / d, my + h * dx / d});
    }
  }
  auto gouge = [&] {
    fail(next.block, "cutter-gouge",
         fmt::format("the offsets of the moves on lines {} and {} do not meet at their concave corner: a move "
                     "shorter than the cutter radius {} mm would reverse (the cutter would gouge)",
                     prev.block.location.line, next.block.location.line, num(radius_)));
  };
  if (hits.empty()) gouge();
  const auto& hit = *std::min_element(hits.begin(), hits.end(), [&](const auto& x, const auto& y) {
    return std::hypot(x[0] - mid[0], x[1] - mid[1]) < std::hypot(y[0] - mid[0], y[1] - mid[1]);
  });
  // The crossing on each element: an arc's angle or a line's parameter, within the element.
  auto angle_on = [&](const Element& el, double near) {
    const auto c = p2(el.frame.centre);
    const Vec3 w = (hit[0] - c[0]) * e1 + (hit[1] - c[1]) * e2;
    return unwrap_near(std::atan2(w.dot(el.frame.e2), w.dot(el.frame.e1)), near);
  };
  auto param_on = [&](const Element& el) {
    const auto p = p2(el.a), q = p2(el.b);
    const double dx = q[0] - p[0], dy = q[1] - p[1];
    return ((hit[0] - p[0]) * dx + (hit[1] - p[1]) * dy) / (dx * dx + dy * dy);
  };
  Vec3 X;
  if (prev.arc) {
    const double phi = angle_on(prev, prev.phi1);
    if (!(phi > prev.phi0)) gouge();
    prev.phi1 = phi;
    X = prev.point(phi);
  } else {
    const double u = param_on(prev);
    if (!(u > 0.0)) gouge();
    X = prev.a + u * (prev.b - prev.a);
  }
  if (next.arc) {
    const double phi = angle_on(next, next.phi0);
    if (!(phi < next.phi1)) gouge();
    next.phi0 = phi;
    if (!prev.arc) X = next.point(phi);  // the line ends exactly where the arc starts
  } else {
    if (!(param_on(next) < 1.0)) gouge();
    next.a = X;
  }
  if (!prev.arc) prev.b = X;
}

void CutterCompensation::emit(const Element& e, std::vector<Block>& out) const {
  Block b = e.block;
  if (!e.arc) {
    if ((e.b - e.a).norm() <= tolerances::cutter_comp_same_point_mm && !b.moves_extra_axes()) return;
    b.geometry.emplace<LineSegment>(e.a, e.b);
    b.start = e.a;
    b.end = e.b;
  } else {
    CircleFrame f = e.frame;
    f.centre = e.frame.centre + e.rise * e.phi0 * e.frame.normal;
    f.e1 = std::cos(e.phi0) * e.frame.e1 + std::sin(e.phi0) * e.frame.e2;
    f.e2 = f.normal.cross(f.e1);
    const double sweep = e.phi1 - e.phi0;
    if (!(sweep > 0.0)) return;
    b.geometry.emplace<HelixArc>(f, e.r0 + e.dr * e.phi0, sweep, e.rise * sweep, e.dr * sweep);
    b.start = e.start();
    b.end = e.end();
  }
  out.push_back(std::move(b));
}

void CutterCompensation::flush_held(std::vector<Block>& out) {
  if (!held_) return;
  emit(*held_, out);
  Vec3 p = held_->end();
  for (Block& t : trailing_) {
    if (const auto* line = std::get_if<LineSegment>(&t.geometry)) {
      // a move along the plane's normal stays at the offset position
      const Vec3 q = p + n_ * n_.dot(line->end() - line->start());
      t.geometry.emplace<LineSegment>(p, q);
      t.start = p;
      t.end = q;
      p = q;
    }
    out.push_back(std::move(t));
  }
  trailing_.clear();
  last_ = p;
  held_.reset();
}

void CutterCompensation::push(Block b, std::vector<Block>& out) {
  const bool geometric = b.type != BlockType::dwell && b.curve() != nullptr;
  const bool comp = b.modal.cutter_comp != CutterComp::off;
  if (!on_ && !comp) {
    out.push_back(std::move(b));
    return;
  }
  const bool line = std::holds_alternative<LineSegment>(b.geometry);
  if (on_ && !comp) {
    // G40: the exit move goes from the offset end of the last move to its programmed end.
    flush_held(out);
    on_ = false;
    if (geometric) {
      if (!line)
        fail(b, "cutter-compensation",
             fmt::format("{}: the move after G40 leaves the compensated path and must be a straight line (G0 / G1)",
                         to_string(b.type)));
      const Vec3 end = std::get<LineSegment>(b.geometry).end();
      b.geometry.emplace<LineSegment>(last_, end);
      b.start = last_;
    }
    out.push_back(std::move(b));
    return;
  }
  // Compensation on for this block.
  // Lines and arcs in the plane only (a 3-D circle is a HelixArc too, but not a G2 / G3).
  if (geometric && b.type != BlockType::line && b.type != BlockType::rapid && b.type != BlockType::arc &&
      b.type != BlockType::helix)
    fail(b, "cutter-compensation",
         fmt::format("{}: cutter radius compensation (G41 / G42) of a {} is not supported: turn it off (G40) before "
                     "the block",
                     to_string(b.type), to_string(b.type)));
  const bool in_plane_motion = [&] {
    if (!geometric) return false;
    if (!line) return true;
    const auto& l = std::get<LineSegment>(b.geometry);
    if (!on_) set_plane(b.modal.plane);
    return in_plane(l.end() - l.start()).norm() > tolerances::cutter_comp_same_point_mm;
  }();
  if (!on_) {
    // The entry move: the first move with motion in the plane after G41 / G42.
    if (!in_plane_motion) {
      out.push_back(std::move(b));
      return;
    }
    set_plane(b.modal.plane);
    side_ = b.modal.cutter_comp == CutterComp::left ? 1.0 : -1.0;
    radius_ = b.modal.cutter_radius_mm;
    if (!line)
      fail(b, "cutter-compensation",
           fmt::format("{}: the entry move after G41 / G42 must be a straight line (G0 / G1) to the contour",
                       to_string(b.type)));
    const auto& l = std::get<LineSegment>(b.geometry);
    const Vec3 d = in_plane(l.end() - l.start());
    const double dist = d.norm();
    if (!(dist > radius_))
      fail(b, "cutter-compensation",
           fmt::format("the entry move after G41 / G42 is {} mm long in the plane, not longer than the cutter "
                       "radius {} mm",
                       num(dist), num(radius_)));
    // The tool ends touching the programmed end point: a line from the start tangent to the cutter
    // circle around it, on the compensation's side.
    const double theta = std::asin(radius_ / dist);
    const Vec3 dh = d / dist;
    const Vec3 u = std::cos(theta) * dh + side_ * std::sin(theta) * left(dh);
    Element e;
    e.block = b;
    e.a = l.start();
    e.b = l.start() + std::sqrt(dist * dist - radius_ * radius_) * u + n_ * n_.dot(l.end() - l.start());
    e.vertex_end = l.end();
    held_ = e;
    on_ = true;
    return;
  }
  if (b.modal.cutter_radius_mm != radius_ || (b.modal.cutter_comp == CutterComp::left ? 1.0 : -1.0) != side_)
    fail(b, "cutter-compensation",
         "the cutter radius or side changes while compensation is on: turn it off (G40) first");
  if (!in_plane_motion) {
    trailing_.push_back(std::move(b));
    return;
  }
  Element e = offset(b, side_, radius_);
  std::optional<Element> corner;
  if (held_) join(e, corner);
  flush_held(out);
  if (corner) emit(*corner, out);
  held_ = e;
}

void CutterCompensation::finish(std::vector<Block>& out) {
  flush_held(out);
  on_ = false;
}

}  // namespace kontur::gcode::detail
