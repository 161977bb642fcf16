// Circle through three points (methods.md section 4, seed program ARC): the reference vectors to
// their printed digits, the curve, both motion modes, random circles in space, and every bad input.
#include <gtest/gtest.h>
#include <kontur/interpolate/arc_motion.hpp>
#include <kontur/geometry/circle_through_points.hpp>
#include <kontur/error.hpp>
#include <kontur/geometry/length.hpp>
#include <kontur/machine_limits.hpp>

#include "support/input_error.hpp"
#include "support/random_curves.hpp"

#include <Eigen/Geometry>

#include <cmath>
#include <limits>
#include <numbers>
#include <random>

namespace kontur {
namespace {

constexpr double pi = std::numbers::pi;

// |a - b| within half a unit of the last printed digit.
void expect_printed(double value, double printed, int decimals, const char* what) {
  EXPECT_NEAR(value, printed, 0.5 * std::pow(10.0, -decimals)) << what;
}
void expect_printed(const Vec3& v, const Vec3& printed, int decimals, const char* what) {
  for (int k = 0; k < 3; ++k) expect_printed(v[k], printed[k], decimals, what);
}

TEST(CircleArc, ReferenceVector1HalfCircleTypeOne) {
  const auto c = circle_through_points({110, 100, 50}, {100, 110, 50}, {90, 100, 50});
  expect_printed(c.centre, {100, 100, 50}, 9, "centre");
  EXPECT_NEAR(c.radius_mm, 10.0, 1e-12);
  EXPECT_NEAR(c.theta13_rad, pi, 1e-14);
  EXPECT_NEAR(c.theta12_rad, pi / 2, 1e-14);
  expect_printed(c.length_mm, 31.415927, 6, "l");
  const auto timing = angular_timing(c.sweep_rad, c.length_mm, AngularProblem::omega_given, 0.5, 4);
  expect_printed(timing.time_s, 6.283185, 6, "t");
  expect_printed(timing.mean_speed_mm_s, 5.0, 9, "V");
  const HelixArc arc = c.curve();
  const AngularStepper stepper(arc, timing, c.end_point());
  ASSERT_EQ(stepper.samples(), 5);
  const Vec3 expected[5] = {{110, 100, 50}, {107.071068, 107.071068, 50}, {100, 110, 50}, {92.928932, 107.071068, 50},
                            {90, 100, 50}};
  for (int i = 0; i < 5; ++i) expect_printed(stepper.sample(i).point, expected[i], 6, "step point");
  // The formula itself reaches r3 (the last sample is r3 by construction).
  EXPECT_LE((arc.point(arc.u_max()) - c.points[2]).norm(), 1e-12 * c.extent_mm);
}

TEST(CircleArc, ReferenceVector2TypeTwo) {
  const auto c = circle_through_points({100, 200, 300}, {200, 250, 310}, {260, 180, 400});
  expect_printed(c.centre, {171.0526316, 171.7611336, 360.6680162}, 7, "centre");
  expect_printed(c.radius_mm, 97.60388424, 8, "R");
  expect_printed(c.theta13_rad, 2.6669643, 7, "theta13 [rad]");
  expect_printed(c.theta13_rad * 180.0 / pi, 152.8057965, 7, "theta13 [deg]");
  expect_printed(c.length_mm, 260.3060714, 7, "l");
  const auto timing = angular_timing(c.sweep_rad, c.length_mm, AngularProblem::time_given, 10.0, 5);
  expect_printed(timing.omega_rad_s, 0.2666964, 7, "omega");
  expect_printed(timing.mean_speed_mm_s, 26.0306071, 7, "V");
  const HelixArc arc = c.curve();
  const AngularStepper stepper(arc, timing, c.end_point());
  expect_printed(stepper.sample(1).point, {138.517634, 233.188777, 292.150597}, 6, "point 1");
  EXPECT_EQ(stepper.sample(5).point, c.points[2]);
  EXPECT_LE((arc.point(arc.u_max()) - c.points[2]).norm(), 1e-12 * c.extent_mm);
  EXPECT_NEAR(stepper.sample(5).time_s, 10.0, 1e-15);
}

TEST(CircleArc, FramesAreInverseAndPointsLieInThePlane) {
  const auto c = circle_through_points({100, 200, 300}, {200, 250, 310}, {260, 180, 400});
  EXPECT_LE((c.to_machine * c.to_relative - Eigen::Matrix4d::Identity()).norm(), 1e-15 * 1000.0);
  for (const auto& q : c.relative_points) {
    EXPECT_NEAR(q.z(), 0.0, 1e-12);
    EXPECT_NEAR(q.head<2>().norm(), c.radius_mm, 1e-12);
  }
  EXPECT_NEAR(c.relative_points[0].y(), 0.0, 1e-12);
  EXPECT_GT(c.relative_points[0].x(), 0.0);
}

TEST(CircleArc, FullCircleReturnsToTheStart) {
  const auto c = circle_through_points({110, 100, 50}, {100, 110, 50}, {90, 100, 50}, CircleMotion::full_circle);
  EXPECT_NEAR(c.sweep_rad, 2 * pi, 1e-15);
  EXPECT_NEAR(c.length_mm, 20 * pi, 1e-12);
  const HelixArc arc = c.curve();
  const auto timing = angular_timing(c.sweep_rad, c.length_mm, AngularProblem::omega_given, 1.0, 8);
  const AngularStepper stepper(arc, timing, c.end_point());
  EXPECT_EQ(stepper.sample(8).point, c.points[0]);
  EXPECT_LE((stepper.sample(4).point - Vec3(90, 100, 50)).norm(), 1e-12);  // through r3 at half-time
  EXPECT_LE((arc.point(1.0) - c.points[0]).norm(), 1e-12 * c.extent_mm);
}

TEST(CircleArc, IsACurveWithExactLengthAndInverse) {
  const auto c = circle_through_points({100, 200, 300}, {200, 250, 310}, {260, 180, 400});
  const HelixArc arc = c.curve();
  const LengthResult gk = gauss_kronrod_length(arc);
  EXPECT_NEAR(gk.length_mm, c.length_mm, 1e-12 * c.length_mm);
  const ArcLengthTable table(arc);
  for (double s = 0.0; s <= c.length_mm; s += c.length_mm / 7) {
    const double u = table.u_of_s(s);
    EXPECT_NEAR(u * c.length_mm, s, 1e-12 * c.length_mm);  // the circle's s is linear in u
  }
}

TEST(CircleArc, ConstantFeedStepsAreEqualArcLengths) {
  const auto c = circle_through_points({100, 200, 300}, {200, 250, 310}, {260, 180, 400});
  const HelixArc arc = c.curve();
  const ArcLengthTable table(arc);
  const ConstantFeedStepper feed(arc, table, c.end_point(), 6000.0, 0.001);  // 0.1 mm per period
  EXPECT_NEAR(feed.step_mm(), 0.1, 1e-15);
  EXPECT_EQ(feed.samples(), static_cast<long>(std::ceil(c.length_mm / 0.1)) + 1);
  for (long k = 0; k + 1 < feed.samples(); ++k) {
    const auto m = feed.sample(k);
    // angle from r1 times R is the arc length
    const Vec3 q = c.to_relative.topLeftCorner<3, 3>() * m.point + c.to_relative.topRightCorner<3, 1>();
    double ang = std::atan2(q.y(), q.x());
    if (ang < 0.0) ang += 2 * pi;
    ASSERT_NEAR(ang * c.radius_mm, 0.1 * static_cast<double>(k), 1e-10) << "period " << k;
  }
  EXPECT_EQ(feed.sample(feed.samples() - 1).point, c.points[2]);
}

TEST(CircleArc, RandomCirclesInSpace) {
  const auto seed = testing::test_seed();
  const auto count = testing::test_count(10000);
  std::mt19937_64 rng(seed ^ 0xC1C1EULL);
  auto uni = [&](double a, double b) { return std::uniform_real_distribution<double>(a, b)(rng); };
  double worst_end = 0.0;
  for (std::uint64_t i = 0; i < count; ++i) {
    const double R = std::exp(uni(std::log(0.1), std::log(1000.0)));
    const Vec3 centre(uni(-1000, 1000), uni(-1000, 1000), uni(-1000, 1000));
    std::normal_distribution<double> n01;
    const Eigen::Quaterniond rot = Eigen::Quaterniond(n01(rng), n01(rng), n01(rng), n01(rng)).normalized();
    const Eigen::Matrix3d Q = rot.toRotationMatrix();
    const double t0 = uni(0, 2 * pi), sweep = uni(0.2, 2 * pi - 0.2), f = uni(0.1, 0.9);
    auto on = [&](double t) { return Vec3(centre + Q * Vec3(R * std::cos(t), R * std::sin(t), 0.0)); };
    const Vec3 r1 = on(t0), r2 = on(t0 + f * sweep), r3 = on(t0 + sweep);
    const auto c = circle_through_points(r1, r2, r3);
    const std::string what = testing::describe_case(seed, i);
    ASSERT_LE((c.centre - centre).norm(), 1e-9 * R) << what;
    ASSERT_NEAR(c.radius_mm, R, 1e-9 * R) << what;
    ASSERT_NEAR(c.sweep_rad, sweep, 1e-9) << what;
    const HelixArc arc = c.curve();
    const auto timing = angular_timing(c.sweep_rad, c.length_mm, AngularProblem::omega_given, 1.0, 16);
    const AngularStepper stepper(arc, timing, c.end_point());
    for (int k = 0; k < stepper.samples(); ++k) {
      const Vec3 q = Q.transpose() * (stepper.sample(k).point - centre);
      ASSERT_LE(std::abs(q.z()), 1e-9 * R) << what;
      ASSERT_NEAR(q.head<2>().norm(), R, 1e-9 * R) << what;
    }
    // Relative to the extent, or to the coordinates when they are larger: the points themselves
    // are known only to the rounding of their coordinates.
    const double scale = std::max({c.extent_mm, r1.cwiseAbs().maxCoeff(), r3.cwiseAbs().maxCoeff()});
    const double end = (arc.point(arc.u_max()) - r3).norm() / scale;
    worst_end = std::max(worst_end, end);
    ASSERT_LE(end, 1e-12) << what;
  }
  RecordProperty("worst_end_point_error_relative", std::to_string(worst_end));
}

// ---- bad input: one test per rule

using testing::expect_input_error;

TEST(CircleArcInput, CoincidentPoints) {
  expect_input_error([] { (void)circle_through_points({1, 2, 3}, {1, 2, 3}, {4, 5, 7}); }, "points-coincident",
                     "r1 (1, 2, 3) and r2 (1, 2, 3) coincide");
}

TEST(CircleArcInput, CollinearPoints) {
  expect_input_error([] { (void)circle_through_points({0, 0, 0}, {1, 1, 1}, {3, 3, 3}); }, "points-collinear",
                     "are collinear");
  // Nearly collinear beyond the relative tolerance, at any scale.
  expect_input_error([] { (void)circle_through_points({0, 0, 0}, {1e6, 1e-5, 0}, {2e6, 0, 0}); },
                     "points-collinear", "must exceed 1e-09");
}

TEST(CircleArcInput, NonFiniteCoordinate) {
  expect_input_error(
      [] { (void)circle_through_points({0, 0, 0}, {1, std::numeric_limits<double>::quiet_NaN(), 0}, {2, 0, 0}); },
      "point-finite", "r2.y = nan");
  expect_input_error(
      [] { (void)circle_through_points({0, 0, std::numeric_limits<double>::infinity()}, {1, 1, 0}, {2, 0, 0}); },
      "point-finite", "r1.z = inf");
}

TEST(CircleArcInput, OmegaTimeAndStepsMustBePositive) {
  expect_input_error([] { (void)angular_timing(pi, 10.0, AngularProblem::omega_given, 0.0, 4); }, "omega-positive",
                     "omega = 0");
  expect_input_error([] { (void)angular_timing(pi, 10.0, AngularProblem::omega_given, -1.0, 4); }, "omega-positive",
                     "omega = -1");
  expect_input_error([] { (void)angular_timing(pi, 10.0, AngularProblem::time_given, -2.0, 4); }, "time-positive",
                     "t = -2");
  expect_input_error(
      [] { (void)angular_timing(pi, 10.0, AngularProblem::time_given, std::numeric_limits<double>::infinity(), 4); },
      "time-positive", "t = inf");
  expect_input_error([] { (void)angular_timing(pi, 10.0, AngularProblem::time_given, 2.0, 0); }, "steps-positive",
                     "N = 0");
}

TEST(CircleArcInput, FeedAndPeriodMustBePositive) {
  const auto c = circle_through_points({110, 100, 50}, {100, 110, 50}, {90, 100, 50});
  const HelixArc arc = c.curve();
  const ArcLengthTable table(arc);
  expect_input_error([&] { ConstantFeedStepper s(arc, table, c.end_point(), 0.0, 0.001); }, "feed-positive", "F = 0");
  expect_input_error([&] { ConstantFeedStepper s(arc, table, c.end_point(), 100.0, -1.0); }, "period-positive",
                     "T = -1");
  expect_input_error([&] { ConstantFeedStepper s(arc, table, c.end_point(), 1e-9, 1e-9, 1000); }, "too-many-periods",
                     "at most 1000");
}

TEST(CircleArcInput, OutsideMachineLimits) {
  MachineLimits limits;
  limits.min_mm = Vec3(1, 1, 1);
  limits.max_mm = Vec3(5000, 5000, 5000);
  EXPECT_NO_THROW(check_inside_limits(limits, {110, 100, 50}, "r1"));
  expect_input_error([&] { check_inside_limits(limits, {110, 100, 0.5}, "r3"); }, "limits-outside",
                     "r3: z = 0.5 mm is below the machine limit 1 mm");
  expect_input_error([&] { check_inside_limits(limits, {5001, 100, 2}, "step 4"); }, "limits-outside",
                     "step 4: x = 5001 mm is above the machine limit 5000 mm");
  MachineLimits bad;
  bad.min_mm = Vec3(0, 10, 0);
  bad.max_mm = Vec3(1, 5, 1);
  expect_input_error([&] { validate_limits(bad); }, "limits-invalid", "machine limits of y");
}

}  // namespace
}  // namespace kontur
