// The programmable frame (Sinumerik TRANS / ATRANS, ROT / AROT, MIRROR / AMIRROR): between the work
// offset and the program coordinates, p_work = A p + t. The absolute forms replace the whole frame
// (an instruction without axes clears it), the additive forms append to it in its own coordinates.
// SCALE would make arcs elliptic in the machine (the geometry is rigid): refused.
#include "executor.hpp"

#include <cmath>

namespace kontur::gcode::detail {

void Executor::programmable_frame() {
  static constexpr const char* names[] = {"", "TRANS", "ATRANS", "ROT", "AROT", "SCALE", "ASCALE", "MIRROR", "AMIRROR"};
  const FrameOp op = w->frame_op;
  const std::string word = names[static_cast<int>(op)];
  const int col = w->frame_column > 0 ? w->frame_column : block_column();
  if (op == FrameOp::scale || op == FrameOp::ascale) {
    const bool any = has_axes();
    if (op == FrameOp::scale && !any) return;  // SCALE alone: no scaling, as without it
    fail(col, "unsupported",
         fmt::format("{}: a scaling frame is not supported by Kontur (dialect sinumerik): its arcs would not be circles "
                     "in the machine; scale the program instead",
                     word));
  }
  for (char c = 'A'; c <= 'Z'; ++c)
    if (w->has(c) && c != 'X' && c != 'Y' && c != 'Z')
      fail(w->col(c), "frame-words", fmt::format("{}: {} is not allowed in a frame block (X Y Z{} only)", word, c,
                                                 op == FrameOp::rot || op == FrameOp::arot ? " RPL=" : ""));
  if (w->g_count > 0 || w->m_count > 0 || w->keyword != Keyword::none)
    fail(col, "frame-words", fmt::format("{}: a frame instruction stands in a block of its own", word));
  const Vec3 machine = to_machine(pos);
  Eigen::Matrix3d a = frames.programmable_linear();
  Vec3 t = frames.programmable_translation();
  const bool any = has_axes() || w->frame_has_rpl;
  auto axis_value = [&](int axis) {
    const char letter = static_cast<char>('X' + axis);
    return w->has(letter) ? w->get(letter) : 0.0;
  };
  switch (op) {
    case FrameOp::trans:
    case FrameOp::atrans: {
      if (w->frame_has_rpl) fail(col, "frame-words", fmt::format("{}: RPL= belongs to ROT / AROT", word));
      const Vec3 v(axis_value(0) * scale(), axis_value(1) * scale(), axis_value(2) * scale());
      if (op == FrameOp::trans) {
        a.setIdentity();
        t = v;
      } else {
        t += a * v;
      }
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
      if (op == FrameOp::rot) {
        a = r;
        t.setZero();
      } else {
        a = a * r;
      }
      break;
    }
    case FrameOp::mirror:
    case FrameOp::amirror: {
      if (w->frame_has_rpl) fail(col, "frame-words", fmt::format("{}: RPL= belongs to ROT / AROT", word));
      Eigen::Matrix3d m = Eigen::Matrix3d::Identity();
      for (int axis = 0; axis < 3; ++axis)
        if (w->has(static_cast<char>('X' + axis))) m(axis, axis) = -1.0;
      if (op == FrameOp::mirror) {
        a = m;
        t.setZero();
      } else {
        a = a * m;
      }
      break;
    }
    default: fail(col, "internal", "frame operation not handled");
  }
  if ((op == FrameOp::trans || op == FrameOp::rot || op == FrameOp::mirror) && !any) {
    a.setIdentity();  // TRANS / ROT / MIRROR alone: no programmable frame
    t.setZero();
  }
  frames.set_programmable(a, t);
  pos = to_program(machine);  // the tool stays where it is; its program coordinates change
}

}  // namespace kontur::gcode::detail
