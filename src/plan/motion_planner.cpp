#include <kontur/geometry/differential.hpp>
#include <kontur/plan/motion_planner.hpp>
#include <kontur/tolerances.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace kontur::plan {

std::vector<MovePiece> split_move(const Curve& c, const ArcLengthTable& table, double feed_mm_s,
                                  const Machine& machine) {
  const std::vector<double> bp = c.breakpoints();
  const std::size_t spans = bp.size() - 1;
  std::vector<MovePiece> pieces;
  double lo = 0.0, hi = 0.0;  // range of the span caps [mm/s] in the current piece
  for (std::size_t k = 0; k < spans; ++k) {
    const PathGeometry g = path_geometry(c, bp[k], bp[k + 1]);
    const double cap = speed_cap(g, feed_mm_s, machine, tolerances::plan_centripetal_shares[0]);
    if (k > 0) {
      const Junction j = junction(c.derivatives_left(bp[k], 2), c.derivatives(bp[k], 2), machine);
      const double new_lo = std::min(lo, cap), new_hi = std::max(hi, cap);
      if (j.jerk_share == 0.0 && !(new_hi > tolerances::plan_piece_cap_ratio * new_lo)) {
        pieces.back().u1 = bp[k + 1];
        pieces.back().geometry.merge(g);
        lo = new_lo;
        hi = new_hi;
        continue;
      }
      pieces.back().end = j;
    }
    MovePiece p;
    p.u0 = bp[k];
    p.u1 = bp[k + 1];
    p.geometry = g;
    p.end = {std::numeric_limits<double>::infinity(), 0.0};
    pieces.push_back(p);
    lo = hi = cap;
  }
  // Lengths; a piece of no length (coincident control points) joins the one before it.
  std::vector<MovePiece> out;
  for (MovePiece& p : pieces) {
    p.s0_mm = table.s_of_u(p.u0);
    p.s1_mm = table.s_of_u(p.u1);
    if (!out.empty() && !(p.s1_mm > p.s0_mm)) {
      MovePiece& q = out.back();
      q.u1 = p.u1;
      q.s1_mm = p.s1_mm;
      q.geometry.merge(p.geometry);
      q.end = {std::min(q.end.velocity, p.end.velocity), std::max(q.end.jerk_share, p.end.jerk_share)};
      continue;
    }
    out.push_back(p);
  }
  // A first piece of no length joins the next.
  if (out.size() > 1 && !(out[0].s1_mm > out[0].s0_mm)) {
    out[1].u0 = out[0].u0;
    out[1].s0_mm = out[0].s0_mm;
    out[1].geometry.merge(out[0].geometry);
    out.erase(out.begin());
  }
  out.back().s1_mm = table.length_mm();
  return out;
}

namespace {

// The machine the planner plans with: its axis limits lowered by tolerances::plan_limit_safety
// (the feeds are the program's and stay).
Machine planning_machine(Machine m) {
  constexpr double f = 1.0 - tolerances::plan_limit_safety;
  for (AxisLimits& a : m.axes) {
    a.max_velocity *= f;
    a.max_acceleration *= f;
    a.max_jerk *= f;
  }
  return m;
}

}  // namespace

MotionPlanner::MotionPlanner(const Machine& machine, trajectory::Trajectory& out)
    : machine_(planning_machine(machine)), period_(machine.servo_period_s), out_(&out) {}

