// The time-optimal reference: analytic rest-to-rest times (trapezoid, triangle, axis projections
// of the limits on a diagonal line, a right-angle corner as two stops), the speed on circles,
// convergence of the grid, every constraint held at the grid points, and the online planner never
// faster than the reference (it is a lower bound).
#include <gtest/gtest.h>
#include "support/planner_run.hpp"
#include <kontur/error.hpp>
#include <kontur/geometry/helix_arc.hpp>
#include <kontur/interpolate/curve_interpolator.hpp>
#include <kontur/geometry/length.hpp>
#include <kontur/geometry/line_segment.hpp>
#include <kontur/plan/motion_planner.hpp>
#include <kontur/plan/time_optimal.hpp>
#include <kontur/tolerances.hpp>

#include <cmath>
#include <memory>
#include <numbers>

namespace kontur::plan {
namespace {

constexpr double pi = std::numbers::pi;

// Rest-to-rest time [s] over L [mm] with speed limit v and acceleration a: trapezoid or triangle.
double rest_to_rest_time(double L, double v, double a) {
  if (L >= v * v / a) return L / v + v / a;
  return 2.0 * std::sqrt(L / a);
}

// A machine with equal axes, a large max feed (so that the axis limits decide) and a loose chord
// tolerance unless a test sets it.
Machine machine(double v_axis, double a_axis) {
  Machine m = default_machine();
  for (AxisLimits& ax : m.axes) {
    ax.max_velocity = v_axis;
    ax.max_acceleration = a_axis;
  }
  m.max_feed_mm_s = 1e5;
  return m;
}

struct Path {
  std::vector<std::shared_ptr<const Curve>> curves;
  std::vector<TimeOptimalMove> moves;
  void add(std::shared_ptr<const Curve> c, double feed, bool exact = false) {
    moves.push_back({c.get(), feed, exact});
    curves.push_back(std::move(c));
  }
  void line(Vec3 a, Vec3 b, double feed, bool exact = false) { add(std::make_shared<LineSegment>(a, b), feed, exact); }
};

CircleFrame frame(Vec3 centre, Vec3 e1, Vec3 normal) {
  CircleFrame f;
  f.centre = centre;
  f.normal = normal.normalized();
  f.e1 = (e1 - e1.dot(f.normal) * f.normal).normalized();
  f.e2 = f.normal.cross(f.e1);
  return f;
}

TEST(TimeOptimal, LineAlongAnAxisIsTheTrapezoidOrTheTriangle) {
  const Machine m = machine(200.0, 2000.0);
  for (const auto& [L, F] : {std::pair{100.0, 50.0}, {1.0, 200.0}, {30.0, 150.0}}) {
    Path p;
    p.line({0, 0, 0}, {L, 0, 0}, F);
    const TimeOptimalProfile r = time_optimal_profile(p.moves, m);
    const double expected = rest_to_rest_time(L, F, 2000.0);
    EXPECT_NEAR(r.total_time_s, expected, 1e-5 * expected) << "L " << L << " F " << F;
    EXPECT_NEAR(r.length_mm, L, 1e-12 * L);
    EXPECT_EQ(r.v_mm_s.front(), 0.0);
    EXPECT_EQ(r.v_mm_s.back(), 0.0);
  }
}

TEST(TimeOptimal, DiagonalLineTakesEachAxisLimitOverItsTangentShare) {
  // Direction (3, 4, 0) / 5: speed min(200 / 0.8, F) and acceleration 2000 / 0.8, both set by Y.
  const Machine m = machine(200.0, 2000.0);
  const Vec3 d = Vec3(3, 4, 0) / 5.0;
  for (const double F : {1000.0, 100.0}) {
    Path p;
    p.line({1, 2, 3}, Vec3(1, 2, 3) + 100.0 * d, F);
    const TimeOptimalProfile r = time_optimal_profile(p.moves, m);
    const double expected = rest_to_rest_time(100.0, std::min(F, 250.0), 2500.0);
    EXPECT_NEAR(r.total_time_s, expected, 1e-5 * expected) << "F " << F;
  }
  // The max feed caps the path speed as well.
  Machine slow = m;
  slow.max_feed_mm_s = 120.0;
  Path p;
  p.line({0, 0, 0}, 100.0 * d, 1000.0);
  EXPECT_NEAR(time_optimal_profile(p.moves, slow).total_time_s, rest_to_rest_time(100.0, 120.0, 2500.0), 1e-5);
}

TEST(TimeOptimal, RightAngleCornerIsTwoStopToStopProfiles) {
  const Machine m = machine(200.0, 2000.0);
  Path p;
  p.line({0, 0, 0}, {50, 0, 0}, 150.0);
  p.line({50, 0, 0}, {50, 30, 0}, 150.0);
  const TimeOptimalProfile r = time_optimal_profile(p.moves, m);
  const double expected = rest_to_rest_time(50.0, 150.0, 2000.0) + rest_to_rest_time(30.0, 150.0, 2000.0);
  EXPECT_NEAR(r.total_time_s, expected, 1e-5 * expected);
  EXPECT_EQ(r.corners, 1u);
  // The corner's grid point is at rest.
  for (std::size_t k = 0; k < r.s_mm.size(); ++k)
    if (std::abs(r.s_mm[k] - 50.0) < 1e-12) {
      EXPECT_EQ(r.v_mm_s[k], 0.0);
    }
  // Collinear moves are no corner, and an exact stop is a stop.
  Path straight;
  straight.line({0, 0, 0}, {50, 0, 0}, 150.0);
  straight.line({50, 0, 0}, {80, 0, 0}, 150.0);
  EXPECT_NEAR(time_optimal_profile(straight.moves, m).total_time_s, rest_to_rest_time(80.0, 150.0, 2000.0), 1e-5);
  straight.moves[0].exact_stop = true;
  EXPECT_NEAR(time_optimal_profile(straight.moves, m).total_time_s, expected, 1e-5 * expected);
}

TEST(TimeOptimal, ServoPeriodCornerRuleAllowsTheOnePeriodVelocityJump) {
  // A right angle: the tangent jumps by 1 on X and on Y; the speed through it is A T = 2 mm/s.
  const Machine m = machine(200.0, 2000.0);
  Path p;
  p.line({0, 0, 0}, {50, 0, 0}, 150.0);
  p.line({50, 0, 0}, {50, 30, 0}, 150.0);
  TimeOptimalOptions o;
  o.corners = CornerRule::servo_period;
  const TimeOptimalProfile r = time_optimal_profile(p.moves, m, o);
  for (std::size_t k = 0; k < r.s_mm.size(); ++k)
    if (std::abs(r.s_mm[k] - 50.0) < 1e-12) {
      EXPECT_NEAR(r.v_mm_s[k], 2000.0 * m.servo_period_s, 1e-9);
    }
  EXPECT_LT(r.total_time_s, time_optimal_profile(p.moves, m).total_time_s);
}

TEST(TimeOptimal, FullCircleRunsAtTheFeedOrAtTheCentripetalLimit) {
  const Machine m = machine(500.0, 2000.0);
  const double R = 50.0;
  // Slow feed, circle in a tilted plane: the feed in the middle. The tangent at the start and end
  // is e2 = n x e1 = (1, 1, -1) / sqrt(3), so the path acceleration there is A sqrt(3); the
  // acceleration phases are 0.014 mm long (centripetal part 2 mm/s^2 of 2000): time
  // L/F + F/(A sqrt 3) to 1e-5 s (the centripetal part changes the 2.9 ms of acceleration by 1e-3).
  {
    Path p;
    p.add(std::make_shared<HelixArc>(frame({5, -3, 2}, {1, 0, 1}, {-1, 2, 1}), R, 2.0 * pi), 10.0);
    const TimeOptimalProfile r = time_optimal_profile(p.moves, m);
    const double L = 2.0 * pi * R;
    EXPECT_NEAR(r.total_time_s, L / 10.0 + 10.0 / (2000.0 * std::sqrt(3.0)), 1e-5);
    for (std::size_t k = 0; k < r.s_mm.size(); ++k)
      if (r.s_mm[k] > 1.0 && r.s_mm[k] < L - 1.0) {
        EXPECT_NEAR(r.v_mm_s[k], 10.0, 1e-9);
      }
  }
  // Fast feed, circle in XY: where the normal is along X (t along Y), |k_x| v^2 <= A_x alone
  // bounds the speed: v = sqrt(A R); nowhere faster than the MVC.
  {
    Path p;
    p.add(std::make_shared<HelixArc>(frame({0, 0, 0}, {1, 0, 0}, {0, 0, 1}), R, 2.0 * pi), 1000.0);
    const TimeOptimalProfile r = time_optimal_profile(p.moves, m);
    const double v_centripetal = std::sqrt(2000.0 * R);
    ASSERT_LT(v_centripetal, chord_limited_feed(R, m.chord_tolerance_mm, m.servo_period_s));
    const double L = 2.0 * pi * R;
    bool found = false;
    for (std::size_t k = 0; k < r.s_mm.size(); ++k) {
      EXPECT_LE(r.v_mm_s[k], r.mvc_mm_s[k] * (1 + 1e-12));
      if (std::abs(r.s_mm[k] - L / 2.0) < 1e-9) {  // phi = pi: normal along +X
        EXPECT_NEAR(r.v_mm_s[k], v_centripetal, 1e-3 * v_centripetal);
        found = true;
      }
    }
    EXPECT_TRUE(found);
    // Never below the speed of the slowest constant-speed run, never above the MVC's time.
    EXPECT_LT(r.total_time_s, L / v_centripetal + 2.0 * v_centripetal / 2000.0);
  }
}

// Independent check at every grid point: the curve's tangent and curvature vector from its own
// arc-length table, the acceleration of the segment that starts there, every limit.
void expect_constraints_hold(const Path& p, const TimeOptimalProfile& r, const Machine& m) {
  std::vector<std::unique_ptr<ArcLengthTable>> tables;
  for (const auto& mv : p.moves) tables.push_back(std::make_unique<ArcLengthTable>(*mv.curve));
  for (std::size_t k = 0; k + 1 < r.s_mm.size(); ++k) {
    const std::size_t mi = r.move_index[k];
    const Curve& c = *p.moves[mi].curve;
    const Derivatives d = c.derivatives(tables[mi]->u_of_s(r.move_s_mm[k]), 2);
    const Vec3 t = d[1].normalized();
    const Vec3 kv = (d[2] - d[2].dot(t) * t) / d[1].squaredNorm();
    const double v = r.v_mm_s[k];
    const double a = (r.v_mm_s[k + 1] * r.v_mm_s[k + 1] - v * v) / (2.0 * (r.s_mm[k + 1] - r.s_mm[k]));
    ASSERT_TRUE(std::isfinite(v) && std::isfinite(a));
    EXPECT_LE(v, std::min(p.moves[mi].feed_mm_s, m.max_feed_mm_s) * (1 + 1e-12));
    if (kv.norm() > 0.0) {
      EXPECT_LE(v, chord_limited_feed(1.0 / kv.norm(), m.chord_tolerance_mm, m.servo_period_s) * (1 + 1e-9));
    }
    for (int i = 0; i < 3; ++i) {
      const AxisLimits& ax = m.axes[static_cast<std::size_t>(i)];
      EXPECT_LE(std::abs(v * t[i]), ax.max_velocity * (1 + 1e-12)) << "k " << k << " axis " << i;
      EXPECT_LE(std::abs(t[i] * a + kv[i] * v * v), ax.max_acceleration * (1 + 1e-9) + 1e-9)
          << "k " << k << " axis " << i << " s " << r.s_mm[k];
    }
  }
}

// Lines, a tangent arc, a corner, a tilted 3-D arc and a helix: a path with every kind of limit.
Path mixed_path() {
  Path p;
  p.line({0, 0, 0}, {40, 0, 0}, 300.0);
  p.add(std::make_shared<HelixArc>(frame({40, 20, 0}, {0, -1, 0}, {0, 0, 1}), 20.0, pi / 2), 300.0);
  p.line({60, 20, 0}, {60, 40, 0}, 300.0);
  p.line({60, 40, 0}, {30, 45, 3}, 250.0);  // corner
  p.add(std::make_shared<HelixArc>(frame({30, 40, 3}, {0, 1, 0}, {1, 1, 2}), 5.0, 1.5 * pi), 400.0);
  p.add(std::make_shared<HelixArc>(frame({0, 0, 10}, {1, 0, 0}, {0, 0, 1}), 2.0, 4.0 * pi, 3.0), 200.0, true);
  p.line(p.curves.back()->point(1.0), {0, 0, 0}, 500.0);
  return p;
}

TEST(TimeOptimal, EveryConstraintHoldsAtTheGridPoints) {
  Machine m = machine(200.0, 2000.0);
  m.axes[1].max_acceleration = 1200.0;  // unequal axes
  m.axes[2].max_velocity = 80.0;
  const Path p = mixed_path();
  for (const CornerRule rule : {CornerRule::stop, CornerRule::servo_period}) {
    TimeOptimalOptions o;
    o.corners = rule;
    const TimeOptimalProfile r = time_optimal_profile(p.moves, m, o);
    EXPECT_GT(r.corners, 0u);
    expect_constraints_hold(p, r, m);
    for (std::size_t k = 0; k < r.s_mm.size(); ++k) EXPECT_LE(r.v_mm_s[k], r.mvc_mm_s[k] * (1 + 1e-12));
  }
}

TEST(TimeOptimal, HalvingTheGridChangesTheTimeByLessThanTheStatedError) {
  const Machine m = machine(200.0, 2000.0);
  const Path p = mixed_path();
  TimeOptimalOptions coarse;
  TimeOptimalOptions fine;
  fine.max_step_mm = coarse.max_step_mm / 2;
  fine.min_intervals_per_move = coarse.min_intervals_per_move * 2;
  fine.max_turn_rad = coarse.max_turn_rad / 2;
  const double t1 = time_optimal_profile(p.moves, m, coarse).total_time_s;
  const double t2 = time_optimal_profile(p.moves, m, fine).total_time_s;
  EXPECT_LT(std::abs(t1 - t2), tolerances::time_optimal_grid_relative * t2) << t1 << " " << t2;
  // Refining approaches from above or below, but the change shrinks: first order at most.
  TimeOptimalOptions finer = fine;
  finer.max_step_mm /= 2;
  finer.min_intervals_per_move *= 2;
  finer.max_turn_rad /= 2;
  const double t3 = time_optimal_profile(p.moves, m, finer).total_time_s;
  EXPECT_LT(std::abs(t3 - t2), 0.75 * std::abs(t2 - t1) + 1e-12);
}

// A near-cusp: C(u) = (u^3 + e u, u^2, 0), u in [-2, 1.7] (asymmetric: no grid point at u = 0 by
// symmetry); at u = 0 the tangent is X, the normal Y and the radius |C'|^3 / |C' x C''| =
// e^3 / (2 e) = e^2 / 2 (5 um for e = 0.1).
class NearCusp final : public Curve {
public:
  explicit NearCusp(double e) : e_(e) {}
  [[nodiscard]] double u_min() const noexcept override { return -2.0; }
  [[nodiscard]] double u_max() const noexcept override { return 1.7; }
  [[nodiscard]] Derivatives derivatives(double u, int order) const noexcept override {
    Derivatives d;
    d[0] = Vec3(u * u * u + e_ * u, u * u, 0.0);
    if (order >= 1) d[1] = Vec3(3 * u * u + e_, 2 * u, 0.0);
    if (order >= 2) d[2] = Vec3(6 * u, 2.0, 0.0);
    if (order >= 3) d[3] = Vec3(6.0, 0.0, 0.0);
    return d;
  }
  [[nodiscard]] std::vector<double> breakpoints() const override { return {-2.0, 1.7}; }

private:
  double e_;
};

TEST(TimeOptimal, RefinementFindsTheSlowSpotOfANearCusp) {
  // Radius e^2 / 2 = 5 um at u = 0, 0.01 mm of path where the tangent turns by nearly pi: a
  // uniform grid of 0.05 mm steps over it. There |k_y| v^2 <= A_y alone bounds the speed:
  // sqrt(A R) = 3.16 mm/s (the chord limit is 6 mm/s).
  const Machine m = machine(200.0, 2000.0);
  const double e = 0.1, R = e * e / 2.0;
  Path p;
  p.add(std::make_shared<NearCusp>(e), 100.0);
  const TimeOptimalProfile r = time_optimal_profile(p.moves, m);
  double slowest = 1e300;
  for (std::size_t k = 1; k + 1 < r.mvc_mm_s.size(); ++k) slowest = std::min(slowest, r.mvc_mm_s[k]);
  EXPECT_NEAR(slowest, std::sqrt(2000.0 * R), 0.02 * std::sqrt(2000.0 * R));
  expect_constraints_hold(p, r, m);
  // Without the refinement the grid misses it (and the time is too short).
  TimeOptimalOptions coarse;
  coarse.max_turn_rad = 10.0;
  const TimeOptimalProfile blind = time_optimal_profile(p.moves, m, coarse);
  double blind_slowest = 1e300;
  for (std::size_t k = 1; k + 1 < blind.mvc_mm_s.size(); ++k) blind_slowest = std::min(blind_slowest, blind.mvc_mm_s[k]);
  EXPECT_GT(blind_slowest, 3.0 * slowest);
  EXPECT_LT(blind.total_time_s, r.total_time_s);
}

// The online planner on an acceleration-limited machine (jerk large) is never faster.
double online_time(const Path& p, const Machine& m) {
  std::vector<program::Move> moves;
  for (std::size_t i = 0; i < p.moves.size(); ++i)
    moves.push_back(program::move_along(p.curves[i], p.moves[i].feed_mm_s, p.moves[i].exact_stop, static_cast<long>(i)));
  return testing::plan_and_sample(m, moves).back().t_s;
}

TEST(TimeOptimal, OnlinePlannerIsNeverFaster) {
  Machine m = machine(200.0, 2000.0);
  for (AxisLimits& ax : m.axes) ax.max_jerk = ax.max_acceleration / m.servo_period_s;  // one-period ramps
  Path square;
  square.line({0, 0, 0}, {40, 0, 0}, 150.0);
  square.line({40, 0, 0}, {40, 40, 0}, 150.0);
  square.line({40, 40, 0}, {0, 40, 0}, 150.0);
  square.line({0, 40, 0}, {0, 0, 0}, 150.0);
  for (const Path* p : {&square}) {
    const double online = online_time(*p, m);
    TimeOptimalOptions o;
    o.corners = CornerRule::servo_period;
    const double reference = time_optimal_profile(p->moves, m, o).total_time_s;
    EXPECT_GE(online, reference) << "online " << online << " reference " << reference;
    EXPECT_LT(online, 1.5 * reference);
  }
  const Path mixed = mixed_path();
  TimeOptimalOptions o;
  o.corners = CornerRule::servo_period;
  const double online = online_time(mixed, m);
  const double reference = time_optimal_profile(mixed.moves, m, o).total_time_s;
  EXPECT_GE(online, reference) << "online " << online << " reference " << reference;
}

// The reference's time per move (the summary's per-block time_optimal_s) is the same total cut at
// the moves: it adds up to total_time_s, a move of zero length takes none, and a move is as long
// as its own grid segments take.
TEST(TimeOptimal, MoveTimesAddUpToTheTotal) {
  const Machine m = machine(200.0, 2000.0);
  Path p = mixed_path();
  p.line({0, 0, 0}, {0, 0, 0}, 100.0);  // zero length: skipped
  p.line({0, 0, 0}, {10, 0, 0}, 100.0);
  TimeOptimalOptions o;
  o.corners = CornerRule::servo_period;
  const TimeOptimalProfile r = time_optimal_profile(p.moves, m, o);
  ASSERT_EQ(r.move_time_s.size(), p.moves.size());
  double sum = 0.0;
  for (double t : r.move_time_s) {
    EXPECT_GE(t, 0.0);
    sum += t;
  }
  EXPECT_NEAR(sum, r.total_time_s, 1e-12 * r.total_time_s);
  EXPECT_EQ(r.move_time_s[p.moves.size() - 2], 0.0);
  for (std::size_t i = 0; i < p.moves.size(); ++i) {
    if (i != p.moves.size() - 2) {
      EXPECT_GT(r.move_time_s[i], 0.0) << "move " << i;
    }
  }
  // With corners as stops the last line starts and ends at rest: its own trapezoid.
  EXPECT_NEAR(time_optimal_profile(p.moves, m).move_time_s.back(), rest_to_rest_time(10.0, 100.0, 2000.0), 1e-5);
  // Nothing to run: one zero per move.
  Path empty;
  empty.line({1, 1, 1}, {1, 1, 1}, 100.0);
  EXPECT_EQ(time_optimal_profile(empty.moves, m).move_time_s, std::vector<double>{0.0});
}

TEST(TimeOptimal, LargestGridCoarsensTheStep) {
  const Machine m = machine(200.0, 2000.0);
  Path p;
  p.line({0, 0, 0}, {1000, 0, 0}, 150.0);
  TimeOptimalOptions o;
  o.max_points = 1000;
  const TimeOptimalProfile r = time_optimal_profile(p.moves, m, o);
  EXPECT_LE(r.s_mm.size(), 1001u);
  EXPECT_NEAR(r.total_time_s, rest_to_rest_time(1000.0, 150.0, 2000.0), 1e-9 * r.total_time_s);
}

TEST(TimeOptimal, RefusesBadInput) {
  const Machine m = machine(200.0, 2000.0);
  Path p;
  p.line({0, 0, 0}, {10, 0, 0}, 0.0);
  EXPECT_THROW((void)time_optimal_profile(p.moves, m), InputError);
  p.moves[0].feed_mm_s = 100.0;
  TimeOptimalOptions o;
  o.min_intervals_per_move = 1;
  EXPECT_THROW((void)time_optimal_profile(p.moves, m, o), InputError);
  Machine xy = m;
  xy.axes.pop_back();  // no Z
  Path z;
  z.line({0, 0, 0}, {0, 0, 10}, 100.0);
  EXPECT_THROW((void)time_optimal_profile(z.moves, xy), InputError);
  // Zero-length moves are skipped; nothing to run takes no time.
  Path empty;
  empty.line({1, 1, 1}, {1, 1, 1}, 100.0);
  EXPECT_EQ(time_optimal_profile(empty.moves, m).total_time_s, 0.0);
}

}  // namespace
}  // namespace kontur::plan
