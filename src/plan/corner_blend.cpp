#include <kontur/geometry/line_segment.hpp>
#include <kontur/plan/corner_blend.hpp>
#include <kontur/verify/checker.hpp>
#include <kontur/plan/lookahead.hpp>
#include <kontur/tolerances.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>

namespace kontur::plan {
namespace {

// Distance from p to the segment [a, b] [mm].
// Is the blend (trim d [mm]) estimated to be faster than the corner's stop?
bool worth_blending(const CornerBlendCurve& blend, double d, double feed_mm_s, const Machine& machine) {
  double jerk = std::numeric_limits<double>::infinity();  // smallest linear axis jerk [mm/s^3]
  for (const AxisLimits& a : machine.axes)
    if (linear_axis_index(a.name) >= 0) jerk = std::min(jerk, a.max_jerk);
  const PathGeometry g = path_geometry(blend, 0.0, 1.0);
  const double v = speed_cap(g, feed_mm_s, machine, tolerances::plan_centripetal_shares[0]);  // [mm/s]
  if (!(v > 0.0)) return false;
  const double t_blend = 2.0 * d / v;
  const double t_stop = std::max(2.0 * std::cbrt(6.0 * d / jerk), 2.0 * d / feed_mm_s);
  return t_blend < t_stop;
}

}  // namespace

Derivatives CornerBlendCurve::derivatives(double u, int order) const noexcept {
  u = std::clamp(u, 0.0, 1.0);
  const double u2 = u * u, u3 = u2 * u, u4 = u3 * u, u5 = u4 * u;
  const double s = d_ / 3.0;
  // 3 alpha and 3 beta and their derivatives (integer coefficients: the ends are exact).
  const double a[4] = {-3.0 + 5.0 * u - 5.0 * u4 + 3.0 * u5, 5.0 - 20.0 * u3 + 15.0 * u4, -60.0 * u2 + 60.0 * u3,
                       -120.0 * u + 180.0 * u2};
  const double b[4] = {10.0 * u3 - 10.0 * u4 + 3.0 * u5, 30.0 * u2 - 40.0 * u3 + 15.0 * u4,
                       60.0 * u - 120.0 * u2 + 60.0 * u3, 60.0 - 240.0 * u + 180.0 * u2};
  Derivatives out;
  const int n = std::clamp(order, 0, 3);
  for (int k = 0; k <= n; ++k) out[k] = s * (a[k] * t1_ + b[k] * t2_);
  out[0] += corner_;
  return out;
}

double unit_blend_deviation(const Vec3& t1, const Vec3& t2) {
  // The blend of trim 1 mm against the unit corner, measured as the checker measures every blend.
  const CornerBlendCurve c(Vec3::Zero(), t1, t2, 1.0);
  return verify::corner_deviation(c, {-t1, Vec3::Zero(), t2, 0.0});
}

double corner_tolerance(const gcode::Block& b, const Machine& machine) {
  if (b.modal.path_control != gcode::PathControl::blend) return 0.0;
  return b.modal.blend_tolerance_mm > 0.0 ? b.modal.blend_tolerance_mm : machine.path_tolerance_mm;
}

void CornerBlender::push(const MoveInput& move, double tolerance_mm, std::uint64_t tag, std::vector<BlendedMove>& out) {
  const auto* line = dynamic_cast<const LineSegment*>(move.curve.get());
  if (held_) {
    Held& h = *held_;
    if (line != nullptr && enabled_ && !h.move.exact_stop && h.tolerance_mm > 0.0) {
      const Vec3 a = h.to - h.from, b = line->end() - line->start();
      const double la = a.norm(), lb = b.norm();
      if (la >= tolerances::blend_min_line_mm && lb >= tolerances::blend_min_line_mm &&
          (line->start() - h.to).norm() <= 1e-12 * std::max(1.0, h.to.norm())) {
        const Vec3 t1 = a / la, t2 = b / lb;
        if ((t2 - t1).norm() > tolerances::plan_junction_smooth && t1.dot(t2) >= tolerances::blend_min_turn_cos) {
          const double g = unit_blend_deviation(t1, t2);
          const double half = tolerances::blend_max_trim_share;
          double d = std::min(half * la, half * lb);
          if (g > 0.0) d = std::min(d, tolerances::blend_tolerance_share * h.tolerance_mm / g);
          auto blend = std::make_shared<const CornerBlendCurve>(h.to, t1, t2, d);
          if (machine_ != nullptr && !worth_blending(*blend, d, move.feed_mm_s, *machine_)) {
            flush(out);
            held_ = Held{move, line->start(), line->start(), line->end(), tolerance_mm, tag};
            return;
          }
          const Vec3 end_in = blend->point(0.0), start_out = blend->point(1.0);
          MoveInput in = h.move;
          in.curve = std::make_shared<const LineSegment>(h.start, end_in);
          in.exact_stop = false;
          out.push_back({in, h.tag});
          BlendedMove bm;
          bm.move = {blend, move.feed_mm_s, false, move.source_line};
          bm.tag = tag;
          bm.blend = true;
          bm.before = h.from;
          bm.corner = h.to;
          bm.after = line->end();
          bm.tolerance_mm = h.tolerance_mm;
          out.push_back(std::move(bm));
          held_ = Held{move, start_out, line->start(), line->end(), tolerance_mm, tag};
          return;
        }
      }
    }
    flush(out);
  }
  if (line != nullptr) {
    held_ = Held{move, line->start(), line->start(), line->end(), tolerance_mm, tag};
  } else {
    out.push_back({move, tag});
  }
}

void CornerBlender::flush(std::vector<BlendedMove>& out) {
  if (!held_) return;
  Held& h = *held_;
  MoveInput m = h.move;
  if (h.start != h.from) m.curve = std::make_shared<const LineSegment>(h.start, h.to);
  out.push_back({m, h.tag});
  held_.reset();
}

}  // namespace kontur::plan
