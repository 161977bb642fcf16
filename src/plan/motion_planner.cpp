#include <kontur/differential.hpp>
#include <kontur/plan/motion_planner.hpp>

#include <algorithm>
#include <cmath>

namespace kontur::plan {

MotionPlanner::MotionPlanner(const Machine& machine) : machine_(machine), period_(machine.servo_period_s) {}

void MotionPlanner::push(const MoveInput& move) {
  auto table = std::make_shared<const ArcLengthTable>(*move.curve);
  const double length = table->length_mm();
  if (!(length > 0.0)) return;
  const Curve& c = *move.curve;
  MoveConstraint mc;
  mc.length_mm = length;
  mc.limits = move_limits({&c, length, move.feed_mm_s}, machine_);
  const Derivatives start = c.derivatives(c.u_min(), 2);
  const Derivatives end = c.derivatives_left(c.u_max(), 2);
  mc.max_end_velocity = move.exact_stop ? 0.0 : mc.limits.max_velocity;
  // The corner with the move before limits that move's end speed; it is still in the window (the
  // window's last move is never released before the next one arrives or the program ends).
  if (last_end_) lookahead_.limit_last_end_velocity(junction_limit(*last_end_, start, machine_));
  last_end_ = end;
  pending_.push_back({move.curve, table, move.source_line});
  lookahead_.push(mc);
  release_ready();
}

void MotionPlanner::finish() {
  finished_ = true;
  lookahead_.finish();
  release_ready();
}

void MotionPlanner::release_ready() {
  while (lookahead_.ready()) {
    Pending p = std::move(pending_.front());
    pending_.pop_front();
    planned_.push_back({std::move(p.curve), std::move(p.table), lookahead_.pop(), p.source_line});
  }
}

bool MotionPlanner::next(Setpoint& out) noexcept {
  if (end_given_) return false;
  if (!started_) {
    if (planned_.empty()) {
      if (finished_) end_given_ = true;  // an empty program: nothing to give
      return false;
    }
    started_ = true;
    const Planned& m = planned_.front();
    u_ = m.curve->u_min();
    s_ = 0.0;
    last_position_ = m.curve->point(u_);
    out = {0.0, last_position_, m.profile.sample(0.0).v, m.source_line};
    return true;
  }
  double t_move = t_move_ + period_;
  // Move on to the following moves while this cycle lies beyond the current one.
  while (!planned_.empty() && t_move >= planned_.front().profile.duration()) {
    if (planned_.size() < 2) {
      if (!finished_ || !pending_.empty()) return false;  // wait for the look-ahead
      // The last move: its end at rest is the last setpoint.
      const Planned& m = planned_.front();
      t_ += period_;
      last_position_ = m.curve->point(m.curve->u_max());
      out = {t_, last_position_, 0.0, m.source_line};
      end_given_ = true;
      return true;
    }
    t_move -= planned_.front().profile.duration();
    planned_.pop_front();
    u_ = planned_.front().curve->u_min();
    s_ = 0.0;
  }
  if (planned_.empty()) return false;
  const Planned& m = planned_.front();
  const PathState st = m.profile.sample(t_move);
  const double speed = m.curve->speed(u_);
  const double hint = speed > 0.0 ? u_ + (st.s - s_) / speed : u_;
  u_ = st.s >= m.table->length_mm() ? m.curve->u_max() : m.table->u_after(u_, s_, st.s, hint);
  s_ = st.s;
  t_move_ = t_move;
  t_ += period_;
  last_position_ = m.curve->point(u_);
  out = {t_, last_position_, st.v, m.source_line};
  return true;
}

}  // namespace kontur::plan
