// The programmable frame (Sinumerik TRANS / ATRANS, ROT / AROT, MIRROR / AMIRROR): between the work
// offset and the program coordinates, p_work = A p + t. The absolute forms replace the whole frame
// (an instruction without axes clears it), the additive forms append to it in its own coordinates
// (an ATRANS after a SCALE is scaled, as on the control). An arc in a plane the frame scales unevenly
// would be an ellipse: arc() refuses it. Also Sinumerik's
// polar coordinates (the pole of G110 / G111 / G112, targets from AP= / RP=) and CT, the arc
// tangent to the previous move.
#include <cmath>

#include "executor.hpp"

namespace kontur::gcode::detail {

void Executor::programmable_frame() {
  static constexpr const char* names[] = {"", "TRANS", "ATRANS", "ROT", "AROT", "SCALE", "ASCALE", "MIRROR", "AMIRROR"};
  const FrameOp op = w->frame_op;
  const std::string word = names[static_cast<int>(op)];
  const int col = w->frame_column > 0 ? w->frame_column : block_column();
  // TRANS / ATRANS shift the extra axes too; ROT, SCALE and MIRROR act on X Y Z only
  const bool translation = op == FrameOp::trans || op == FrameOp::atrans;
  if (!translation) refuse_extra_words(word, "in a frame instruction: ROT, SCALE and MIRROR act on X Y Z");
  for (char c = 'A'; c <= 'Z'; ++c)
    if (w->has(c) && c != 'X' && c != 'Y' && c != 'Z' && !(translation && extra_axis_index(c) >= 0))
      fail(w->col(c), "frame-words",
           fmt::format("{}: {} is not allowed in a frame block (X Y Z{} only)", word, c,
                       op == FrameOp::rot || op == FrameOp::arot ? " RPL=" : ""));
  if (w->g_count > 0 || w->m_count > 0 || w->keyword != Keyword::none)
    fail(col, "frame-words", fmt::format("{}: a frame instruction stands in a block of its own", word));
  const Vec3 machine = to_machine(pos);
  const ExtraAxes extra_machine = extra_to_machine(xpos);
  ExtraAxes xt = frames.programmable_extra();
  Eigen::Matrix3d a = frames.programmable_linear();
  Vec3 t = frames.programmable_translation();
  auto axis_value = [&](int axis) {
    const char letter = static_cast<char>('X' + axis);
    return w->has(letter) ? w->get(letter) : 0.0;
  };
  // TRANS / ROT / SCALE / MIRROR replace the programmable frame; ATRANS / AROT / ASCALE / AMIRROR add to it.
  const bool replaces = op == FrameOp::trans || op == FrameOp::rot || op == FrameOp::scale || op == FrameOp::mirror;
  if (replaces) {
    a.setIdentity();
    t.setZero();
    xt.fill(0.0);
  }
  if (w->frame_has_rpl && op != FrameOp::rot && op != FrameOp::arot)
    fail(col, "frame-words", fmt::format("{}: RPL= belongs to ROT / AROT", word));
  switch (op) {
    case FrameOp::trans:
    case FrameOp::atrans: {
      t += a * Vec3(axis_value(0) * scale(), axis_value(1) * scale(), axis_value(2) * scale());
      for (int i = 0; i < extra_axis_count; ++i)
        if (w->has(extra_axis_letters[i]))
          xt[static_cast<std::size_t>(i)] += w->get(extra_axis_letters[i]) * extra_scale(i);
      break;
    }
    case FrameOp::rot:
    case FrameOp::arot: {
      if (w->frame_has_rpl && has_axes())
        fail(col, "frame-words", fmt::format("{}: RPL= or X Y Z angles, not both", word));
      Eigen::Matrix3d r = Eigen::Matrix3d::Identity();
      const double d = pi / 180.0;
      if (w->frame_has_rpl) {
        r = Eigen::AngleAxisd(w->frame_rpl * d, unit(plane_axes(modal.plane).n)).toRotationMatrix();
      } else {  // about Z, then the new Y, then the new X (Sinumerik's default order)
        r = (Eigen::AngleAxisd(axis_value(2) * d, Vec3::UnitZ()) * Eigen::AngleAxisd(axis_value(1) * d, Vec3::UnitY()) *
             Eigen::AngleAxisd(axis_value(0) * d, Vec3::UnitX()))
                .toRotationMatrix();
      }
      a = a * r;
      break;
    }
    case FrameOp::scale:
    case FrameOp::ascale: {  // factors per axis (1 where not given); an arc needs equal ones in its plane
      Eigen::Matrix3d m = Eigen::Matrix3d::Identity();
      for (int axis = 0; axis < 3; ++axis) {
        const char letter = static_cast<char>('X' + axis);
        if (!w->has(letter)) continue;
        const double f = w->get(letter);
        if (!(std::abs(f) > 1e-9) || std::abs(f) > 1e6)
          fail(w->col(letter), "frame-words",
               fmt::format("{} {}{}: a scale factor must not be 0", word, letter, num(f)));
        m(axis, axis) = f;
      }
      a = a * m;
      break;
    }
    case FrameOp::mirror:
    case FrameOp::amirror: {
      Eigen::Matrix3d m = Eigen::Matrix3d::Identity();
      for (int axis = 0; axis < 3; ++axis)
        if (w->has(static_cast<char>('X' + axis))) m(axis, axis) = -1.0;
      a = a * m;
      break;
    }
    default:
      fail(col, "internal", "frame operation not handled");
  }
  frames.set_programmable(a, t);
  frames.set_programmable_extra(xt);
  pos = to_program(machine);  // the tool stays where it is; its program coordinates change
  xpos = xto = extra_to_program(extra_machine);
}

}  // namespace kontur::gcode::detail

