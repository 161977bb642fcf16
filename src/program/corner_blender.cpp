#include <algorithm>
#include <cmath>
#include <kontur/geometry/length.hpp>
#include <kontur/geometry/line_segment.hpp>
#include <kontur/program/corner_blender.hpp>
#include <kontur/tolerances.hpp>
#include <limits>
#include <memory>

namespace kontur::program {
namespace {

// Is the blend (trim d [mm]) estimated to be faster than the corner's stop?
bool worth_blending(const CornerBlendCurve& blend, double d, double feed_mm_s, const Machine& machine,
                    const BlendSpeed& speed) {
  double jerk = std::numeric_limits<double>::infinity();  // smallest linear axis jerk [mm/s^3]
  for (const AxisLimits& a : machine.axes)
    if (linear_axis_index(a.name) >= 0) jerk = std::min(jerk, a.max_jerk);
  const double v = speed(blend, feed_mm_s);  // [mm/s]
  if (!(v > 0.0)) return false;
  const double t_blend = 2.0 * d / v;
  const double t_stop = std::max(2.0 * std::cbrt(6.0 * d / jerk), 2.0 * d / feed_mm_s);
  return t_blend < t_stop;
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
  const auto* line = moves_extra_axes(move) ? nullptr : dynamic_cast<const LineSegment*>(move.curve.get());
  if (held_) {
    Held& h = *held_;
    const double tolerance_mm = h.move.corner_tolerance_mm;
    if (line != nullptr && enabled_ && !h.move.exact_stop && tolerance_mm > 0.0) {
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
            held_ = Held{move, line->start(), line->start(), line->end()};
            return;
          }
          const Vec3 end_in = blend->point(0.0), start_out = blend->point(1.0);
          Move in = with_line(h.move, h.start, end_in);
          in.exact_stop = false;
          out.push_back(std::move(in));
          Move bm;
          bm.curve = blend;
          bm.feed_mm_s = move.feed_mm_s;
          bm.exact_stop = false;
          bm.source_line = move.source_line;
          bm.type = "blend";
          bm.length_mm = length(*blend);
          bm.corner = ProgrammedCorner{h.from, h.to, line->end(), tolerance_mm};
          out.push_back(std::move(bm));
          held_ = Held{move, start_out, line->start(), line->end()};
          return;
        }
      }
    }
    flush(out);
  }
  if (line != nullptr) {
    held_ = Held{move, line->start(), line->start(), line->end()};
  } else {
    out.push_back(move);
  }
}

void CornerBlender::flush(std::vector<Move>& out) {
  if (!held_) return;
  Held& h = *held_;
  out.push_back(h.start != h.from ? with_line(h.move, h.start, h.to) : h.move);
  held_.reset();
}

}  // namespace kontur::program
