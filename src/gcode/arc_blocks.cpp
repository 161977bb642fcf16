// Circular blocks: G2 / G3 arcs and helices in a plane (I J K or R, P turns), the 3-D circle
// through an intermediate point (Sinumerik CIP, Fanuc G02.4 / G03.4), and Kontur's CONIC block.
#include "executor.hpp"
#include <kontur/geometry/circle_through_points.hpp>
#include <kontur/geometry/conic_through_points.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>

namespace kontur::gcode::detail {

void Executor::arc(bool clockwise, const Vec3& to, int col) {
  const std::string word = clockwise ? "G2" : "G3";
  const Feed feed = feed_move(word);
  const PlaneAxes pa = plane_axes(modal.plane);
  const char offset_letter[3] = {'I', 'J', 'K'};
  const char plane_name[3][3] = {"XY", "ZX", "YZ"};
  const int pidx = static_cast<int>(modal.plane);
  // the offset word of the normal axis is not allowed, but for zero (FreeCAD's posts write
  // `G2 X Y Z I J K0.000` in G17, which the controls they are written for accept)
  if (w->has(offset_letter[pa.n]) && w->get(offset_letter[pa.n]) != 0.0)
    fail(w->col(offset_letter[pa.n]), "arc-offset",
         fmt::format("{}: {} not allowed for an arc in the {} plane (G{}), which uses {} and {}", word,
                     offset_letter[pa.n], plane_name[pidx], pidx == 0 ? 17 : pidx == 1 ? 18 : 19,
                     offset_letter[pa.a1], offset_letter[pa.a2]));
  const bool has_ijk = w->has(offset_letter[pa.a1]) || w->has(offset_letter[pa.a2]);
  const bool has_r = w->has('R');
  const bool polar_centre = !has_ijk && !has_r && w->polar != 0;  // Sinumerik: AP= / RP= about the pole
  if (!has_ijk && !has_r && !polar_centre)
    fail(col, "arc-centre-missing",
         fmt::format("{}: {} {} (centre) or R (radius) missing", word, offset_letter[pa.a1], offset_letter[pa.a2]));
  int turns = 1;
  if (w->has('P')) {
    const double p = w->get('P');
    if (p != std::floor(p) || p < 1.0 || p > tolerances::gcode_max_arc_turns)
      fail(w->col('P'), "arc-turns", fmt::format("{} P{}: turns must be an integer 1..{}", word, num(p), tolerances::gcode_max_arc_turns));
    turns = static_cast<int>(p);
  }
  const Vec3 n = unit(pa.n), e_a1 = unit(pa.a1), e_a2 = unit(pa.a2);
  auto in_plane = [&](const Vec3& v) { return Vec3(v - v.dot(n) * n); };
  const Vec3 s_p = in_plane(pos), e_p = in_plane(to);
  Vec3 centre;
  // LinuxCNC's radius check: a difference up to its absolute tolerance (0.0283 mm in a mm program,
  // 0.00283 in in an inch program, or the INI's CENTER_ARC_RADIUS_TOLERANCE_*), or up to 100 times
  // that where it is within 0.1 % of the radius.
  const double tol_abs = modal.units == Units::inch ? arc_tolerance_inch_ * 25.4 : arc_tolerance_mm_;
  auto allowed = [&](double radius) {  // the largest difference of radii accepted [mm]
    return std::min(std::max(tol_abs, tolerances::gcode_arc_radius_relative * radius),
                    tolerances::gcode_arc_radius_relative_cap * tol_abs);
  };
  if (polar_centre) {
    centre = in_plane(pole);
  } else if (has_ijk) {
    const double i1 = w->has(offset_letter[pa.a1]) ? w->get(offset_letter[pa.a1]) * scale() : 0.0;
    const double i2 = w->has(offset_letter[pa.a2]) ? w->get(offset_letter[pa.a2]) * scale() : 0.0;
    const bool abs1 = w->absolute(offset_letter[pa.a1], modal.arc_distance == DistanceMode::absolute);
    const bool abs2 = w->absolute(offset_letter[pa.a2], modal.arc_distance == DistanceMode::absolute);
    centre = (abs1 ? i1 : s_p.dot(e_a1) + i1) * e_a1 + (abs2 ? i2 : s_p.dot(e_a2) + i2) * e_a2;
    if (has_r) {
      const double r_ijk = (s_p - centre).norm();
      const double r = std::abs(w->get('R') * scale());
      if (std::abs(r_ijk - r) > allowed(r))
        fail(w->col('R'), "arc-r-inconsistent",
             fmt::format("{}: R{} and the radius {} mm of {} {} disagree: I/J/K inconsistent with R", word,
                         num(w->get('R')), num(r_ijk), offset_letter[pa.a1], offset_letter[pa.a2]));
    }
  } else {
    const double r_signed = w->get('R') * scale();
    const double r = std::abs(r_signed);
    const Vec3 chord = e_p - s_p;
    const double c = chord.norm();
    if (c <= tolerances::gcode_same_point_mm)
      fail(col, "arc-r-full-circle",
           fmt::format("{} R{}: the end point is the start point; a full circle needs {} {} (the centre)", word,
                       num(w->get('R')), offset_letter[pa.a1], offset_letter[pa.a2]));
    if (!(r > 0.0)) fail(w->col('R'), "arc-radius", fmt::format("{} R{}: radius must not be zero", word, num(w->get('R'))));
    double h2 = r * r - c * c / 4.0;
    if (h2 < 0.0) {
      if (c / 2.0 - r > allowed(r))
        fail(w->col('R'), "arc-radius-too-small",
             fmt::format("{} R{}: radius smaller than half the distance {} mm from start to end", word,
                         num(w->get('R')), num(c)));
      h2 = 0.0;
    }
    const Vec3 u = chord / c;
    const Vec3 left = n.cross(u);
    const double side = (clockwise ? -1.0 : 1.0) * (r_signed < 0.0 ? -1.0 : 1.0);
    centre = 0.5 * (s_p + e_p) + side * std::sqrt(h2) * left;
  }
  const double r_start = (s_p - centre).norm(), r_end = (e_p - centre).norm();
  if (!(r_start > tolerances::gcode_same_point_mm))
    fail(col, "arc-radius", fmt::format("{}: the centre {} is the start point (radius zero)", word, point_text(centre)));
  const double mismatch = std::abs(r_start - r_end), r_max = std::max(r_start, r_end);
  if (mismatch > allowed(r_max))
    fail(col, "arc-radius-mismatch",
         fmt::format("{}: radius to the start {} mm and to the end {} mm differ by {} mm (more than {} mm)", word,
                     num(r_start), num(r_end), num(mismatch), num(allowed(r_max))));
  if (mismatch > tolerances::gcode_arc_radius_warning_mm)
    warn(col, fmt::format("{}: radius to the start {} mm and to the end {} mm differ by {} mm: the arc is a spiral "
                          "that ends at the programmed point",
                          word, num(r_start), num(r_end), num(mismatch)));
  CircleFrame f;
  f.normal = clockwise ? Vec3(-n) : n;
  f.e1 = (s_p - centre) / r_start;
  f.e2 = f.normal.cross(f.e1);
  f.centre = centre + pos.dot(n) * n;
  const Vec3 v = e_p - centre;
  double angle = std::atan2(v.dot(f.e2), v.dot(f.e1));
  if (angle < 0.0) angle += 2.0 * pi;
  // A full circle only where the end is the start as computed (LinuxCNC: the end angle equals the
  // start angle), not within a tolerance: CAM output has arcs of 0.1 um (CamBam), and a circle there
  // would be an unprogrammed loop.
  if (e_p == s_p || angle <= 0.0) angle = 2.0 * pi;
  const double sweep = angle + 2.0 * pi * (turns - 1);
  const double rise = (to - pos).dot(f.normal);
  // to machine coordinates: rotation about Z and translation, and a programmable frame (Sinumerik
  // ROT, MIRROR, SCALE) that maps the arc's plane by a similarity (a mirror turns it the other way
  // round, a scale k makes its radius k times)
  const Eigen::Matrix3d lin = rotation();
  CircleFrame mf;
  mf.centre = to_machine(f.centre);
  double k = 1.0;
  double machine_rise = rise;
  if (!frames.programmable_linear_set()) {  // rigid: a rotation about Z
    mf.e1 = lin * f.e1;
    mf.e2 = lin * f.e2;
    mf.normal = lin * f.normal;
  } else {
    const Vec3 u1 = lin * f.e1, u2 = lin * f.e2, un = lin * f.normal;
    k = u1.norm();
    if (std::abs(u2.norm() - k) > 1e-9 * k || std::abs(u1.dot(u2)) > 1e-9 * k * k ||
        un.cross(u1.cross(u2)).norm() > 1e-9 * un.norm() * k * k)
      fail(col, "arc-frame",
           fmt::format("{}: the programmable frame scales the arc's plane unevenly: the arc would not be a circle in "
                       "the machine",
                       word));
    mf.e1 = u1 / k;
    mf.e2 = u2 / k;
    mf.normal = mf.e1.cross(mf.e2);
    machine_rise = rise * un.dot(mf.normal);
  }
  Block b = make_block(std::abs(rise) > 0.0 ? BlockType::helix : BlockType::arc, col);
  b.start = to_machine(pos);
  b.end = to_machine(to);
  b.feed = feed;
  b.geometry.emplace<HelixArc>(
      at(col, word, [&] { return HelixArc(mf, r_start * k, sweep, machine_rise, (r_end - r_start) * k); }));
  emit(std::move(b));
  pos = to;
}

void Executor::emit_circle(const Vec3& mid, const Vec3& to, int col, const std::string& word) {
  const Feed feed = feed_move(word);
  Block b = make_block(BlockType::circle_3d, col);
  b.start = to_machine(pos);
  b.end = to_machine(to);
  b.via[0] = to_machine(mid);
  b.via_count = 1;
  b.feed = feed;
  b.geometry.emplace<HelixArc>(at(col, word, [&] { return make_circle_3d(b.start, b.via[0], b.end); }));
  emit(std::move(b));
  pos = to;
}

HelixArc Executor::make_circle_3d(const Vec3& r1, const Vec3& r2, const Vec3& r3) {
  return circle_through_points(r1, r2, r3).curve();
}

void Executor::circle_block(int motion, int col) {
  if (!has_axes()) return;
  if (!circle_pending) {
    circle_pending = true;
    circle_mid = target();
    circle_loc = location(col);
    circle_g = motion;
    feed_move(g_name(motion, true));  // report a missing feed at the first block
    return;
  }
  // end point block: in G91 relative to the intermediate point (Fanuc)
  Vec3 end_point = circle_mid;
  const char letters[3] = {'X', 'Y', 'Z'};
  for (int a = 0; a < 3; ++a)
    if (w->has(letters[a])) {
      const double v = w->get(letters[a]) * scale();
      end_point[a] = modal.distance == DistanceMode::absolute ? v : circle_mid[a] + v;
    } else {
      end_point[a] = modal.distance == DistanceMode::absolute ? pos[a] : circle_mid[a];
    }
  circle_pending = false;
  // the circle is the block of its first line: report its errors there
  const long this_line = diag.line();
  diag.set_line(circle_loc.line);
  emit_circle(circle_mid, end_point, circle_loc.column, g_name(circle_g, true));
  diag.set_line(this_line);
  queue.back().location = circle_loc;
}

Vec3 Executor::indexed_point(int point) const {
  Vec3 p = pos;
  for (int a = 0; a < 3; ++a)
    if (w->has_indexed(point, a)) {
      const double v = w->indexed[static_cast<std::size_t>(point)][static_cast<std::size_t>(a)] * scale();
      p[a] = modal.distance == DistanceMode::absolute ? v : pos[a] + v;
    }
  return p;
}

void Executor::cip(const Vec3& to, int col) {
  for (int p = 1; p < 3; ++p)
    for (int a = 0; a < 3; ++a)
      if (w->has_indexed(p, a))
        fail(w->indexed_column[static_cast<std::size_t>(p)][static_cast<std::size_t>(a)], "cip-words",
             fmt::format("CIP: {}{}= not allowed (CIP has one intermediate point I1= J1= K1=)", static_cast<char>('I' + a), p + 1));
  if (!(w->indexed_present & 7u))
    fail(col, "cip-intermediate-missing", "CIP: intermediate point missing (I1= J1= K1=)");
  if (!has_axes()) fail(col, "cip-end-missing", "CIP: end point missing (X Y Z)");
  emit_circle(indexed_point(0), to, col, "CIP");
}

void Executor::conic(const Vec3& to, int col) {
  static constexpr const char* names[3] = {"I", "J", "K"};
  for (int p = 0; p < 3; ++p)
    for (int a = 0; a < 3; ++a)
      if (!w->has_indexed(p, a))
        fail(col, "conic-words",
             fmt::format("CONIC: {}{}= missing: a conic needs three intermediate points I1= J1= K1= I2= J2= K2= I3= "
                         "J3= K3= and the end point X Y Z",
                         names[a], p + 1));
  if (!has_axes()) fail(col, "conic-words", "CONIC: end point missing (X Y Z)");
  const Feed feed = feed_move("CONIC");
  const std::array<Vec3, 5> pts{to_machine(pos), to_machine(indexed_point(0)), to_machine(indexed_point(1)),
                                 to_machine(indexed_point(2)), to_machine(to)};
  Block b = make_block(BlockType::conic, col);
  b.start = pts[0];
  b.end = pts[4];
  for (int i = 0; i < 3; ++i) b.via[static_cast<std::size_t>(i)] = pts[static_cast<std::size_t>(i + 1)];
  b.via_count = 3;
  b.feed = feed;
  ConicOptions options;
  options.plane_tolerance_mm = tolerances::gcode_conic_plane_mm;  // programs round coordinates
  b.geometry.emplace<ConicArc>(at(col, "CONIC", [&] { return conic_through_points(pts, options).curve(); }));
  emit(std::move(b));
  pos = to;
}

}  // namespace kontur::gcode::detail