namespace kontur::gcode::detail {

void Executor::define_pole() {
  const int col = w->polar_column > 0 ? w->polar_column : block_column();
  const std::string word = g_name(w->pole_g * 10);
  if (w->polar != 0)
    fail(col, "unsupported",
         fmt::format(
             "{} with AP= / RP=: a pole given in polar coordinates is not supported by Kontur (dialect sinumerik)",
             word));
  refuse_extra_words(word, "in a pole definition (the pole lies in the plane)");
  if (w->g_count > 1 || w->m_count > 0 || w->keyword != Keyword::none)
    fail(col, "pole", fmt::format("{}: a pole is defined in a block of its own", word));
  const PlaneAxes pa = plane_axes(modal.plane);
  const Vec3 base = w->pole_g == 110 ? pos : w->pole_g == 112 ? pole : Vec3::Zero();
  Vec3 p = base;
  for (const int a : {pa.a1, pa.a2}) {
    const char letter = static_cast<char>('X' + a);
    if (w->has(letter)) p[a] = (w->pole_g == 111 ? 0.0 : base[a]) + w->get(letter) * scale();
  }
  if (w->has(static_cast<char>('X' + pa.n)))
    fail(w->col(static_cast<char>('X' + pa.n)), "pole",
         fmt::format("{}: the pole lies in the plane; {} is its normal axis", word, static_cast<char>('X' + pa.n)));
  pole = p;
}

Vec3 Executor::polar_target(const Vec3& t) const {
  const PlaneAxes pa = plane_axes(modal.plane);
  for (const int a : {pa.a1, pa.a2}) {
    const char letter = static_cast<char>('X' + a);
    if (w->has(letter))
      fail(w->col(letter), "polar",
           fmt::format("{}: an axis of the plane with {} in one block (polar coordinates give both)", letter,
                       rules_.linuxcnc_polar ? "@ ^" : "AP= / RP="));
  }
  const double rel1 = pos[pa.a1] - pole[pa.a1], rel2 = pos[pa.a2] - pole[pa.a2];
  double angle = (w->polar & 1u) ? w->polar_angle * pi / 180.0 : std::atan2(rel2, rel1);
  double radius = (w->polar & 2u) ? w->polar_radius * scale() : std::hypot(rel1, rel2);
  if (rules_.linuxcnc_polar) {  // @ ^ about the XY origin (pole stays 0); G91 adds to the current ones
    if (modal.plane != Plane::xy)
      fail(w->polar_column, "polar", "@ ^: LinuxCNC's polar coordinates are in the XY plane only (G17)");
    if (modal.distance == DistanceMode::incremental) {
      if (std::hypot(rel1, rel2) <= tolerances::gcode_same_point_mm)
        fail(w->polar_column, "polar", "@ ^: an incremental polar move cannot start at the origin (no angle there)");
      angle = std::atan2(rel2, rel1) + ((w->polar & 1u) ? w->polar_angle * pi / 180.0 : 0.0);
      radius = std::hypot(rel1, rel2) + ((w->polar & 2u) ? w->polar_radius * scale() : 0.0);
    }
  }
  if (radius < 0.0 && !rules_.linuxcnc_polar) fail(w->polar_column, "polar", fmt::format("RP={}: the radius must be >= 0", num(w->polar_radius)));
  Vec3 r = t;
  r[pa.a1] = pole[pa.a1] + radius * std::cos(angle);
  r[pa.a2] = pole[pa.a2] + radius * std::sin(angle);
  return r;
}

void Executor::tangent_arc(const Vec3& to, int col) {
  const PlaneAxes pa = plane_axes(modal.plane);
  const Vec3 n = unit(pa.n);
  Vec3 t = rotation().inverse() * end_tangent;  // in program coordinates
  t -= t.dot(n) * n;
  if (!(t.norm() > 1e-9))
    fail(col, "ct-tangent",
         "CT: no direction to be tangent to (a tangential arc needs a move before it that is not along the plane's "
         "normal)");
  t.normalize();
  const Vec3 s_p = pos - pos.dot(n) * n, e_p = to - to.dot(n) * n;
  const Vec3 chord = e_p - s_p;
  if (chord.norm() <= tolerances::gcode_same_point_mm)
    fail(col, "ct-tangent", "CT: the end point is the start point (in the plane)");
  const Vec3 left = n.cross(t);
  const double across = chord.dot(left);
  if (std::abs(across) <= 1e-12 * chord.norm()) {  // along the tangent: the arc is a straight line
    line_move(BlockType::line, to, col, feed_move("CT"));
    return;
  }
  const double r = chord.squaredNorm() / (2.0 * across);  // > 0: the centre on the left, counter-clockwise
  const Vec3 offset = r * left;
  Words arc_words = *w;
  const char letters[3] = {'I', 'J', 'K'};
  for (const char c : {'I', 'J', 'K', 'R', 'P'}) arc_words.present &= ~(1u << (c - 'A'));
  arc_words.keyword = Keyword::none;
  for (const int a : {pa.a1, pa.a2}) {
    arc_words.set(letters[a], offset[a] / scale(), col);
    arc_words.incremental_words |= 1u << (letters[a] - 'A');
    arc_words.absolute_words &= ~(1u << (letters[a] - 'A'));
  }
  const Words* block = w;
  w = &arc_words;
  try {
    arc(r < 0.0, to, col);
  } catch (...) {
    w = block;
    throw;
  }
  w = block;
}

void Executor::arc_by_angle(bool clockwise, const Vec3& to, int col) {
  const std::string word = clockwise ? "G2" : "G3";
  const double ar = w->arc_angle;
  if (!(ar > 0.0 && ar < 360.0))
    fail(col, "arc-angle", fmt::format("{} AR={}: the opening angle must be between 0 and 360 degrees", word, num(ar)));
  if (w->has('R')) fail(w->col('R'), "arc-angle", fmt::format("{}: AR= and CR= in one block: give one of them", word));
  const PlaneAxes pa = plane_axes(modal.plane);
  const char offset_letter[3] = {'I', 'J', 'K'};
  const Vec3 n = unit(pa.n);
  const double a = ar * pi / 180.0;
  const bool has_ijk = w->has(offset_letter[pa.a1]) || w->has(offset_letter[pa.a2]);
  const Vec3 s_p = pos - pos.dot(n) * n, e_p = to - to.dot(n) * n;
  if (!has_ijk) {  // the end point and the angle: the radius (negative beyond 180 degrees)
    const double c = (e_p - s_p).norm();
    if (c <= tolerances::gcode_same_point_mm)
      fail(col, "arc-angle", fmt::format("{} AR={}: the end point is the start point", word, num(ar)));
    const double r = c / (2.0 * std::sin(a / 2.0));
    Words radius_words = *w;
    radius_words.has_arc_angle = false;
    radius_words.set('R', (ar > 180.0 ? -r : r) / scale(), col);
    const Words* block = w;
    w = &radius_words;
    try {
      arc(clockwise, to, col);
    } catch (...) {
      w = block;
      throw;
    }
    w = block;
    return;
  }
  // the centre and the angle: the end point is the start turned by AR about the centre
  if ((e_p - s_p).norm() > 0.0 || (to - pos).dot(n) != 0.0)
    fail(col, "arc-angle",
         fmt::format("{} AR=: the centre, the end point and the angle over-determine the arc: give two of them", word));
  const Vec3 e_a1 = unit(pa.a1), e_a2 = unit(pa.a2);
  const double i1 = w->has(offset_letter[pa.a1]) ? w->get(offset_letter[pa.a1]) * scale() : 0.0;
  const double i2 = w->has(offset_letter[pa.a2]) ? w->get(offset_letter[pa.a2]) * scale() : 0.0;
  const bool abs1 = w->absolute(offset_letter[pa.a1], modal.arc_distance == DistanceMode::absolute);
  const bool abs2 = w->absolute(offset_letter[pa.a2], modal.arc_distance == DistanceMode::absolute);
  const Vec3 centre = (abs1 ? i1 : s_p.dot(e_a1) + i1) * e_a1 + (abs2 ? i2 : s_p.dot(e_a2) + i2) * e_a2;
  const Vec3 v = s_p - centre;
  const double turn = clockwise ? -a : a;
  const Vec3 end = centre + v * std::cos(turn) + n.cross(v) * std::sin(turn) + pos.dot(n) * n;
  arc(clockwise, end, col);
}

}  // namespace kontur::gcode::detail
