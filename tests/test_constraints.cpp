// The constraints both planners share (plan/constraints.hpp), and the one rule for an axis the
// machine lacks: a path that moves along it has a speed cap of zero (the online planner) and is
// refused (the time-optimal reference); a path that does not move along it is planned as on the
// machine with the axis, by both.
#include <gtest/gtest.h>
#include <kontur/geometry/curve_piece.hpp>
#include <kontur/geometry/differential.hpp>
#include <kontur/geometry/helix_arc.hpp>
#include <kontur/geometry/line_segment.hpp>
#include <kontur/geometry/nurbs.hpp>
#include <kontur/plan/constraints.hpp>
#include <kontur/plan/time_optimal.hpp>

#include "support/input_error.hpp"
#include "support/machine_limits.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>

namespace kontur::plan {
namespace {

// The default machine (200 mm/s, 2000 mm/s^2 per axis) with a max feed the axes decide.
Machine full_machine() {
  Machine m = default_machine();
  m.max_feed_mm_s = 1e5;
  return m;
}

Machine without_z() {
  Machine m = full_machine();
  m.axes.pop_back();  // X Y Z: no Z
  m.name = "no Z";
  return m;
}

// Largest speed of the time-optimal reference's maximum velocity curve inside the path.
double reference_cap(const Curve& c, double feed, const Machine& m) {
  const TimeOptimalMove move{&c, feed, false};
  const TimeOptimalProfile r = time_optimal_profile({&move, 1}, m);
  return r.mvc_mm_s[r.mvc_mm_s.size() / 2];
}

TEST(MissingAxis, BothPlannersGiveTheSameCapOnAMachineWithoutZForAPathInXY) {
  const Machine full = full_machine(), xy = without_z();
  const LineSegment line({0, 0, 0}, {30, 40, 0});
  const double feed = 1000.0;
  // The online planner's cap of the stretch and the reference's at its points: V_Y / |t_Y| here.
  const double la = speed_cap(path_geometry(line, line.u_min(), line.u_max()), feed, xy, 0.5);
  EXPECT_DOUBLE_EQ(la, 200.0 / 0.8);
  EXPECT_DOUBLE_EQ(reference_cap(line, feed, xy), la);
  // Both plan such a path as on the machine with Z: the axis bounds nothing.
  const HelixArc arc(CircleFrame{}, 20.0, 1.5 * std::numbers::pi);
  for (const Curve* c : {static_cast<const Curve*>(&line), static_cast<const Curve*>(&arc)}) {
    const PathLimits a = move_limits({c, 1.0, feed}, xy), b = move_limits({c, 1.0, feed}, full);
    EXPECT_EQ(a.max_velocity, b.max_velocity);
    EXPECT_EQ(a.max_acceleration, b.max_acceleration);
    EXPECT_EQ(a.max_jerk, b.max_jerk);
    const TimeOptimalMove move{c, feed, false};
    EXPECT_EQ(time_optimal_profile({&move, 1}, xy).total_time_s, time_optimal_profile({&move, 1}, full).total_time_s);
  }
  // A tangent component at the tolerance is rounding, not motion along Z.
  const Vec3 t = Vec3(0.6, 0.8, tolerances::missing_axis_tangent).normalized();
  EXPECT_EQ(missing_axis_moved(t, linear_axes(xy)), -1);
  EXPECT_EQ(velocity_cap(t, feed, xy, linear_axes(xy)), velocity_cap(t, feed, full, linear_axes(full)));
}

TEST(MissingAxis, BothPlannersRefuseAPathThatMovesZOnAMachineWithoutZ) {
  const Machine xy = without_z();
  const LineSegment line({0, 0, 0}, {10, 0, 10});
  const HelixArc helix(CircleFrame{}, 20.0, std::numbers::pi, 5.0);  // rises along Z
  for (const Curve* c : {static_cast<const Curve*>(&line), static_cast<const Curve*>(&helix)}) {
    // The online planner: a speed cap of zero.
    EXPECT_EQ(speed_cap(path_geometry(*c, c->u_min(), c->u_max()), 100.0, xy, 0.5), 0.0);
    EXPECT_EQ(move_limits({c, 10.0, 100.0}, xy).max_velocity, 0.0);
    EXPECT_EQ(velocity_cap(c->derivatives(c->u_min(), 1)[1].normalized(), 100.0, xy, linear_axes(xy)), 0.0);
    // The reference: refused, naming the axis.
    const TimeOptimalMove move{c, 100.0, false};
    testing::expect_input_error([&] { (void)time_optimal_profile({&move, 1}, xy); }, "missing-axis", "axis Z");
  }
  EXPECT_EQ(missing_axis_moved(Vec3(0, 0, 1), linear_axes(xy)), 2);
  EXPECT_EQ(missing_axis_moved(Vec3(0, 0, 1), linear_axes(full_machine())), -1);
}

TEST(Constraints, CornerAccelerationCapIsTheOnePeriodVelocityJump) {
  const Machine m = without_z();  // A = 2000 mm/s^2, T = 1 ms
  const LinearAxes axes = linear_axes(m);
  // A right angle in XY: each axis's tangent jumps by 1, v <= share A T.
  EXPECT_DOUBLE_EQ(corner_acceleration_cap(Vec3(-1, 1, 0), m, axes, 1.0, 0.0), 2.0);
  EXPECT_DOUBLE_EQ(corner_acceleration_cap(Vec3(-1, 1, 0), m, axes, 0.1, 1e-9), 0.2);
  // Jumps at or below ignore_below, and on axes the machine lacks, bound nothing.
  EXPECT_TRUE(std::isinf(corner_acceleration_cap(Vec3(1e-10, 0, 1), m, axes, 1.0, 1e-9)));
}

TEST(Constraints, BothCurvatureFormsGiveTheCurvatureVector) {
  // A circle of radius 20 in XY, at a point where |C'| is not 1: K = -p / R^2, |K| = 1 / R.
  const HelixArc arc(CircleFrame{}, 20.0, std::numbers::pi);
  const Derivatives d = arc.derivatives(0.3, 3);
  const auto [t, k] = tangent_and_curvature(d);
  const Vec3 k2 = curvature_vector_and_rate(d).first;
  EXPECT_NEAR(k.norm(), 1.0 / 20.0, 1e-15);
  EXPECT_NEAR((k - k2).norm(), 0.0, 1e-15);
  EXPECT_NEAR(t.dot(k), 0.0, 1e-15);
  EXPECT_NEAR(k.dot(arc.point(0.3)), -1.0, 1e-12);  // towards the centre: K = -p / R^2
}

TEST(Constraints, ArcKeepsTheAccelerationItsTangentAndCurvatureLeaveTogether) {
  // On a circle of radius R the x component of the acceleration is -sin(theta) a - cos(theta) v^2/R:
  // at a centripetal share c of A the path may accelerate by sqrt(1 - c^2) A, not (1 - c) A as the
  // maxima of |t_x| and |K_x| alone allow (PathGeometry::pairs). (A stiff machine: the cross term
  // 3 K v a of the jerk bounds nothing.)
  Machine m = full_machine();
  for (AxisLimits& axis : m.axes) axis.max_jerk = 1e9;
  const double r_mm = 20.0, a_max = m.axes[0].max_acceleration;
  const HelixArc arc(CircleFrame{}, r_mm, 1.5 * std::numbers::pi);
  const PathGeometry g = path_geometry(arc, arc.u_min(), arc.u_max());
  for (const double c : {0.5, 0.7, 0.9}) {
    const double v = std::sqrt(c * a_max * r_mm);
    const double a = path_limits_at(g, v, m, 0.0).max_acceleration;
    SCOPED_TRACE(c);
    EXPECT_LE(a, std::sqrt(1.0 - c * c) * a_max);         // a bound: never above the exact share
    // and near it (the maxima alone: (1 - c) A, at c = 0.9 a fifth of what is left)
    EXPECT_GE(a, (c < 0.8 ? 0.85 : 0.7) * std::sqrt(1.0 - c * c) * a_max);
  }
}

TEST(Constraints, AxisFarSlowerThanTheOthersLeavesAHelixAccelerationAtItsCap) {
  // LinuxCNC's XY_slowZ.ini: Z has 1/300 of X's and Y's limits. Along a flat helix (half a turn of
  // radius 12.7 mm falling 0.05 mm) Z's curvature is zero, but the bound of what may lie between
  // samples raised it to 4e-4 / mm in the pairs, which at the cap the maxima allowed was beyond Z's
  // limit: no path acceleration was left, and path_limits took the first axis's (762 mm/s^2) on a
  // circle whose centripetal part already took 600 of it (helix_slowdown: X at 1.10 times its limit).
  // At the cap and acceleration path_limits gives, every axis stays within its limit at every point.
  Machine m = full_machine();
  testing::set_every_axis(m, 203.2, 762.0, 76200.0);
  m.axes[2].max_velocity = 0.254;
  m.axes[2].max_acceleration = 2.54;
  m.axes[2].max_jerk = 254.0;
  const HelixArc helix(CircleFrame{Vec3(12.7, 0, 0.0508), Vec3(-1, 0, 0), Vec3(0, -1, 0), Vec3(0, 0, 1)}, 12.7,
                       std::numbers::pi, -0.0508);
  const PathGeometry g = path_geometry(helix, helix.u_min(), helix.u_max());
  const PathLimits l = path_limits(g, 39.0, 423.3, m);
  ASSERT_GT(l.max_velocity, 0.0);
  ASSERT_GT(l.max_acceleration, 0.0);
  for (int k = 0; k <= 1000; ++k) {
    const double u = helix.u_min() + (helix.u_max() - helix.u_min()) * k / 1000.0;
    const auto [t, kv] = tangent_and_curvature(helix.derivatives(u, 2));
    for (int i = 0; i < 3; ++i)
      EXPECT_LE(std::abs(t[i]) * l.max_acceleration + std::abs(kv[i]) * l.max_velocity * l.max_velocity,
                m.axes[static_cast<std::size_t>(i)].max_acceleration * (1.0 + 1e-9))
          << "axis " << i << " at u " << u;
  }
}

TEST(Constraints, PairedBoundHoldsAtEveryPointOfRandomNurbs) {
  // Seeded random cubic NURBS (weights 0.2..5): at the speed cap and the path acceleration of each
  // span, |t_i| a + |K_i| v^2 stays within A_i at 2 000 points of the span, not only at the samples.
  Machine m = full_machine();
  for (AxisLimits& axis : m.axes) axis.max_jerk = 1e9;  // (the jerk's cross term bounds nothing)
  std::mt19937 rng(20261203);
  std::uniform_real_distribution<double> coord(-20.0, 20.0), logw(std::log(0.2), std::log(5.0));
  double worst = 0.0;
  for (int trial = 0; trial < 200; ++trial) {
    NurbsData d;
    d.degree = 3;
    d.knots = {0, 0, 0, 0, 1, 1, 1, 1};
    for (int k = 0; k < 4; ++k) {
      d.points.push_back({coord(rng), coord(rng), trial % 2 == 0 ? 0.0 : coord(rng)});
      d.weights.push_back(std::exp(logw(rng)));
    }
    const NurbsCurve c(d);
    const PathGeometry g = path_geometry(c, 0.0, 1.0);
    for (const double share : tolerances::plan_centripetal_shares) {
      const double v = speed_cap(g, 1e5, m, share);
      const double a = path_limits_at(g, v, m, 0.0).max_acceleration;
      for (int k = 0; k <= 2000; ++k) {
        const auto [t, kv] = tangent_and_curvature(c.derivatives(k / 2000.0, 2));
        for (int i = 0; i < 3; ++i)
          worst = std::max(worst, (std::abs(t[i]) * a + std::abs(kv[i]) * v * v) / m.axes[static_cast<std::size_t>(i)].max_acceleration);
      }
    }
  }
  EXPECT_LE(worst, 1.0 + 1e-9);
  EXPECT_GE(worst, 0.9);  // (and the bound is not slack everywhere)
}

// An arc's geometry bounds come from its samples and the exact rise of a sinusoid between them
// (every component of t, K and dK/ds is a constant plus a sinusoid of the angle), not from the 5 %
// margin a general curve gets: on a full circle that margin on K_i cost 2.5 % of the speed
// (single_circle ran at 153 mm/s on the jerk = A / T machine, the reference's slowest point 165).
// On circles and helices in tilted planes, whole and in pieces, every bound holds at 20 000 points,
// each point lies under one of the pairs, and the curvature bound is within 0.6 % of |K| of the
// true maximum.
TEST(Constraints, AnArcsGeometryBoundsItsTrueMaximaWithinTheRiseBetweenSamples) {
  const Vec3 n = Vec3(0.3, -0.5, 0.81).normalized(), e1 = n.unitOrthogonal(), e2 = n.cross(e1);
  const CircleFrame tilted{Vec3(1, 2, 3), e1, e2, n};
  const auto full = std::make_shared<HelixArc>(CircleFrame{}, 35.9, 2.0 * std::numbers::pi);
  const auto helix = std::make_shared<HelixArc>(tilted, 4.0, 6.0 * std::numbers::pi, 60.0);  // steep: 3 turns, 60 mm
  const auto flat = std::make_shared<HelixArc>(tilted, 12.0, 2.2);
  const std::vector<std::shared_ptr<const Curve>> curves{
      full, helix, flat, std::make_shared<CurvePiece>(full, 0.1, 0.37), std::make_shared<CurvePiece>(helix, 0.5, 0.52)};
  for (std::size_t c = 0; c < curves.size(); ++c) {
    SCOPED_TRACE(c);
    const Curve& curve = *curves[c];
    const PathGeometry g = path_geometry(curve, curve.u_min(), curve.u_max());
    Vec3 t_max = Vec3::Zero(), k_max = Vec3::Zero(), r_max = Vec3::Zero();
    double kappa = 0.0;
    std::array<std::vector<std::array<double, 2>>, 3> pairs;
    for (int i = 0; i < 3; ++i) pairs[static_cast<std::size_t>(i)] = g.axis_pairs(i);
    for (int k = 0; k <= 20000; ++k) {
      const double u = curve.u_min() + (curve.u_max() - curve.u_min()) * k / 20000.0;
      const Derivatives d = curve.derivatives(u, 3);
      const Vec3 t = d[1].normalized();
      const auto [kv, kr] = curvature_vector_and_rate(d);
      t_max = t_max.cwiseMax(t.cwiseAbs());
      k_max = k_max.cwiseMax(kv.cwiseAbs());
      r_max = r_max.cwiseMax(kr.cwiseAbs());
      kappa = kv.norm();
      for (std::size_t i = 0; i < 3; ++i)
        EXPECT_TRUE(std::ranges::any_of(pairs[i], [&](const std::array<double, 2>& p) {
          return p[0] >= std::abs(t[static_cast<Eigen::Index>(i)]) - 1e-12 &&
                 p[1] >= std::abs(kv[static_cast<Eigen::Index>(i)]) - 1e-15;
        })) << "axis " << i << " at u " << u;
    }
    for (int i = 0; i < 3; ++i) {
      EXPECT_GE(g.tangent[i], t_max[i] - 1e-12) << i;
      EXPECT_GE(g.curvature[i], k_max[i] - 1e-15) << i;
      EXPECT_GE(g.curvature_rate[i], r_max[i] - 1e-15) << i;
      EXPECT_LE(g.curvature[i], k_max[i] + 0.006 * kappa) << i;
    }
    EXPECT_NEAR(g.max_kappa, kappa, 1e-12 * kappa);
  }
}

// A corner's velocity step (v |dt_i| / T) takes up to plan_corner_acceleration_share of an axis's
// acceleration in the period it is passed; a curve beside it may take up to 0.97 of it at its cap
// (plan_centripetal_shares), so the corner keeps the curves' centripetal acceleration there within
// the rest: two quarter circles of radius 10 mm meeting at a kink of 1e-4 rad (the step, the
// jerk and the curvature jump would allow more than 200 mm/s) pass at sqrt(0.9 A R).
TEST(Constraints, ACornerBesideACurveKeepsTheCentripetalAccelerationWithinWhatItsStepLeaves) {
  const Machine m = full_machine();  // A = 2000 mm/s^2, J = 50000 mm/s^3, T = 1 ms: step share 0.1
  const double R = 10.0, A = 2000.0, kink = 1e-4;
  const HelixArc first(CircleFrame{}, R, 0.5 * std::numbers::pi);  // ends at (0, R) heading -X
  const Vec3 p = first.point(1.0);
  const Eigen::Matrix3d turn = Eigen::AngleAxisd(kink, Vec3::UnitZ()).toRotationMatrix();
  CircleFrame f;
  f.centre = p + turn * (Vec3::Zero() - p);
  f.e1 = (p - f.centre).normalized();
  f.normal = Vec3::UnitZ();
  f.e2 = f.normal.cross(f.e1);
  const HelixArc second(f, R, 0.5 * std::numbers::pi);
  const Junction j = junction(first.derivatives_left(1.0, 2), second.derivatives(0.0, 2), m);
  ASSERT_FALSE(j.smooth());
  EXPECT_NEAR(j.velocity, std::sqrt(0.9 * A * R), 1e-9 * j.velocity);
  const Vec3 k_in = curvature_vector(first.derivatives_left(1.0, 2)), k_out = curvature_vector(second.derivatives(0.0, 2));
  for (int i = 0; i < 3; ++i)
    EXPECT_LE(std::max(std::abs(k_in[i]), std::abs(k_out[i])) * j.velocity * j.velocity, 0.9 * A * (1 + 1e-12)) << i;
}

// The share choice weighs the speed changes at a piece's ends from the speed its junctions allow:
// from rest (a stop or a corner) a quarter circle alone in its chain takes a smaller centripetal
// share (more acceleration left to reach its cap), but between two small jumps of curvature (a
// spiral of arcs, each run through almost at the arcs' cap) the largest. Until 2026-12-05 every
// end was weighed from rest: arceye-circle-slowdown ran its arcs at 0.81 of the reference's speed
// on the jerk = A / T machine (5.983 s; 5.525 s with the ends weighed from their junctions' speed,
// 5.375 s with the 0.97 share and the time a change loses against the cap, not its duration).
TEST(Constraints, AnArcBetweenSmallCurvatureJumpsTakesTheLargestCentripetalShare) {
  Machine m = full_machine();
  testing::set_every_axis(m, 203.2, 762.0, 762000.0);
  const double R = 9.65;  // [mm]
  const HelixArc arc(CircleFrame{}, R, 0.5 * std::numbers::pi);
  const PathGeometry g = path_geometry(arc, arc.u_min(), arc.u_max());
  const double largest = speed_cap(g, 1270.0, m, std::ranges::max(tolerances::plan_centripetal_shares));  // [mm/s]
  const PathLimits from_rest = path_limits(g, arc.length_mm(), 1270.0, m, {.alone = true});
  EXPECT_LT(from_rest.max_velocity, 0.98 * largest);
  const PathLimits near_cap = path_limits(g, arc.length_mm(), 1270.0, m, {.alone = true, .change_from_mm_s = 0.97 * largest});
  EXPECT_EQ(near_cap.max_velocity, largest);
  // Inside a chain (no change weighed) at most the chain's largest share: the length alone would
  // always take the largest and leave the chain's profile little acceleration.
  const PathLimits inside = path_limits(g, arc.length_mm(), 1270.0, m, {.change_weight = 0.0});
  EXPECT_EQ(inside.max_velocity, speed_cap(g, 1270.0, m, tolerances::plan_chain_centripetal_share_max));
}

// An arc that starts its chain at a corner and runs on into the next piece smoothly (half of
// arc-terminal: a quarter inch circle from a line's corner to a curvature jump) speeds up under its
// speed bands, as the look-ahead and the chain profile plan it, so its share is chosen by them as
// for an arc alone: the largest, not the third, which the cap's acceleration (0.24 A at 0.97)
// would have chosen. Until 2026-12-05 only an arc alone was estimated by its bands: arc-terminal
// at 1.1005 of the reference on the jerk = A / T machine, 1.0931 with its bands.
TEST(Constraints, AnArcAtTheStartOfAChainIsEstimatedByItsSpeedBands) {
  Machine m = full_machine();
  testing::set_every_axis(m, 203.2, 762.0, 762000.0);
  const double R = 2.54;  // [mm]
  const HelixArc arc(CircleFrame{}, R, std::numbers::pi);
  const PathGeometry g = path_geometry(arc, arc.u_min(), arc.u_max());
  const double feed = 423.33;  // [mm/s]
  const PathLimits alone = path_limits(g, arc.length_mm(), feed, m, {.alone = true});
  const PathLimits chain_start = path_limits(g, arc.length_mm(), feed, m, {.change_weight = 0.5, .change_from_mm_s = 5.0});
  EXPECT_GT(chain_start.max_velocity, speed_cap(g, feed, m, tolerances::plan_chain_centripetal_share_max) * 1.01);
  EXPECT_GE(chain_start.max_velocity, alone.max_velocity);
}

// On a circle of radius R the curvature vector turns at |dK/ds| = 1/R^2, so K'_i v^3 caps the
// speed where the jerk is small against the acceleration. A piece inside a chain (ends weighed
// little) may give that term more of the jerk than the first share, as long as the path keeps
// plan_path_jerk_share_min of it, up to the chain's largest (plan_chain_curvature_rate_share_max),
// and the largest at a low of its chain's caps (at_a_low: the motion passes it at its cap, so the
// path's own jerk matters little there); next to a junction that takes half the jerk it may not.
// Either way every axis's jerk t_i j + 3 K_i v a + K'_i v^3 stays within its limit at every point.
TEST(Constraints, CurvatureChangeTakesALargerShareInsideAChainAndNeverMoreThanTheJerkLeaves) {
  const Machine m = full_machine();  // A = 2000 mm/s^2, J = 50000 mm/s^3 per axis
  const double R = 2.0, A = 2000.0, J = 50000.0;
  const HelixArc arc(CircleFrame{}, R, 2.0 * std::numbers::pi);
  const PathGeometry g = path_geometry(arc, arc.u_min(), arc.u_max());
  const double first = std::cbrt(tolerances::plan_curvature_rate_jerk_shares[0] * J * R * R);
  const double largest = std::cbrt(std::ranges::max(tolerances::plan_curvature_rate_jerk_shares) * J * R * R);
  ASSERT_LT(largest, std::sqrt(tolerances::plan_centripetal_shares[2] * A * R));  // the rate binds
  const PathLimits inside = path_limits(g, arc.length_mm(), 1e4, m, {.change_weight = 2 * tolerances::plan_share_choice_change_weight});
  const PathLimits beside = path_limits(g, arc.length_mm(), 1e4, m, {.junction_jerk_share = tolerances::plan_smooth_junction_jerk_share});
  const PathLimits at_low = path_limits(g, arc.length_mm(), 1e4, m, {.change_weight = 0.0, .at_a_low = true});
  const double chain_largest = std::cbrt(tolerances::plan_chain_curvature_rate_share_max * J * R * R);
  EXPECT_GT(inside.max_velocity, first * 1.2);
  EXPECT_LE(inside.max_velocity, chain_largest * (1 + 1e-12));
  EXPECT_GT(at_low.max_velocity, chain_largest * 1.03);
  EXPECT_LE(at_low.max_velocity, largest * (1 + 1e-12));
  EXPECT_LE(beside.max_velocity, first * (1 + 1e-12));
  for (const auto& [l, share] : {std::pair{inside, 0.0}, std::pair{at_low, 0.0},
                                 std::pair{beside, tolerances::plan_smooth_junction_jerk_share}}) {
    ASSERT_GT(l.max_jerk, 0.0);
    const double v = l.max_velocity, a = l.max_acceleration, j = l.max_jerk;
    for (int k = 0; k < 720; ++k) {  // axis X at angle theta (Y is the same shifted by 90 degrees)
      const double th = 2.0 * std::numbers::pi * k / 720.0, st = std::abs(std::sin(th)), ct = std::abs(std::cos(th));
      EXPECT_LE(st * a + ct / R * v * v, A * (1 + 1e-12)) << th;
      EXPECT_LE(st * j + 3.0 * ct / R * v * a + st / (R * R) * v * v * v, (1.0 - share) * J * (1 + 1e-12)) << th;
    }
  }
}

}  // namespace
}  // namespace kontur::plan
