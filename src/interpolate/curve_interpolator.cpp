#include <kontur/geometry/differential.hpp>
#include <kontur/interpolate/curve_interpolator.hpp>
#include <kontur/geometry/length.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace kontur {
const char* to_string(Interpolator kind) noexcept {
  switch (kind) {
    case Interpolator::taylor_first_order: return "taylor1";
    case Interpolator::taylor_second_order: return "taylor2";
    case Interpolator::arc_length_exact: return "exact";
  }
  return "?";
}

CurveInterpolator::CurveInterpolator(const Curve& curve, Interpolator kind)
    : curve_(&curve), kind_(kind), u_(curve.u_min()) {
  if (kind_ == Interpolator::arc_length_exact) table_.emplace(curve);
}

void CurveInterpolator::reset() noexcept {
  u_ = curve_->u_min();
  s_ = 0.0;
}

double CurveInterpolator::taylor_step(double ds) const noexcept {
  const Derivatives d = curve_->derivatives(u_, 2);
  const double v = d[1].norm();
  if (!(v > 0.0)) {
    // Not regular here (C' = 0): move by a small step that makes progress; the next cycle's
    // derivative takes over.
    return std::max(1e-9 * (curve_->u_max() - curve_->u_min()),
                    4 * std::numeric_limits<double>::epsilon() * std::abs(u_));
  }
  double du = ds / v;
  if (kind_ != Interpolator::taylor_first_order) {
    const double second = du - ds * ds * d[1].dot(d[2]) / (2.0 * v * v * v * v);
    if (second > 0.0) du = second;  // the second-order term may not reverse the motion
  }
  return du;
}

double CurveInterpolator::advance(double ds) noexcept {
  const double u_max = curve_->u_max();
  if (!(ds > 0.0) || u_ >= u_max) return u_;
  const double predicted = u_ + taylor_step(ds);
  s_ += ds;
  if (kind_ == Interpolator::arc_length_exact) {
    if (s_ >= table_->length_mm()) {
      s_ = table_->length_mm();
      u_ = u_max;
    } else {
      u_ = std::min(table_->u_after(u_, s_ - ds, s_, predicted), u_max);
    }
  } else {
    u_ = std::min(predicted, u_max);
  }
  return u_;
}

double chord_limited_feed(double radius_mm, double tolerance_mm, double period_s) noexcept {
  return max_chord_for_error(radius_mm, tolerance_mm) / period_s;
}

FeedFluctuation measure_feed_fluctuation(const Curve& curve, Interpolator kind, double feed_mm_s, double period_s) {
  FeedFluctuation out;
  CurveInterpolator ip(curve, kind);
  const double ds = feed_mm_s * period_s;
  Vec3 prev = ip.point();
  double prev_u = ip.u();
  double sum = 0.0;
  while (true) {
    const double u = ip.advance(ds);
    if (ip.at_end()) {
      out.final_gap_mm = (curve.point(curve.u_max()) - prev).norm();
      break;
    }
    const Vec3 q = ip.point();
    // Compare the arc of the step (what the tool travels along the path) with V T; measured by
    // the adaptive quadrature on the step, independently of the table the exact mode uses.
    const double arc = gauss_kronrod_length(curve, prev_u, u, 1e-14).length_mm;
    const double rel = std::abs(arc / ds - 1.0);
    out.max_relative = std::max(out.max_relative, rel);
    sum += rel;
    out.max_chord_error_mm = std::max(out.max_chord_error_mm, chord_error(curve, prev_u, u, 4));
    ++out.cycles;
    prev = q;
    prev_u = u;
  }
  out.mean_relative = out.cycles > 0 ? sum / static_cast<double>(out.cycles) : 0.0;
  return out;
}

}  // namespace kontur
