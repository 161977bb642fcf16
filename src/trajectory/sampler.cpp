#include <algorithm>
#include <cmath>
#include <kontur/tolerances.hpp>
#include <kontur/trajectory/sampler.hpp>

namespace kontur::trajectory {

void Sampler::emit(Setpoint& out, double t, const Vec3& p, const ExtraAxes& extra, double v, long line,
                   program::MoveId move) const noexcept {
  out.t_s = t;
  out.position = layout_.from_tool(p, extra);
  out.v_mm_s = v;
  out.source_line = line;
  out.move = move;
  if (derivatives_) {
    out.velocity = AxisVector::Zero(layout_.size());
    out.acceleration = AxisVector::Zero(layout_.size());
    out.a_mm_s2 = 0.0;
    out.j_mm_s3 = 0.0;
  }
}

void Sampler::emit_derivatives(Setpoint& out, const Segment& m, double u, const PathState& st) const noexcept {
  out.a_mm_s2 = st.a;
  out.j_mm_s3 = st.j;
  if (st.v == 0.0 && st.a == 0.0) return;
  // Tool point: x(t) = C(u(s(t))); with the unit tangent T = C'/|C'| and the curvature vector
  // K = (C'' - (T.C'') T) / |C'|^2: dx/dt = T v, d2x/dt2 = K v^2 + T a.
  Vec3 velocity = Vec3::Zero(), acceleration = Vec3::Zero();
  if (!m.tool_still) {
    const Derivatives d = m.curve->derivatives(u, 2);
    const double speed_u = d[1].norm();  // ds/du
    if (speed_u > 0.0) {
      const Vec3 tangent = d[1] / speed_u;
      const Vec3 curvature = (d[2] - tangent * tangent.dot(d[2])) / (speed_u * speed_u);
      velocity = tangent * st.v;
      acceleration = curvature * (st.v * st.v) + tangent * st.a;
    }
  }
  // Extra axes: linear in the distance along the move.
  ExtraAxes rate{}, rate_v{}, rate_a{};
  if (m.moves_extra && m.move_length_mm > 0.0)
    for (std::size_t e = 0; e < rate.size(); ++e) {
      rate[e] = (m.extra_end[e] - m.extra_start[e]) / m.move_length_mm;
      rate_v[e] = rate[e] * st.v;
      rate_a[e] = rate[e] * st.a;
    }
  out.velocity = layout_.from_tool(velocity, rate_v);
  out.acceleration = layout_.from_tool(acceleration, rate_a);
}

Vec3 Sampler::point_at_s(const Segment& m) const noexcept {
  // The parameter is a double: where |C'| is large (a NURBS weight of 100 next to 0.01) one ulp of
  // u moves the point by up to 1e-9 mm, and the steps of u_ then show as jerk. u_after knows how
  // far the arc length at u_ is from s_ (s_error_, computed from the exact difference of u); the
  // point is moved back along the tangent by it, which is exact to second order (|K| s_error^2).
  if (m.tool_still || !(std::abs(s_error_) > tolerances::sample_arc_error_correct_mm)) return m.curve->point(u_);
  const Derivatives d = m.curve->derivatives(u_, 1);
  const double speed_u = d[1].norm();  // ds/du
  if (!(speed_u > 0.0) || !std::isfinite(speed_u)) return d[0];
  return d[0] - d[1] * (s_error_ / speed_u);
}

bool Sampler::next(Setpoint& out) noexcept {
  if (end_given_) return false;
  Trajectory& tr = *trajectory_;
  if (!started_) {
    if (current_ >= tr.end_index()) {
      if (tr.closed()) end_given_ = true;  // an empty program: nothing to give
      return false;
    }
    started_ = true;
    const Segment& m = tr.segment(current_);
    u_ = m.u0;
    s_ = m.s0_mm;
    t_move_ = 0.0;
    const bool holding = m.hold_before_s > 0.0;
    emit(out, 0.0, m.curve->point(u_), m.extra_at(s_), holding ? 0.0 : m.start_velocity(),
         holding ? m.hold_before_line : m.source_line, holding ? m.hold_before_move : m.move);
    if (derivatives_ && !holding) {
      PathState st = m.profile.sample(m.window_t0_s);
      emit_derivatives(out, m, u_, st);
    }
    return true;
  }
  double t_move = t_move_ + clock_.period_s();
  // Move on to the following segments while this cycle lies beyond the current one.
  while (current_ < tr.end_index() && t_move >= tr.segment(current_).duration()) {
    if (current_ + 1 >= tr.end_index()) {
      if (!tr.closed()) return false;  // wait for the planner
      // The last segment: its end at rest is the last setpoint.
      const Segment& m = tr.segment(current_);
      ++cycle_;
      emit(out, clock_.time_s(cycle_), m.curve->point(m.u1), m.extra_at(m.s1_mm), 0.0,
           m.hold_after_s > 0.0 ? m.hold_after_line : m.source_line, m.move);
      end_given_ = true;
      return true;
    }
    // (t_move_ too: if the planner makes us wait below, the next call goes on from here)
    t_move -= tr.segment(current_).duration();
    t_move_ -= tr.segment(current_).duration();
    ++current_;
    tr.mark_done_before(current_);
    u_ = tr.segment(current_).u0;
    s_ = tr.segment(current_).s0_mm;
    s_error_ = 0.0;
  }
  if (current_ >= tr.end_index()) return false;
  const Segment& m = tr.segment(current_);
  const double t_profile = t_move - m.hold_before_s;
  PathState st;
  long line = m.source_line;
  program::MoveId move = m.move;
  if (t_profile <= 0.0) {
    if (m.hold_before_s > 0.0) {  // dwelling before the segment
      line = m.hold_before_line;
      move = m.hold_before_move;
    } else {  // exactly at its start: the state of its window's start (a chain's speed may be > 0)
      st = m.profile.sample(m.window_t0_s);
      st.s = 0.0;
    }
  } else if (t_profile >= m.motion_s()) {
    st.s = m.s1_mm - m.s0_mm;  // dwelling after the segment
    line = m.hold_after_line;
  } else {
    st = m.profile.sample(m.window_t0_s + t_profile);
    st.s -= m.window_s0_mm;
  }
  const double s_target = m.s0_mm + st.s;
  if (st.s >= m.s1_mm - m.s0_mm || s_target >= m.s1_mm) {
    u_ = m.u1;
    s_error_ = 0.0;
  } else if (s_target > s_ && !m.tool_still) {
    // (u_after starts from the Taylor series of u(s) at u_; no hint needed: it falls back to the
    // table interval's linear guess.) The error of the step is carried into the next one.
    u_ = m.table->u_after(u_, s_, s_target, u_, s_error_, &s_error_);
  }
  s_ = std::max(s_, s_target);
  t_move_ = t_move;
  ++cycle_;
  emit(out, clock_.time_s(cycle_), point_at_s(m), m.extra_at(st.s >= m.s1_mm - m.s0_mm ? m.s1_mm : s_), st.v, line, move);
  if (derivatives_) emit_derivatives(out, m, u_, st);
  return true;
}

}  // namespace kontur::trajectory