void MotionPlanner::push(const program::Move& move) {
  out_->reclaim();
  auto table = std::make_shared<const ArcLengthTable>(*move.curve);
  const double length = table->length_mm();
  if (!(length > 0.0)) return;
  const Curve& c = *move.curve;
  const std::vector<MovePiece> pieces = split_move(c, *table, move.feed_mm_s, machine_);
  // The junction with the move before limits that move's end speed and sets its jerk; the move
  // is still the window's last (never released before the next one arrives or the program ends).
  Junction in{std::numeric_limits<double>::infinity(), 0.0};
  if (last_end_ && !last_exact_stop_ && !pending_.empty()) {
    in = junction(*last_end_, c.derivatives(c.u_min(), 2), machine_);
    lookahead_.limit_last_end_velocity(in.velocity);
  }
  settle_last(in.jerk_share);
  for (std::size_t i = 0; i < pieces.size(); ++i) {
    const MovePiece& p = pieces[i];
    const bool last = i + 1 == pieces.size();
    Piece piece;
    trajectory::Segment& seg = piece.segment;
    seg.curve = move.curve;
    seg.table = table;
    seg.u0 = p.u0;
    seg.u1 = p.u1;
    seg.s0_mm = p.s0_mm;
    seg.s1_mm = p.s1_mm;
    seg.move = move.id;
    seg.source_line = move.source_line;
    piece.geometry = p.geometry;
    piece.feed_mm_s = move.feed_mm_s;
    piece.start_share = i == 0 ? in.jerk_share : pieces[i - 1].end.jerk_share;
    if (initial_hold_s_ > 0.0) {
      seg.hold_before_s = initial_hold_s_;
      seg.hold_before_line = initial_hold_line_;
      // a dwell after moves already released at rest counts to the move before it
      seg.hold_before_move = last_move_ != program::no_move ? last_move_ : move.id;
      initial_hold_s_ = 0.0;
    }
    MoveConstraint mc;
    mc.length_mm = p.s1_mm - p.s0_mm;
    // The last piece's end junction is not known yet: it is planned with the largest share a
    // junction may take, and raised (settle_last) when the next move arrives. Limits may only rise
    // after moves before were released on them (they were planned to brake within the lower ones).
    mc.limits = path_limits(p.geometry, mc.length_mm, move.feed_mm_s, machine_,
                            std::max({piece.start_share, last ? tolerances::plan_smooth_junction_jerk_share : 0.0,
                                      last ? 0.0 : p.end.jerk_share}));
    piece.cap_mm_s = mc.limits.max_velocity;
    mc.max_end_velocity = last ? (move.exact_stop ? 0.0 : mc.limits.max_velocity)
                               : std::min(mc.limits.max_velocity, p.end.velocity);
    pending_.push_back(std::move(piece));
    lookahead_.push(mc);
  }
  last_end_ = c.derivatives_left(c.u_max(), 2);
  last_exact_stop_ = move.exact_stop;
  last_move_ = move.id;
  release_ready();
}

void MotionPlanner::settle_last(double end_share) {
  if (pending_.empty()) return;
  const Piece& prev = pending_.back();
  MoveConstraint& mc = lookahead_.back();
  const PathLimits l = path_limits_at(prev.geometry, prev.cap_mm_s, machine_, std::max(prev.start_share, end_share));
  mc.limits.max_jerk = std::max(mc.limits.max_jerk, l.max_jerk);
}

void MotionPlanner::dwell(double seconds, long source_line) {
  if (finished_ || !(seconds > 0.0)) return;
  if (pending_.empty()) {  // before the first move, or after moves already released at rest
    initial_hold_s_ += seconds;
    initial_hold_line_ = source_line;
    return;
  }
  trajectory::Segment& p = pending_.back().segment;
  p.hold_after_s += seconds;
  p.hold_after_line = source_line;
  lookahead_.limit_last_end_velocity(0.0);
  settle_last(0.0);  // it ends at rest: no junction
  last_exact_stop_ = true;  // the next move starts from rest
}

void MotionPlanner::finish() {
  if (!finished_) settle_last(0.0);  // the last move ends at rest
  finished_ = true;
  lookahead_.finish();
  release_ready();
}

void MotionPlanner::release_ready() {
  while (lookahead_.ready()) {
    Piece p = std::move(pending_.front());
    pending_.pop_front();
    p.segment.profile = lookahead_.pop();
    out_->append(std::move(p.segment));
  }
  if (finished_ && pending_.empty()) out_->close();
}

}  // namespace kontur::plan
