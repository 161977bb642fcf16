#include <algorithm>
#include <cmath>
#include <kontur/geometry/curve_piece.hpp>
#include <kontur/geometry/helix_arc.hpp>
#include <kontur/geometry/length.hpp>
#include <kontur/geometry/line_segment.hpp>
#include <kontur/geometry/transition_curve.hpp>
#include <kontur/program/corner_blender.hpp>
#include <kontur/tolerances.hpp>
#include <limits>
#include <memory>

namespace kontur::program {
namespace {

// The smallest linear axis jerk [mm/s^3].
double smallest_jerk(const Machine& machine) {
  double jerk = std::numeric_limits<double>::infinity();
  for (const AxisLimits& a : machine.axes)
    if (linear_axis_index(a.name) >= 0) jerk = std::min(jerk, a.max_jerk);
  return jerk;
}

// The time [s] to pass the 2 d [mm] around a corner without a blend: stopping at the corner and
// starting again within d on each side at the smallest axis jerk, or passing it at
// junction_mm_s where that is faster (a corner that is a near stop has junction_mm_s 0).
double corner_time(double d, double feed_mm_s, double junction_mm_s, const Machine& machine) {
  const double t_stop = std::max(2.0 * std::cbrt(6.0 * d / smallest_jerk(machine)), 2.0 * d / feed_mm_s);
  return junction_mm_s > 0.0 ? std::min(t_stop, 2.0 * d / junction_mm_s) : t_stop;
}

// Is the blend (trim d [mm]) estimated to be faster than the corner's stop?
bool worth_blending(const CornerBlendCurve& blend, double d, double feed_mm_s, const Machine& machine,
                    const BlendSpeed& speed) {
  const double v = speed(blend, feed_mm_s);  // [mm/s]
  if (!(v > 0.0)) return false;
  const double t_blend = 2.0 * d / v;
  return t_blend < corner_time(d, feed_mm_s, 0.0, machine);
}

// The blend move of a corner: the source line and feed of the outgoing move.
Move blend_move(std::shared_ptr<const Curve> blend, double length_mm, const Move& outgoing, ProgrammedCorner corner) {
  Move bm;
  bm.curve = std::move(blend);
  bm.feed_mm_s = outgoing.feed_mm_s;
  bm.exact_stop = false;
  bm.source_line = outgoing.source_line;
  bm.type = "blend";
  bm.length_mm = length_mm;
  bm.corner = std::move(corner);
  return bm;
}

// `m` running along the line from `a` to `b` instead (its length recomputed).
Move with_line(const Move& m, const Vec3& a, const Vec3& b) {
  Move out = m;
  out.curve = std::make_shared<const LineSegment>(a, b);
  out.length_mm = length(*out.curve);
  return out;
}

}  // namespace

void CornerBlender::push(const Move& move, std::vector<Move>& out) {
  // A move of extra axes is not blended (its corner stays as programmed).
  const bool extra = moves_extra_axes(move);
  const auto* line = extra ? nullptr : dynamic_cast<const LineSegment*>(move.curve.get());
  const auto* arc = extra ? nullptr : dynamic_cast<const HelixArc*>(move.curve.get());
  if (held_) {
    Held& h = *held_;
    const double tolerance_mm = h.move.corner_tolerance_mm;
    const bool may_blend = enabled_ && !h.move.exact_stop && tolerance_mm > 0.0;
    if (may_blend && line != nullptr && h.line) {
      const Vec3 a = h.to - h.from, b = line->end() - line->start();
      const double la = a.norm(), lb = b.norm();
      if (la >= tolerances::blend_min_line_mm && lb >= tolerances::blend_min_line_mm &&
          (line->start() - h.to).norm() <= 1e-12 * std::max(1.0, h.to.norm())) {
        const Vec3 t1 = a / la, t2 = b / lb;
        if ((t2 - t1).norm() > tolerances::plan_junction_smooth && t1.dot(t2) >= tolerances::blend_min_turn_cos) {
          const double g = unit_blend_deviation(t1, t2);
          const double half = tolerances::blend_max_trim_share;
          double d = std::min(half * la, half * lb);
          if (g > 0.0) d = std::min(d, tolerances::blend_tolerance_share * tolerance_mm / g);
          auto blend = std::make_shared<const CornerBlendCurve>(h.to, t1, t2, d);
          if (machine_ != nullptr && speed_ && !worth_blending(*blend, d, move.feed_mm_s, *machine_, speed_)) {
            flush(out);
            held_ = Held{move, line->start(), line->start(), line->end(), 0.0, true};
            return;
          }
          const Vec3 end_in = blend->point(0.0), start_out = blend->point(1.0);
          out.push_back(held_until(end_in, 0.0));
          out.push_back(blend_move(blend, length(*blend), move,
                                   ProgrammedCorner{std::make_shared<const LineSegment>(h.from, h.to),
                                                    std::make_shared<const LineSegment>(h.to, line->end()),
                                                    tolerance_mm}));
          held_ = Held{move, start_out, line->start(), line->end(), 0.0, true};
          return;
        }
      }
    } else if (may_blend && (line != nullptr || arc != nullptr) && blend_with_arc(move, line != nullptr, out)) {
      return;
    }
    flush(out);
  }
  if (line != nullptr) {
    held_ = Held{move, line->start(), line->start(), line->end(), 0.0, true};
  } else if (arc != nullptr) {
    const Vec3 from = arc->point(arc->u_min()), to = arc->point(arc->u_max());
    held_ = Held{move, from, from, to, arc->u_min(), false};
  } else {
    out.push_back(move);
  }
}

bool CornerBlender::blend_with_arc(const Move& move, bool move_is_line, std::vector<Move>& out) {
  Held& h = *held_;
  const Curve& ca = *h.move.curve;
  const Curve& cb = *move.curve;
  const double la = h.move.length_mm, lb = move.length_mm;  // the programmed lengths [mm]
  if (!(la >= tolerances::blend_min_line_mm && lb >= tolerances::blend_min_line_mm)) return false;
  const Derivatives d_in = ca.derivatives_left(ca.u_max(), 3), d_out = cb.derivatives(cb.u_min(), 3);
  const CurveEnd end_in = curve_end(d_in), start_out = curve_end(d_out);
  if (!((start_out.point - end_in.point).norm() <= tolerances::blend_arc_contiguous_relative *
                                                        std::max(1.0, end_in.point.norm())))
    return false;
  const bool corner = (start_out.tangent - end_in.tangent).norm() > tolerances::plan_junction_smooth;
  const bool jump = (start_out.curvature - end_in.curvature).norm() > tolerances::plan_junction_smooth;
  if (!(corner || jump) || end_in.tangent.dot(start_out.tangent) < tolerances::blend_min_turn_cos) return false;
  const double tolerance_mm = h.move.corner_tolerance_mm;
  const double target_mm = tolerances::blend_tolerance_share * tolerance_mm;
  // (u of the arc length s from an end: lines and arcs run at a constant parametric speed)
  const double ra = (ca.u_max() - ca.u_min()) / la, rb = (cb.u_max() - cb.u_min()) / lb;
  const auto piece_of = [](const std::shared_ptr<const Curve>& c, bool is_line, double u0,
                           double u1) -> std::shared_ptr<const Curve> {
    if (is_line) return std::make_shared<const LineSegment>(c->point(u0), c->point(u1));
    return std::make_shared<const CurvePiece>(c, u0, u1);
  };
  double d = tolerances::blend_max_trim_share * std::min(la, lb);
  for (int attempt = 0; attempt < tolerances::blend_arc_attempts; ++attempt) {
    const double ua = ca.u_max() - ra * d, ub = cb.u_min() + rb * d;
    auto blend = std::make_shared<const TransitionCurve>(curve_end(ca, ua, false), curve_end(cb, ub, false));
    std::shared_ptr<const Curve> before = piece_of(h.move.curve, h.line, ua, ca.u_max());
    std::shared_ptr<const Curve> after = piece_of(move.curve, move_is_line, cb.u_min(), ub);
    const double deviation_mm = curves_deviation(*blend, *before, *after);
    if (!(deviation_mm <= target_mm)) {
      // A jump of curvature strays by ~d^2, a corner by ~d: the square root of the ratio first,
      // then the ratio itself.
      const double ratio = std::isfinite(deviation_mm) ? target_mm / deviation_mm : 0.0;
      d *= std::clamp(attempt == 0 ? std::sqrt(ratio) : ratio, 0.01, 0.9);
      continue;
    }
    const double blend_mm = length(*blend);
    if (machine_ != nullptr && speed_) {
      const double v = speed_(*blend, move.feed_mm_s);  // [mm/s]
      const double junction_mm_s = junction_ ? junction_(d_in, d_out) : 0.0;
      if (!(v > 0.0) || !(blend_mm / v < corner_time(d, move.feed_mm_s, junction_mm_s, *machine_))) return false;
    }
    out.push_back(held_until(blend->point(0.0), ua));
    out.push_back(blend_move(blend, blend_mm, move,
                             ProgrammedCorner{before, after, tolerance_mm}));
    const Vec3 from = cb.point(cb.u_min()), to = cb.point(cb.u_max());
    held_ = Held{move, blend->point(1.0), from, to, ub, move_is_line};
    return true;
  }
  return false;
}

Move CornerBlender::held_until(const Vec3& end, double u_end) const {
  const Held& h = *held_;
  if (h.line) return h.start == h.from && end == h.to ? h.move : with_line(h.move, h.start, end);
  if (h.u_start == h.move.curve->u_min() && u_end == h.move.curve->u_max()) return h.move;
  Move m = h.move;
  m.curve = std::make_shared<const CurvePiece>(h.move.curve, h.u_start, u_end);
  m.length_mm = length(*m.curve);
  return m;
}

void CornerBlender::flush(std::vector<Move>& out) {
  if (!held_) return;
  out.push_back(held_until(held_->to, held_->move.curve->u_max()));
  held_.reset();
}

}  // namespace kontur::program
