#include <algorithm>
#include <cmath>
#include <kontur/geometry/corner_blend_curve.hpp>
#include <kontur/geometry/curve_piece.hpp>
#include <kontur/geometry/golden_section.hpp>
#include <kontur/geometry/helix_arc.hpp>
#include <kontur/geometry/length.hpp>
#include <kontur/geometry/line_segment.hpp>
#include <kontur/geometry/transition_curve.hpp>
#include <kontur/program/corner_blender.hpp>
#include <kontur/tolerances.hpp>
#include <limits>
#include <memory>
#include <optional>

namespace kontur::program {
namespace {

// The smallest linear axis acceleration [mm/s^2] and jerk [mm/s^3].
struct SmallestLimits {
  double acceleration_mm_s2 = std::numeric_limits<double>::infinity();
  double jerk_mm_s3 = std::numeric_limits<double>::infinity();
};
SmallestLimits smallest_limits(const Machine& machine) {
  SmallestLimits l;
  for (const AxisLimits& a : machine.axes)
    if (linear_axis_index(a.name) >= 0) {
      l.acceleration_mm_s2 = std::min(l.acceleration_mm_s2, a.max_acceleration);
      l.jerk_mm_s3 = std::min(l.jerk_mm_s3, a.max_jerk);
    }
  return l;
}

// The time [s] to cover x [mm] from v0 [mm/s] with zero acceleration, speeding up to v_max
// [mm/s] and then cruising: the jerk-limited S-curve at the limits l.
double time_to_cover(double v0, double x, double v_max, const SmallestLimits& l) {
  if (!(x > 0.0)) return 0.0;
  if (!(v_max > v0)) return x / v0;
  const double a = l.acceleration_mm_s2, j = l.jerk_mm_s3;
  const double dv = v_max - v0;
  const bool full = dv >= a * a / j;                   // the acceleration reaches its limit
  const double t1 = full ? a / j : std::sqrt(dv / j);  // [s] each jerk phase
  const double peak = j * t1;                          // [mm/s^2]
  const double t2 = full ? dv / a - a / j : 0.0;       // [s] at the peak acceleration
  const double total = 2.0 * t1 + t2;                  // [s] of the whole change
  const double s_change = 0.5 * (v0 + v_max) * total;  // [mm] covered in it
  if (x >= s_change) return total + (x - s_change) / v_max;
  const double v1 = v0 + 0.5 * peak * t1, s1 = v0 * t1 + j * t1 * t1 * t1 / 6.0;
  const auto s_at = [&](double t) {  // [mm] covered after t [s]
    if (t <= t1) return v0 * t + j * t * t * t / 6.0;
    if (t <= t1 + t2) return s1 + v1 * (t - t1) + 0.5 * peak * (t - t1) * (t - t1);
    const double r = total - t;  // the last jerk phase, from its end
    return s_change - (v_max * r - j * r * r * r / 6.0);
  };
  double lo = 0.0, hi = total;
  for (int i = 0; i < tolerances::blend_estimate_bisections; ++i) {
    const double mid = 0.5 * (lo + hi);
    (s_at(mid) < x ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

// One side of a junction as the estimate sees it: the move's programmed length [mm], the speed it
// can run at [mm/s] and its curvature at the junction [1/mm].
struct Side {
  double length_mm;
  double cap_mm_s;
  double curvature_per_mm;
};

Side side_of(const Move& m, double length_mm, double curvature_per_mm, const BlendSpeed& speed) {
  return {length_mm, speed(*m.curve, m.feed_mm_s), curvature_per_mm};
}

// Is a blend of length blend_mm [mm] run at v_blend [mm/s], trimming d [mm] of each move, faster
// than passing the junction as it is (`junction`: its speed, 0 for a stop, and the share of the
// jerk it takes from the moves beside it)? Both are timed over a window of half of each move (the
// other half belongs to the junction at its other end), speeding up from the junction (or the
// blend's end) to the move's cap at the smallest axis acceleration and jerk (on a curve, the
// acceleration its centripetal part leaves at the cap): what a slow blend saves near the corner
// it can lose speeding up from its lower speed further out, and a stop costs the time to reach
// speed again, acceleration included. (Until 2026-12-04 the estimate timed only the 2 d around
// the corner and a stop by the jerk alone: with a large jerk a stop looked almost free, and a
// machine with ten times the jerk ran arc programs slower.)
bool blend_pays(double blend_mm, double v_blend, double d, const Side& a, const Side& b, const JunctionPass& junction,
                const Machine& machine) {
  if (!(v_blend > 0.0) || !(blend_mm > 0.0)) return false;
  const SmallestLimits smallest = smallest_limits(machine);
  double t_blend = blend_mm / v_blend, t_junction = 0.0;
  for (const Side& side : {a, b}) {
    // On a curve the centripetal part takes its share of the acceleration: what is left at the cap.
    SmallestLimits l = smallest;
    const double centripetal =
        std::min(1.0, side.cap_mm_s * side.cap_mm_s * side.curvature_per_mm / l.acceleration_mm_s2);
    l.acceleration_mm_s2 *=
        std::sqrt(std::max(tolerances::blend_estimate_least_acceleration_share, 1.0 - centripetal * centripetal));
    const double w = std::max(d, 0.5 * side.length_mm);  // [mm] the window on this side
    const double v_from = std::min(junction.velocity_mm_s, side.cap_mm_s);
    t_blend += time_to_cover(std::min(v_blend, side.cap_mm_s), w - d, side.cap_mm_s, l);
    // (the junction takes its share of the jerk from the moves beside it)
    l.jerk_mm_s3 *= 1.0 - junction.jerk_share;
    t_junction += time_to_cover(v_from, w, side.cap_mm_s, l);
  }
  return t_blend < t_junction;
}

// What the blender compares a junction's blends by [s]: the time along a blend of blend_mm [mm] at
// its speed cap v [mm/s], less the time the moves it trims (d [mm] on each side) would take at
// sides_mm_s (the slower side's cap; at least the blend's).
double pass_time_s(double blend_mm, double d, double v, double sides_mm_s) {
  if (!(v > 0.0)) return std::numeric_limits<double>::infinity();
  return blend_mm / v - 2.0 * d / std::max(sides_mm_s, v);
}

// The blend of the corner `corner` between lines of lengths la and lb [mm] in the unit directions
// t1 and t2, of the given shape: as large as the tolerance [mm] allows (its deviation from the
// lines, which grows with d), trimming at most tolerances::blend_max_trim_share of each line.
struct LineBlend {
  std::shared_ptr<const CornerBlendCurve> curve;
  double length_mm = 0.0;
};
// (measured: unit_blend_deviation; else estimated by the distance of its middle from the lines, where
// the blend, convex and symmetric, strays farthest: what the search compares shapes by)
LineBlend line_blend(const Vec3& corner, const Vec3& t1, const Vec3& t2, double la, double lb, double tolerance_mm,
                     const CornerBlendShape& shape, bool measured = true) {
  // B(1/2) = P + (1 + 5 s + 10 e) / 32 d (t2 - t1), at m sin(turn) of each line
  const double g = measured ? unit_blend_deviation(t1, t2, shape)
                            : (1.0 + 5.0 * shape.second + 10.0 * shape.third) / 32.0 * (t2 - t2.dot(t1) * t1).norm();
  const double half = tolerances::blend_max_trim_share;
  double d = std::min(half * la, half * lb);
  if (g > 0.0) d = std::min(d, tolerances::blend_tolerance_share * tolerance_mm / g);
  auto curve = std::make_shared<const CornerBlendCurve>(corner, t1, t2, d, shape);
  const double blend_mm = length(*curve);
  return {std::move(curve), blend_mm};
}

// The blend of the family (corner_blend_shape) that passes the corner fastest (pass_time_s, the
// lines at `lines_mm_s` [mm/s]). Golden sections over the family's parameter; the time falls as
// the blend's cap rises while its curvature or its curvature change binds, and rises again once
// the other does.
LineBlend fastest_line_blend(const Vec3& corner, const Vec3& t1, const Vec3& t2, double la, double lb,
                             double tolerance_mm, double feed_mm_s, double lines_mm_s, const BlendSpeed& speed) {
  const auto blend_time_s = [&](double third) {
    const LineBlend b = line_blend(corner, t1, t2, la, lb, tolerance_mm, corner_blend_shape(third), false);
    return pass_time_s(b.length_mm, b.curve->trim_mm(), speed(*b.curve, feed_mm_s), lines_mm_s);
  };
  const double third = golden_section_minimum(blend_time_s, tolerances::blend_shape_third_min,
                                              tolerances::blend_shape_third_max, tolerances::blend_shape_search_steps)
                           .first;
  return line_blend(corner, t1, t2, la, lb, tolerance_mm, corner_blend_shape(third));
}

// The blend move of a corner: the source line and feed of the outgoing move.
Move blend_move(std::shared_ptr<const Curve> blend, double length_mm, const Move& outgoing, ProgrammedCorner corner) {
  Move bm;
  bm.curve = std::move(blend);
  bm.feed_mm_s = outgoing.feed_mm_s;
  // The extra axes stand where both moves have them (a move of extra axes is not blended).
  bm.extra_start = bm.extra_end = outgoing.extra_start;
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
  double straight_before_mm = 0.0;  // [mm] of the new held line (Held::straight_before_mm)
  if (held_) {
    Held& h = *held_;
    const double tolerance_mm = h.move.corner_tolerance_mm;
    const bool may_blend = enabled_ && !h.move.exact_stop && tolerance_mm > 0.0;
    if (line != nullptr && h.line) {
      // Two lines: the held one, as programmed, and the next.
      const Vec3 a = h.to - h.from, b = line->end() - line->start();
      const double la = a.norm(), lb = b.norm();
      const bool joined = (line->start() - h.to).norm() <= 1e-12 * std::max(1.0, h.to.norm());
      if (may_blend && joined && la >= tolerances::blend_min_line_mm && lb >= tolerances::blend_min_line_mm) {
        const Vec3 t1 = a / la, t2 = b / lb;
        if ((t2 - t1).norm() > tolerances::plan_junction_smooth && t1.dot(t2) >= tolerances::blend_min_turn_cos) {
          const bool planned = machine_ != nullptr && speed_;
          const Side before = planned ? side_of(h.move, h.straight_before_mm + la, 0.0, speed_) : Side{},
                     after = planned ? side_of(move, lb, 0.0, speed_) : Side{};
          const LineBlend chosen = planned ? fastest_line_blend(h.to, t1, t2, la, lb, tolerance_mm, move.feed_mm_s,
                                                           std::min(before.cap_mm_s, after.cap_mm_s), speed_)
                                      : line_blend(h.to, t1, t2, la, lb, tolerance_mm, CornerBlendShape{});
          const auto& blend = chosen.curve;
          const double d = blend->trim_mm();
          if (planned && !blend_pays(chosen.length_mm, speed_(*blend, move.feed_mm_s), d, before, after,
                                     JunctionPass{0.0, tolerances::plan_corner_jerk_share}, *machine_)) {
            flush(out);
            held_ = Held{move, line->start(), line->start(), line->end(), 0.0, true};
            return;
          }
          const Vec3 end_in = blend->point(0.0), start_out = blend->point(1.0);
          out.push_back(held_until(end_in, 0.0));
          out.push_back(
              blend_move(blend, chosen.length_mm, move,
                         ProgrammedCorner{std::make_shared<const LineSegment>(h.from, h.to),
                                          std::make_shared<const LineSegment>(h.to, line->end()), tolerance_mm}));
          held_ = Held{move, start_out, line->start(), line->end(), 0.0, true};
          return;
        }
      }
      // A line going straight on from an untrimmed held line, without a stop, extends its stretch.
      if (joined && !h.move.exact_stop && h.start == h.from && la > 0.0 && lb > 0.0 &&
          (b / lb - a / la).norm() <= tolerances::plan_junction_smooth)
        straight_before_mm = h.straight_before_mm + la;
    } else if (may_blend && (line != nullptr || arc != nullptr) && blend_with_arc(move, line != nullptr, out)) {
      return;
    }
    flush(out);
  }
  if (line != nullptr) {
    held_ = Held{move, line->start(), line->start(), line->end(), 0.0, true, straight_before_mm};
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
  if (!((start_out.point - end_in.point).norm() <=
        tolerances::blend_arc_contiguous_relative * std::max(1.0, end_in.point.norm())))
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
  // The blend of tangent scale `scale` as large as the tolerance allows (within the attempts).
  struct ArcBlend {
    std::shared_ptr<const TransitionCurve> curve;
    std::shared_ptr<const Curve> before, after;
    double d = 0.0, ua = 0.0, ub = 0.0, length_mm = 0.0;  // [mm], parameters, [mm]
  };
  const auto sized = [&](double scale) -> std::optional<ArcBlend> {
    double d = tolerances::blend_max_trim_share * std::min(la, lb);
    for (int attempt = 0; attempt < tolerances::blend_arc_attempts; ++attempt) {
      const double ua = ca.u_max() - ra * d, ub = cb.u_min() + rb * d;
      auto blend =
          std::make_shared<const TransitionCurve>(curve_end(ca, ua, false), curve_end(cb, ub, false), scale);
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
      return ArcBlend{std::move(blend), std::move(before), std::move(after), d, ua, ub, blend_mm};
    }
    return std::nullopt;
  };
  std::optional<ArcBlend> chosen = sized(1.0);
  if (!chosen) return false;
  if (machine_ != nullptr && speed_) {
    const Side before = side_of(h.move, la, end_in.curvature.norm(), speed_),
               after = side_of(move, lb, start_out.curvature.norm(), speed_);
    // Whether to blend is judged on the chord's scale (1); where it pays, the scale that passes the
    // junction fastest is taken (as fastest_line_blend judges a corner's blends). (Judged on the
    // chosen scale, a junction turning by 120 degrees into an arc on a machine with jerk A / T was
    // blended, 5 % slower than kept: CornerBlend.TheBlenderChoosesTheFasterOfBlendAndJunction.)
    const JunctionPass pass =
        junction_ ? junction_(d_in, d_out) : JunctionPass{0.0, tolerances::plan_corner_jerk_share};
    const double v = speed_(*chosen->curve, move.feed_mm_s);  // [mm/s]
    if (!blend_pays(chosen->length_mm, v, chosen->d, before, after, pass, *machine_)) return false;
    const double sides_mm_s = std::min(before.cap_mm_s, after.cap_mm_s);
    double best_s = pass_time_s(chosen->length_mm, chosen->d, v, sides_mm_s);
    for (const double scale : tolerances::blend_arc_tangent_scales) {
      if (scale == 1.0) continue;
      std::optional<ArcBlend> other = sized(scale);
      if (!other) continue;
      const double t_s =
          pass_time_s(other->length_mm, other->d, speed_(*other->curve, move.feed_mm_s), sides_mm_s);
      if (t_s < best_s) {
        best_s = t_s;
        chosen = std::move(other);
      }
    }
  }
  out.push_back(held_until(chosen->curve->point(0.0), chosen->ua));
  out.push_back(blend_move(chosen->curve, chosen->length_mm, move,
                           ProgrammedCorner{chosen->before, chosen->after, tolerance_mm}));
  const Vec3 from = cb.point(cb.u_min()), to = cb.point(cb.u_max());
  held_ = Held{move, chosen->curve->point(1.0), from, to, chosen->ub, move_is_line};
  return true;
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
