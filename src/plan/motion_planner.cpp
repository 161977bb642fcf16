#include <algorithm>
#include <array>
#include <cmath>
#include <iterator>
#include <kontur/geometry/corner_blend_curve.hpp>
#include <kontur/geometry/differential.hpp>
#include <kontur/geometry/line_segment.hpp>
#include <kontur/geometry/transition_curve.hpp>
#include <kontur/plan/chain_profile.hpp>
#include <kontur/plan/motion_planner.hpp>
#include <kontur/tolerances.hpp>
#include <limits>
#include <optional>

namespace kontur::plan {

namespace {

// A stretch of a span with its geometry and speed cap [mm/s].
struct CapSpan {
  double u0 = 0.0, u1 = 0.0;
  PathGeometry geometry;
  double cap = 0.0;
};

double span_cap(const PathGeometry& g, double feed_mm_s, const Machine& machine) {
  return speed_cap(g, feed_mm_s, machine, tolerances::plan_centripetal_shares[0]);
}

// How add_stretches cuts a span: into `parts` equal parts of its parameter where one part's cap
// is over `ratio` times the whole's (`fine_ratio` in the first `fine_depth` levels), at most
// `max_depth` times deep.
struct StretchCut {
  int parts = 4;
  double ratio = tolerances::plan_piece_cap_ratio;
  int max_depth = tolerances::plan_span_max_depth;
  double fine_ratio = tolerances::plan_span_cut_cap_ratio;
  int fine_depth = tolerances::plan_span_fine_cut_depth;
  [[nodiscard]] constexpr double ratio_at(int depth) const noexcept { return depth < fine_depth ? fine_ratio : ratio; }
};

constexpr StretchCut kSpanCut{};
// a corner blend, or a blend at an arc (tolerances::plan_blend_parts)
constexpr StretchCut kBlendCut{tolerances::plan_blend_parts, tolerances::plan_blend_cap_ratio, 1,
                               tolerances::plan_blend_cap_ratio, 0};
constexpr int kMaxCutParts = std::max(kSpanCut.parts, kBlendCut.parts);

// Appends [u0, u1] to `out`, cut in four while one part's cap is over plan_piece_cap_ratio times the
// whole's (plan_span_cut_cap_ratio in the first plan_span_fine_cut_depth levels; a tight turn in a
// span then slows only a short stretch around it; in four, not two: a span tight at both ends and
// easy between has each half as slow as the whole). Only a cap set by
// the curvature is looked at: the feed and the axis velocities do not change much within a span.
// A corner blend is cut once, finer (kBlendCut); so is a blend at an arc whose parts are long
// enough to brake in (tolerances::plan_blend_part_min_periods).
void add_stretches(const Curve& c, double u0, double u1, const PathGeometry& g, double cap, double feed_mm_s,
                   const Machine& machine, double speed_floor, int depth, std::vector<CapSpan>& out, int& budget) {
  const bool transition = dynamic_cast<const TransitionCurve*>(&c) != nullptr;
  const bool blend = dynamic_cast<const CornerBlendCurve*>(&c) != nullptr || transition;
  const StretchCut& cut = blend ? kBlendCut : kSpanCut;
  const int parts = cut.parts;
  // (a blend at an arc is cut only where each part takes a few servo periods at the whole's cap:
  // its chord bounds its length from below)
  const auto long_enough = [&] {
    return !transition || (c.point(u1) - c.point(u0)).norm() >=
                         parts * tolerances::plan_blend_part_min_periods * machine.servo_period_s * cap;
  };
  PathGeometry straight = g;
  straight.drop_curvature();
  const bool bent = cap < span_cap(straight, feed_mm_s, machine);
  // No part can be ratio_at(depth) times faster where even the smallest sampled curvature and
  // curvature change would not raise the cap that much (the parts are then not sampled).
  const auto may_pay = [&] {
    PathGeometry easiest = g;
    easiest.curvature = g.curvature_low;
    easiest.curvature_rate = g.curvature_rate_low;
    easiest.max_kappa = g.kappa_low;
    return span_cap(easiest, feed_mm_s, machine) > cut.ratio_at(depth) * cap;
  };
  if (bent && depth < cut.max_depth && budget > parts - 1 && long_enough() && may_pay()) {
    const auto n = static_cast<std::size_t>(parts);
    std::array<double, kMaxCutParts + 1> us{};
    for (std::size_t i = 0; i <= n; ++i) us[i] = i == n ? u1 : u0 + (u1 - u0) * static_cast<double>(i) / parts;
    bool distinct = true;
    for (std::size_t i = 0; i < n; ++i) distinct = distinct && us[i] < us[i + 1];
    if (distinct) {
      std::array<PathGeometry, kMaxCutParts> gs;
      std::array<double, kMaxCutParts> cs{};
      double best = 0.0;
      for (std::size_t i = 0; i < n; ++i) {
        gs[i] = path_geometry(c, us[i], us[i + 1], tolerances::plan_samples_per_span, speed_floor);
        cs[i] = span_cap(gs[i], feed_mm_s, machine);
        best = std::max(best, cs[i]);
      }
      if (best > cut.ratio_at(depth) * cap) {
        budget -= parts - 1;
        for (std::size_t i = 0; i < n; ++i)
          add_stretches(c, us[i], us[i + 1], gs[i], cs[i], feed_mm_s, machine, speed_floor, depth + 1, out, budget);
        return;
      }
    }
  }
  out.push_back({u0, u1, g, cap});
}

// The stretch next to a stationary point that no setpoint can show [mm] (tolerances.hpp:
// plan_stationary_blind_share of the smallest a T^2 / 4 and j T^3 / 8, times plan_limit_safety).
double stationary_blind_mm(const Machine& machine) {
  double blind_mm = std::numeric_limits<double>::infinity();
  const double T = machine.servo_period_s;
  for (const AxisLimits& ax : machine.axes)
    blind_mm = std::min({blind_mm, ax.max_acceleration * T * T / 4.0, ax.max_jerk * T * T * T / 8.0});
  return blind_mm * tolerances::plan_stationary_blind_share * tolerances::plan_limit_safety;
}

// The parameter between `from` (a stationary point) and `toward` up to which the curve stays
// within blind_mm of the point, or within plan_stationary_noise_factor times the distance its
// evaluation wanders 2^-48 .. 2^-40 of the way from it (where the curve cannot have moved but by
// rounding: a spline ending on a repeated point with weights 68 and 0.027 wandered 1e-13 mm there,
// with curvatures of 1e21 / mm). Found by doubling a parameter step from the point, not by the
// arc-length table, whose rounding there is of the same order.
double blind_boundary(const Curve& c, double from, double toward, double blind_mm) {
  const Vec3 stop = c.point(from);
  const double range = toward - from;
  double noise_mm = 0.0;
  for (const int e : {-48, -44, -40}) noise_mm = std::max(noise_mm, (c.point(from + std::ldexp(range, e)) - stop).norm());
  const double radius_mm = std::max(blind_mm, tolerances::plan_stationary_noise_factor * noise_mm);
  double last = from;
  for (int e = -60; e <= 0; ++e) {
    const double u = from + std::ldexp(range, e);
    if (!((c.point(u) - stop).norm() <= radius_mm)) break;
    last = u;
  }
  return last;
}

}  // namespace

std::vector<MovePiece> split_move(const Curve& c, const ArcLengthTable& table, double feed_mm_s,
                                  const Machine& machine) {
  if (dynamic_cast<const LineSegment*>(&c) != nullptr) {
    // A line is one piece: no breakpoint inside, no stationary point, no curvature to cut it by.
    MovePiece p;
    p.u0 = c.u_min();
    p.u1 = c.u_max();
    p.geometry = path_geometry(c, p.u0, p.u1, tolerances::plan_samples_per_span, 0.0);
    p.end = {std::numeric_limits<double>::infinity(), 0.0};
    p.s0_mm = 0.0;
    p.s1_mm = table.length_mm();
    return {p};
  }
  const std::vector<double> bp = c.breakpoints();
  // Where the pieces may end: the breakpoints and the stationary points (C' = 0: the path stops).
  struct Cut {
    double u = 0.0;
    bool breakpoint = false, stationary = false;
  };
  std::vector<Cut> cuts;
  for (double u : bp) cuts.push_back({u, true, false});
  for (double u : stationary_points(c, tolerances::plan_stationary_speed_relative,
                                    tolerances::plan_stationary_search_samples)) {
    const auto at = std::lower_bound(cuts.begin(), cuts.end(), u, [](const Cut& a, double b) { return a.u < b; });
    if (at != cuts.end() && at->u == u) at->stationary = true;
    else cuts.insert(at, {u, false, true});
  }
  const double blind_mm = stationary_blind_mm(machine);
  std::vector<MovePiece> pieces;
  double lo = 0.0, hi = 0.0;  // range of the stretch caps [mm/s] in the current piece
  double piece_mm = 0.0;      // its length [mm]
  double own_s = 0.0;         // its time at each stretch's own cap [s]
  for (std::size_t k = 0; k + 1 < cuts.size(); ++k) {
    const Cut& at = cuts[k];
    std::vector<CapSpan> stretches;
    int budget = tolerances::plan_span_max_pieces;
    // the caps are measured without the blind stretches at stationary ends
    double ua = at.u, ub = cuts[k + 1].u;
    if (std::isfinite(blind_mm)) {
      if (at.stationary) ua = blind_boundary(c, at.u, cuts[k + 1].u, blind_mm);
      if (cuts[k + 1].stationary) ub = blind_boundary(c, cuts[k + 1].u, at.u, blind_mm);
    }
    // (then its turn is not measured at all: it lies within blind_mm of a stop)
    const bool all_blind = !(ua < ub);
    if (all_blind) {
      ua = at.u;
      ub = cuts[k + 1].u;
    }
    // Next to a stationary point, |C'| below tolerances::plan_noise_speed_relative of its peak
    // between the cuts is the stationary point's neighbourhood, where the curvature is rounding
    // noise (elsewhere a small |C'| is only a slow parametrisation, e.g. of a large weight).
    const double speed_floor =
        at.stationary || cuts[k + 1].stationary
            ? tolerances::plan_noise_speed_relative *
                  peak_parametric_speed(c, at.u, cuts[k + 1].u, tolerances::plan_stationary_search_samples)
            : 0.0;
    PathGeometry g = path_geometry(c, ua, ub, tolerances::plan_samples_per_span, speed_floor);
    if (all_blind) {
      g.drop_curvature();
    }
    add_stretches(c, ua, ub, g, span_cap(g, feed_mm_s, machine), feed_mm_s, machine, speed_floor, 0, stretches, budget);
    stretches.front().u0 = at.u;
    stretches.back().u1 = cuts[k + 1].u;
    for (std::size_t i = 0; i < stretches.size(); ++i) {
      const CapSpan& st = stretches[i];
      const double len_mm = table.s_of_u(st.u1) - table.s_of_u(st.u0);
      const double len_own_s = st.cap > 0.0 ? len_mm / st.cap : 0.0;  // at its own cap [s]
      if (!pieces.empty()) {
        // inside a span where it was cut: smooth; at a stationary point: a stop
        Junction j{std::numeric_limits<double>::infinity(), 0.0};
        if (i == 0 && at.stationary) j = {0.0, tolerances::plan_corner_jerk_share};
        else if (i == 0 && at.breakpoint) j = junction(c.derivatives_left(at.u, 2), c.derivatives(at.u, 2), machine);
        const double new_lo = std::min(lo, st.cap), new_hi = std::max(hi, st.cap);
        // (one piece runs at its smallest cap: merged only where that loses little time, so that
        // one tight stretch does not slow a long easy one)
        const double new_own_s = own_s + len_own_s;
        const bool cheap = new_lo > 0.0 && (piece_mm + len_mm) / new_lo <=
                                               (1.0 + tolerances::plan_piece_merge_time_loss) * new_own_s;
        if (j.smooth() && !(new_hi > tolerances::plan_piece_cap_ratio * new_lo) && cheap) {
          pieces.back().u1 = st.u1;
          pieces.back().geometry.merge(st.geometry);
          lo = new_lo;
          hi = new_hi;
          piece_mm += len_mm;
          own_s = new_own_s;
          continue;
        }
        pieces.back().end = j;
      }
      MovePiece p;
      p.u0 = st.u0;
      p.u1 = st.u1;
      p.geometry = st.geometry;
      p.end = {std::numeric_limits<double>::infinity(), 0.0};
      pieces.push_back(p);
      lo = hi = st.cap;
      piece_mm = len_mm;
      own_s = len_own_s;
    }
  }
  pieces.front().stationary_start = cuts.front().stationary;
  pieces.back().stationary_end = cuts.back().stationary;
  // Lengths; a piece of no length (coincident control points) joins the one before it.
  std::vector<MovePiece> out;
  for (MovePiece& p : pieces) {
    p.s0_mm = table.s_of_u(p.u0);
    p.s1_mm = table.s_of_u(p.u1);
    if (!out.empty() && !(p.s1_mm > p.s0_mm)) {
      MovePiece& q = out.back();
      q.u1 = p.u1;
      q.s1_mm = p.s1_mm;
      // (its geometry is not run through; sampled there, it is rounding noise)
      q.end = {std::min(q.end.velocity, p.end.velocity), std::max(q.end.jerk_share, p.end.jerk_share)};
      q.stationary_end = p.stationary_end;
      continue;
    }
    out.push_back(p);
  }
  // A first piece of no length joins the next.
  if (out.size() > 1 && !(out[0].s1_mm > out[0].s0_mm)) {
    out[1].u0 = out[0].u0;
    out[1].s0_mm = out[0].s0_mm;
    out[1].stationary_start = out[0].stationary_start;
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

// The length [mm] at or below which a move is the rounding of its coordinates:
// tolerances::plan_rounding_move_ulps units in the last place of its largest end coordinate.
double rounding_length(const Curve& c) {
  const double x = std::max(c.point(c.u_min()).cwiseAbs().maxCoeff(), c.point(c.u_max()).cwiseAbs().maxCoeff());
  return tolerances::plan_rounding_move_ulps * (std::nextafter(x, std::numeric_limits<double>::infinity()) - x);
}

}  // namespace

MotionPlanner::MotionPlanner(const Machine& machine, trajectory::Trajectory& out)
    : machine_(planning_machine(machine)), period_(machine.servo_period_s), out_(&out) {}

void MotionPlanner::push(const program::Move& move) {
  out_->reclaim();
  const Curve& c = *move.curve;
  // The tool path's arc-length table; a move of the extra axes alone runs over their distance.
  std::shared_ptr<const ArcLengthTable> table;
  std::vector<MovePiece> pieces;
  double length = 0.0;  // [mm] (or [deg]): the distance s runs over
  if (move.tool_still) {
    length = move.length_mm;
    if (!(length > 0.0)) return;
    MovePiece p;
    p.u0 = p.u1 = c.u_min();
    p.s0_mm = 0.0;
    p.s1_mm = length;
    p.end = {std::numeric_limits<double>::infinity(), 0.0};
    pieces.push_back(p);
  } else {
    table = std::make_shared<const ArcLengthTable>(c);
    length = table->length_mm();
    // A move of a few ulps (a G91 step that lands back on an absolute end leaves one: 8.9e-16 mm
    // near 5.46 mm) has no direction to go along; as a piece, the corner before it let the tool
    // arrive at a speed the corner after it (a stop) did not, and the jerk jumped 1.0034 times
    // its limit (property seed 3922). It is no move, as one of zero length.
    if (!(length > rounding_length(c))) return;
    pieces = split_move(c, *table, move.feed_mm_s, machine_);
  }
  // The extra axes' rates dq/ds (signed), constant along the move.
  ExtraAxes rate{}, rate_bound{};
  for (std::size_t e = 0; e < rate.size(); ++e) {
    rate[e] = (move.extra_end[e] - move.extra_start[e]) / length;
    rate_bound[e] = std::abs(rate[e]);
  }
  for (MovePiece& p : pieces) p.geometry.extra_rate = rate_bound;
  // The junction with the move before (still the open chain's last piece unless it stopped).
  Junction in{0.0, 0.0};  // at rest
  double in_speed = 0.0;   // [mm/s] at most, through a junction that is not smooth (0: from rest)
  if (!open_.pieces.empty()) {
    if (move.tool_still || last_tool_still_) {
      // The tool point stops where only the extra axes go on (or start): a stop unless both stand.
      in = move.tool_still && last_tool_still_ ? extra_axes_junction(last_rate_, rate, machine_)
                                               : Junction{0.0, tolerances::plan_corner_jerk_share};
    } else if (last_stationary_end_ || pieces.front().stationary_start) {
      in = {0.0, tolerances::plan_corner_jerk_share};  // C' = 0 on one side: no tangent to go on along
    } else {
      in = tighter(junction(*last_end_, c.derivatives(c.u_min(), 2), machine_),
                   extra_axes_junction(last_rate_, rate, machine_));
    }
    if (in.smooth()) {
      settle_last(in.jerk_share, true, in.velocity);
    } else {
      // A corner or a curvature jump: the speed there is limited, also by the caps beside it (the
      // last piece's, and about this move's first piece's, at the largest centripetal share).
      in_speed = std::min(in.velocity, open_.pieces.back().limits.max_velocity);
      const double next_cap = speed_cap(pieces.front().geometry, move.feed_mm_s, machine_,
                                        std::end(tolerances::plan_centripetal_shares)[-1]);
      settle_last(in.jerk_share, false, std::min(in.velocity, next_cap));
      close_chain(in.velocity);
      reach_from(in);
    }
  }
  const bool continues_chain = !open_.pieces.empty();
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
    seg.extra_start = move.extra_start;
    seg.extra_end = move.extra_end;
    seg.move_length_mm = length;
    seg.tool_still = move.tool_still;
    seg.moves_extra = program::moves_extra_axes(move);
    seg.move = move.id;
    seg.source_line = move.source_line;
    piece.geometry = p.geometry;
    piece.feed_mm_s = move.feed_mm_s;
    piece.start_share = i == 0 ? in.jerk_share : pieces[i - 1].end.jerk_share;
    // (within the reach of a junction before it, that junction's share: reach_from)
    if (reach_left_s_ > 0.0) piece.start_share = std::max(piece.start_share, reach_share_);
    piece.start_smooth = i == 0 ? continues_chain : pieces[i - 1].end.smooth();
    piece.start_velocity = i == 0 ? in_speed : pieces[i - 1].end.velocity;
    piece.length_mm = p.s1_mm - p.s0_mm;
    if (initial_hold_s_ > 0.0) {
      seg.hold_before_s = initial_hold_s_;
      seg.hold_before_line = initial_hold_line_;
      // a dwell after moves already released at rest counts to the move before it
      seg.hold_before_move = last_move_ != program::no_move ? last_move_ : move.id;
      initial_hold_s_ = 0.0;
    }
    // The end junction of the last piece is not known yet: its limits are chosen for a smooth one
    // and chosen anew when it is known (settle_last; the open chain is not yet in the look-ahead).
    piece.planned_share = std::max(piece.start_share, last ? 0.0 : p.end.jerk_share);
    piece.planned_end_smooth = last || p.end.smooth();
    piece.planned_end_velocity = last ? std::numeric_limits<double>::infinity() : p.end.velocity;
    piece.limits = piece_limits(piece, piece.planned_share, piece.planned_end_smooth, piece.planned_end_velocity);
    // (the motion takes at least the piece's length at its cap to pass it)
    if (reach_left_s_ > 0.0) {
      const double cap = piece.limits.max_velocity;  // [mm/s]
      reach_left_s_ = cap > 0.0 ? reach_left_s_ - piece.length_mm / cap : 0.0;
    }
    add_piece(std::move(piece));  // (an inner piece's end is known: its limits are final)
    if (!last && !p.end.smooth()) {
      close_chain(p.end.velocity);
      reach_from(p.end);
    }
  }
  last_end_ = c.derivatives_left(c.u_max(), 2);
  last_stationary_end_ = pieces.back().stationary_end;
  last_rate_ = rate;
  last_tool_still_ = move.tool_still;
  last_exact_stop_ = move.exact_stop;
  last_move_ = move.id;
  if (move.exact_stop) {
    settle_last(0.0, false, 0.0);
    close_chain(0.0);
  }
  release_ready();
}

void MotionPlanner::add_piece(Piece piece) {
  if (!open_.pieces.empty()) {
    const double lo = std::min(open_.min_cap_mm_s, piece.limits.max_velocity),
                 hi = std::max(open_.max_cap_mm_s, piece.limits.max_velocity);
    // The look-ahead plans a chain with its smallest acceleration: a piece far below the chain's
    // would slow all of it (a tight stretch of 4 um next to a near-cusp dragged 190 mm of
    // G6_Curva_Delfino down by a quarter). (Jerk is not looked at: smoothed runs of lines vary in
    // it, and breaking their chains slows them.)
    const double a_lo = std::min(open_.pieces.front().limits.max_acceleration, piece.limits.max_acceleration),
                 a_hi = std::max(open_.pieces.front().limits.max_acceleration, piece.limits.max_acceleration);
    // Keeping the piece costs the time of running the whole chain at the smaller cap (less what
    // the chain's profile wins back); closing costs about a change of speed between the caps.
    const double length = open_.length_mm + piece.length_mm,
                 own_time = open_.own_time_s + (lo > 0.0 ? piece.length_mm / piece.limits.max_velocity : 0.0);
    const double change_s = velocity_change_time(
        lo, hi, a_lo, std::min(open_.pieces.front().limits.max_jerk, piece.limits.max_jerk));
    const bool costly = lo > 0.0 && length / lo - own_time > std::max(tolerances::plan_chain_close_time_loss * own_time,
                                                          tolerances::plan_chain_close_change_share * change_s);
    // Pieces of different speeds each keep their own cap; a chain is bounded in length.
    if (costly || hi > tolerances::plan_piece_cap_ratio * lo || a_hi > tolerances::plan_chain_limit_ratio * a_lo ||
        open_.pieces.size() >= tolerances::plan_chain_max_pieces)
      close_chain(std::numeric_limits<double>::infinity(), piece.limits.max_velocity);
  }
  open_.count(piece, open_.pieces.empty());
  open_.pieces.push_back(std::move(piece));
}

void MotionPlanner::raise_chain_lows(Chain& chain, double cap_before, double cap_after) {
  std::vector<Piece>& ps = chain.pieces;
  const std::size_t n = ps.size();
  // (a curved piece whose share was chosen by its length alone: not an end at a corner or a stop,
  // where the change of speed was weighed)
  const auto raisable = [&](std::size_t k) {
    return !ps[k].geometry.curvature.isZero() && !(k == 0 && !ps[k].start_smooth) &&
           !(k + 1 == n && !ps[k].planned_end_smooth);
  };
  // (the caps as the chain was built: the raised limits are set only after the last is found)
  const auto cap = [&](std::size_t k) { return ps[k].limits.max_velocity; };
  std::vector<double>& raised = raise_to_;
  std::vector<double>& tops = raise_tops_;
  raised.assign(n, 0.0);
  tops.assign(n, -1.0);
  const auto top = [&](std::size_t k) {  // its cap at the largest shares [mm/s], once a piece
    if (tops[k] < 0.0) {
      const Piece& p = ps[k];
      tops[k] = path_limits(p.geometry, p.length_mm, p.feed_mm_s, machine_,
                            {.junction_jerk_share = p.planned_share, .change_weight = 0.0, .at_a_low = true})
                    .max_velocity;
    }
    return tops[k];
  };
  const auto cap_at = [&](std::size_t k, bool before) {  // the neighbour's cap, outside the chain too
    if (before) return k > 0 ? cap(k - 1) : cap_before;
    return k + 1 < n ? cap(k + 1) : cap_after;
  };
  for (std::size_t k = 0; k < n; ++k) {
    if (!raisable(k) || !(cap(k) <= cap_at(k, true) && cap(k) <= cap_at(k, false))) continue;
    // The motion passes this low at its cap, and the pieces around it below the low's raised cap
    // at theirs: all of them rise to that level (the two middle parts of a symmetric blend have
    // the same cap), within each one's own and below the pieces beyond them.
    double level = top(k);
    std::size_t i = k, j = k;
    while (i > 0 && cap(i - 1) < level && raisable(i - 1)) --i;
    while (j + 1 < n && cap(j + 1) < level && raisable(j + 1)) ++j;
    level = std::min({level, cap_at(i, true), cap_at(j, false)});
    // (level <= top(k): each piece of the region at most its own largest cap)
    for (std::size_t q = i; q <= j; ++q) raised[q] = std::max(raised[q], std::min(level, top(q)));
  }
  // (the look-ahead plans a chain of several pieces with their smallest jerk: a raise that would
  // lower it is not taken; with it, 3D_Chips on the default machine ran 1 % slower)
  double j_least = std::numeric_limits<double>::infinity();  // [mm/s^3]
  for (const Piece& p : ps) j_least = std::min(j_least, p.limits.max_jerk);
  bool any = false;
  for (std::size_t k = 0; k < n; ++k) {
    if (!(raised[k] > cap(k))) continue;
    const PathLimits l = path_limits_at(ps[k].geometry, raised[k], machine_, ps[k].planned_share);
    if (n > 1 && l.max_jerk < j_least) continue;
    ps[k].limits = l;
    any = true;
  }
  if (any) chain.recount();
}

void MotionPlanner::Chain::count(const Piece& p, bool first) noexcept {
  const double cap = p.limits.max_velocity;
  min_cap_mm_s = first ? cap : std::min(min_cap_mm_s, cap);
  max_cap_mm_s = first ? cap : std::max(max_cap_mm_s, cap);
  length_mm = (first ? 0.0 : length_mm) + p.length_mm;
  own_time_s = (first ? 0.0 : own_time_s) + (cap > 0.0 ? p.length_mm / cap : 0.0);
}

void MotionPlanner::Chain::recount() noexcept {
  for (std::size_t k = 0; k < pieces.size(); ++k) count(pieces[k], k == 0);
}

void MotionPlanner::append_stretches(const Chain& chain, std::vector<CapStretch>& out) {
  for (const Piece& p : chain.pieces)
    out.push_back({p.length_mm, p.limits.max_velocity, p.limits.max_acceleration, p.limits.max_jerk,
                   p.bands});
}

std::optional<trajectory::PathProfile> MotionPlanner::following_profile(std::span<const CapStretch> stretches,
                                                                        double v0, double v1, const PathLimits& least,
                                                                        double time_bound_s) const {
  // Steps of at most a servo period, a quarter of the time the jerk takes to build up the
  // acceleration, at least an eighth of a period.
  const double ramp_s = least.max_acceleration / least.max_jerk;
  const double step = std::clamp(0.25 * ramp_s, period_ / 8.0, period_);
  // (each stretch at its own acceleration and jerk)
  const PathLimits ceiling{least.max_velocity, std::numeric_limits<double>::infinity(),
                           std::numeric_limits<double>::infinity()};
  return plan_chain_profile(stretches, v0, v1, ceiling, step, time_bound_s);
}

trajectory::PathProfile MotionPlanner::chain_profile(const Chain& chain, const trajectory::PathProfile& planned) const {
  // The look-ahead's profile (the S-curve at the smallest cap, or under the chain's bands) always
  // fits; the others are taken only where they are faster.
  std::optional<trajectory::PathProfile> best;
  double best_s = planned.duration();
  const auto consider = [&](std::optional<trajectory::PathProfile> p) {
    if (p && p->duration() < best_s) {
      best_s = p->duration();
      best = std::move(p);
    }
  };
  // Up to the smallest cap, speeding up and braking harder where every piece's centripetal part
  // leaves more (the pieces' speed bands, each at its lowest over the chain's band; a curved piece
  // alone in its chain: its own bands, plan/banded_profile.hpp).
  if (chain.bands.n > 0)
    consider(plan_banded_profile(chain.length_mm, planned.start_velocity(), planned.end_velocity(), chain.bands));
  // (a chain has bands where one of its pieces has: chain_bands)
  if (chain.max_cap_mm_s > chain.min_cap_mm_s || chain.bands.n > 0) {
    std::vector<CapStretch> stretches;
    append_stretches(chain, stretches);
    consider(following_profile(stretches, planned.start_velocity(), planned.end_velocity(), chain.limits,
                               planned.duration()));
  }
  return best ? std::move(*best) : planned;
}

AccelerationBands MotionPlanner::chain_bands(const Chain& chain) const {
  // A chain band's top is a share of the chain's smallest cap, at most the same share of each
  // piece's own cap: every speed of the band lies in that piece's band of the same index or a
  // lower one, whose acceleration is at least as large (a piece without bands: its limits').
  AccelerationBands b;
  b.n = static_cast<int>(std::size(tolerances::plan_acceleration_band_tops));
  b.max_jerk = chain.limits.max_jerk;
  for (int k = 0; k < b.n; ++k) {
    const auto i = static_cast<std::size_t>(k);
    b.top_mm_s[i] = k + 1 < b.n ? tolerances::plan_acceleration_band_tops[i] * chain.min_cap_mm_s : chain.min_cap_mm_s;
    b.acceleration[i] = std::numeric_limits<double>::infinity();
  }
  bool any = false;
  for (const Piece& p : chain.pieces) {
    const AccelerationBands& own = p.bands;
    any = any || own.n > 0;
    b.max_jerk = std::min(b.max_jerk, own.n > 0 ? own.max_jerk : p.limits.max_jerk);
    for (int k = 0; k < b.n; ++k) {
      const auto i = static_cast<std::size_t>(k);
      const double own_k = own.n > 0 ? own.at(b.top_mm_s[i]) : p.limits.max_acceleration;
      b.acceleration[i] = std::min(b.acceleration[i], own_k);
    }
  }
  if (!any) return {};  // lines only: the chain's own limits
  for (int k = 1; k < b.n; ++k) {
    const auto i = static_cast<std::size_t>(k);
    b.acceleration[i] = std::min(b.acceleration[i], b.acceleration[i - 1]);
  }
  return b;
}

void MotionPlanner::reach_from(const Junction& j) noexcept {
  if (j.smooth()) return;
  reach_share_ = j.jerk_share;
  reach_left_s_ = tolerances::plan_junction_share_reach_periods * period_;
}

PathLimits MotionPlanner::piece_limits(const Piece& piece, double share, bool end_smooth, double end_velocity) const {
  const auto end_weight = [](bool smooth) {
    return smooth ? tolerances::plan_share_choice_change_weight : 0.5;
  };
  // The speed changes at the ends start from the slower junction that is not smooth: 0 at a stop
  // or a corner, near the cap at a small jump of curvature (a spiral of arcs: a jump at each arc,
  // the speed through it almost the arcs' cap; from rest, the change outweighed the arcs' length,
  // and each took the middle centripetal share: arceye-circle-slowdown at 0.81 of the reference's
  // speed on the jerk = A / T machine).
  double from = std::numeric_limits<double>::infinity();  // [mm/s]
  if (!piece.start_smooth) from = std::min(from, piece.start_velocity);
  if (!end_smooth) from = std::min(from, end_velocity);
  // (a piece with a corner or a stop at both ends is alone in its chain: planned by speed bands)
  return path_limits(piece.geometry, piece.length_mm, piece.feed_mm_s, machine_,
                     {.junction_jerk_share = share,
                      .change_weight = end_weight(piece.start_smooth) + end_weight(end_smooth),
                      .alone = !piece.start_smooth && !end_smooth,
                      .change_from_mm_s = std::isfinite(from) ? from : 0.0});
}

void MotionPlanner::settle_last(double end_share, bool end_smooth, double end_velocity) {
  if (open_.pieces.empty()) return;
  Piece& p = open_.pieces.back();
  const double share = std::max(p.start_share, end_share);
  if (share == p.planned_share && end_smooth == p.planned_end_smooth && end_velocity == p.planned_end_velocity) return;
  // The open chain is not in the look-ahead yet: the piece's limits may still change either way.
  p.planned_share = share;
  p.planned_end_smooth = end_smooth;
  p.planned_end_velocity = end_velocity;
  const double old_cap = p.limits.max_velocity;
  p.limits = piece_limits(p, share, end_smooth, end_velocity);
  if (p.limits.max_velocity == old_cap) return;
  // Its cap changed: it may no longer belong to the chain (add_piece decides anew).
  Piece moved = std::move(p);
  open_.pieces.pop_back();
  open_.recount();
  add_piece(std::move(moved));
}

void MotionPlanner::close_chain(double end_velocity, double next_cap_mm_s) {
  if (open_.pieces.empty()) return;
  const double inf = std::numeric_limits<double>::infinity();
  raise_chain_lows(open_, open_.pieces.front().start_smooth ? last_chain_end_cap_mm_s_ : inf,
                   std::isinf(end_velocity) ? next_cap_mm_s : inf);
  last_chain_end_cap_mm_s_ = std::isinf(end_velocity) ? open_.pieces.back().limits.max_velocity : inf;
  MoveConstraint mc;
  mc.limits = open_.pieces.front().limits;
  mc.limits.max_velocity = open_.min_cap_mm_s;
  for (Piece& p : open_.pieces) {
    p.bands = acceleration_bands(p.geometry, p.limits, machine_, p.planned_share);  // (its limits are final)
    mc.length_mm += p.length_mm;
    mc.limits.max_acceleration = std::min(mc.limits.max_acceleration, p.limits.max_acceleration);
    mc.limits.max_jerk = std::min(mc.limits.max_jerk, p.limits.max_jerk);
  }
  mc.max_end_velocity = std::min(mc.limits.max_velocity, end_velocity);
  open_.limits = mc.limits;
  // (a curved chain speeds up and brakes harder where it runs below its cap)
  open_.bands = chain_bands(open_);
  mc.bands = open_.bands;
  open_.smooth_end = std::isinf(end_velocity);
  lookahead_.push(mc);
  pending_.push_back(std::move(open_));
  open_ = Chain{};
}

void MotionPlanner::dwell(double seconds, long source_line) {
  if (finished_ || !(seconds > 0.0)) return;
  if (!open_.pieces.empty()) {
    settle_last(0.0, false, 0.0);  // it ends at rest: no junction
    close_chain(0.0);
  }
  last_exact_stop_ = true;  // the next move starts from rest
  if (pending_.empty()) {   // before the first move, or after moves already released at rest
    initial_hold_s_ += seconds;
    initial_hold_line_ = source_line;
    return;
  }
  trajectory::Segment& p = pending_.back().pieces.back().segment;
  p.hold_after_s += seconds;
  p.hold_after_line = source_line;
  lookahead_.limit_last_end_velocity(0.0);
}

void MotionPlanner::finish() {
  if (!finished_ && !open_.pieces.empty()) {
    settle_last(0.0, false, 0.0);  // the last move ends at rest
    close_chain(0.0);
  }
  finished_ = true;
  lookahead_.finish();
  release_ready();
}

void MotionPlanner::release_ready() {
  while (lookahead_.ready()) {
    Chain chain = std::move(pending_.front());
    pending_.pop_front();
    // (one profile over chains of much smaller and larger acceleration is rarely faster)
    if (!held_.empty()) {
      const double a = chain.limits.max_acceleration, held_a = held_.front().chain.limits.max_acceleration;
      if (a > tolerances::plan_held_acceleration_ratio * held_a || held_a > tolerances::plan_held_acceleration_ratio * a)
        release_held();
    }
    const bool joins_next = chain.smooth_end;
    for (std::size_t k = 0; k < chain.pieces.size(); ++k)
      if (k == 0 || chain.pieces[k].segment.move != chain.pieces[k - 1].segment.move) ++held_pieces_;
    held_.push_back({std::move(chain), lookahead_.pop()});
    if (!joins_next || held_pieces_ >= tolerances::plan_held_max_pieces) release_held();
  }
  if (finished_ && pending_.empty() && open_.pieces.empty()) {
    release_held();
    out_->close();
  }
}

void MotionPlanner::release_held() {
  if (held_.empty()) return;
  // Each chain's own profile, between the look-ahead's speeds at its ends ...
  std::vector<trajectory::PathProfile> own;
  own.reserve(held_.size());
  for (const Planned& p : held_) own.push_back(chain_profile(p.chain, p.planned));
  // ... or, over runs of them, one profile carrying the acceleration across their junctions.
  std::vector<Run> runs;
  fastest_runs(0, held_.size(), own, runs);
  for (Run& r : runs) {
    if (r.profile) {
      double offset = 0.0, t0 = 0.0;  // along the run's profile [mm], [s]
      for (std::size_t k = r.first; k < r.last; ++k) release_chain(held_[k].chain, *r.profile, offset, t0, k + 1 == r.last);
    } else {
      for (std::size_t k = r.first; k < r.last; ++k) {
        double offset = 0.0, t0 = 0.0;
        release_chain(held_[k].chain, own[k], offset, t0, true);
      }
    }
  }
  held_.clear();
  held_pieces_ = 0;
}

double MotionPlanner::fastest_runs(std::size_t first, std::size_t last, const std::vector<trajectory::PathProfile>& own,
                                   std::vector<Run>& out) const {
  double own_s = 0.0, planned_s = 0.0;  // [s]
  for (std::size_t k = first; k < last; ++k) {
    own_s += own[k].duration();
    planned_s += held_[k].planned.duration();
  }
  std::optional<trajectory::PathProfile> whole;
  if (last - first > 1) {
    std::vector<CapStretch> stretches;
    PathLimits least = held_[first].chain.limits;
    for (std::size_t k = first; k < last; ++k) {
      const Chain& c = held_[k].chain;
      append_stretches(c, stretches);
      least.max_velocity = std::min(least.max_velocity, c.limits.max_velocity);
      least.max_acceleration = std::min(least.max_acceleration, c.limits.max_acceleration);
      least.max_jerk = std::min(least.max_jerk, c.limits.max_jerk);
    }
    whole = following_profile(stretches, held_[first].planned.start_velocity(), held_[last - 1].planned.end_velocity(),
                              least, planned_s);
  }
  const double whole_s = whole ? whole->duration() : own_s;
  // Where one profile over all is not faster, each half the fastest way.
  if (!(whole_s < own_s) && last - first >= tolerances::plan_held_split_chains) {
    std::vector<Run> halves;
    const std::size_t mid = first + (last - first) / 2;
    const double halves_s = fastest_runs(first, mid, own, halves) + fastest_runs(mid, last, own, halves);
    if (halves_s < own_s) {
      for (Run& r : halves) out.push_back(std::move(r));
      return halves_s;
    }
  }
  if (whole && whole_s < own_s) {
    out.push_back({first, last, std::move(whole)});
    return whole_s;
  }
  out.push_back({first, last, std::nullopt});
  return own_s;
}

void MotionPlanner::release_chain(Chain& chain, const trajectory::PathProfile& profile, double& offset, double& t0,
                                  bool last) {
  // Each piece runs through its window of the profile.
  for (std::size_t k = 0; k < chain.pieces.size(); ++k) {
    trajectory::Segment& seg = chain.pieces[k].segment;
    const double next = offset + chain.pieces[k].length_mm;
    const double t1 = last && k + 1 == chain.pieces.size() ? profile.duration() : std::max(t0, profile.time_at(next));
    seg.profile = profile;
    seg.window_t0_s = t0;
    seg.window_t1_s = t1;
    seg.window_s0_mm = offset;
    out_->append(std::move(seg));
    offset = next;
    t0 = t1;
  }
}

}  // namespace kontur::plan
