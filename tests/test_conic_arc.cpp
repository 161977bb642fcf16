// Conic through five points (methods.md section 5, seed program SOCADI): the reference vectors to
// their printed digits, the length against elliptic integrals, seeded random conics of every type
// in space, both motion modes and every bad input.
#include <gtest/gtest.h>
#include <kontur/interpolate/arc_motion.hpp>
#include <kontur/geometry/conic_through_points.hpp>
#include <kontur/error.hpp>
#include <kontur/geometry/length.hpp>
#include <kontur/tolerances.hpp>

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
constexpr double deg = 180.0 / pi;

void expect_printed(double value, double printed, int decimals, const char* what) {
  EXPECT_NEAR(value, printed, 0.5 * std::pow(10.0, -decimals)) << what;
}

// The plane of the reference vectors: (x, y) -> (100 + x, 200 + 0.6 y, 300 + 0.8 y).
Vec3 to_space(double x, double y) { return {100 + x, 200 + 0.6 * y, 300 + 0.8 * y}; }

TEST(ConicArc, ReferenceEllipse) {
  const std::array<Vec3, 5> r{Vec3(105, 200, 300), Vec3(104, 201.08, 301.44), Vec3(103, 201.44, 301.92),
                              Vec3(100, 201.8, 302.4), Vec3(96, 201.08, 301.44)};
  const auto k = conic_through_points(r);
  EXPECT_EQ(k.type, ConicType::ellipse);
  EXPECT_NEAR(k.a_mm, 5.0, 1e-12);
  EXPECT_NEAR(k.b_mm, 3.0, 1e-12);
  EXPECT_NEAR(k.c_mm, 4.0, 1e-12);
  EXPECT_NEAR(k.eccentricity, 0.8, 1e-13);
  EXPECT_NEAR(k.focal_parameter_mm, 1.8, 1e-12);
  EXPECT_LE((k.centre - to_space(0, 0)).norm(), 1e-12);
  EXPECT_LE((k.focus - to_space(4, 0)).norm(), 1e-12);  // the focus on r1's side
  expect_printed(k.theta15_rad * deg, 167.319617, 6, "theta15 [deg]");
  const auto timing = angular_timing(k.theta15_rad, 1.0, AngularProblem::omega_given, 0.5, 4);
  expect_printed(timing.time_s, 5.840556, 6, "t");
  const ConicArc arc = k.curve();
  const AngularStepper stepper(arc, timing, r[4]);
  const Vec3 expected[3] = {{104.840316, 200.451271, 300.601695}, {104.182641, 200.986263, 301.315017},
                            {102.048748, 201.641957, 302.189275}};
  for (int i = 0; i < 3; ++i)
    for (int a = 0; a < 3; ++a) expect_printed(stepper.sample(i + 1).point[a], expected[i][a], 6, "point");
  EXPECT_LE((arc.point(arc.u_max()) - r[4]).norm(), 1e-12 * k.extent_mm);
  EXPECT_LE((arc.point(0.0) - r[0]).norm(), 1e-12 * k.extent_mm);
}

TEST(ConicArc, ReferenceParabola) {
  const std::array<Vec3, 5> r{Vec3(96, 202.4, 303.2), Vec3(98, 200.6, 300.8), Vec3(100, 200, 300),
                              Vec3(102, 200.6, 300.8), Vec3(106, 205.4, 307.2)};
  const auto k = conic_through_points(r);
  EXPECT_EQ(k.type, ConicType::parabola);
  EXPECT_EQ(k.eccentricity, 1.0);
  EXPECT_NEAR(k.focal_parameter_mm, 2.0, 1e-12);
  EXPECT_LE((k.vertex - to_space(0, 0)).norm(), 1e-12);
  EXPECT_LE((k.focus - to_space(0, 1)).norm(), 1e-12);
  expect_printed(k.theta15_rad * deg, 270.0, 9, "theta15 [deg]");
  const auto timing = angular_timing(k.theta15_rad, 1.0, AngularProblem::omega_given, 0.5, 4);
  expect_printed(timing.time_s, 9.424778, 6, "t");
  const ConicArc arc = k.curve();
  EXPECT_LE((arc.point(arc.u_max()) - r[4]).norm(), 1e-12 * k.extent_mm);
  // Closed-form length of x^2 = 4 y, x from -4 to 6: s(x) = x/2 sqrt(1 + x^2/4) + asinh(x/2).
  auto s = [](double x) { return 0.5 * x * std::sqrt(1 + x * x / 4) + std::asinh(x / 2); };
  EXPECT_NEAR(length(arc), s(6) - s(-4), 1e-12 * (s(6) - s(-4)));
}

TEST(ConicArc, ReferenceHyperbola) {
  const std::array<Vec3, 5> r{Vec3(108.5, 196.625, 295.5), Vec3(105, 198.65, 298.2), Vec3(104, 200, 300),
                              Vec3(105, 201.35, 301.8), Vec3(108.5, 203.375, 304.5)};
  const auto k = conic_through_points(r);
  EXPECT_EQ(k.type, ConicType::hyperbola);
  EXPECT_NEAR(k.a_mm, 4.0, 1e-12);
  EXPECT_NEAR(k.b_mm, 3.0, 1e-12);
  EXPECT_NEAR(k.c_mm, 5.0, 1e-12);
  EXPECT_NEAR(k.eccentricity, 1.25, 1e-13);
  EXPECT_NEAR(k.focal_parameter_mm, 2.25, 1e-12);
  EXPECT_LE((k.centre - to_space(0, 0)).norm(), 1e-12);
  EXPECT_LE((k.focus - to_space(5, 0)).norm(), 1e-12);
  EXPECT_LE((k.vertex - to_space(4, 0)).norm(), 1e-12);
  expect_printed(k.theta15_rad * deg, 243.781584, 6, "theta15 [deg]");
  const auto timing = angular_timing(k.theta15_rad, 1.0, AngularProblem::omega_given, 0.5, 4);
  expect_printed(timing.time_s, 8.509583, 6, "t");
  const ConicArc arc = k.curve();
  EXPECT_LE((arc.point(arc.u_max()) - r[4]).norm(), 1e-12 * k.extent_mm);
}

TEST(ConicArc, RelativeFrameUsesTheCorrectedLambda) {
  const std::array<Vec3, 5> r{Vec3(105, 200, 300), Vec3(104, 201.08, 301.44), Vec3(103, 201.44, 301.92),
                              Vec3(100, 201.8, 302.4), Vec3(96, 201.08, 301.44)};
  const auto k = conic_through_points(r);
  const Vec3 a = r[1] - r[0], b = r[2] - r[0];
  EXPECT_NEAR(k.lambda, -b.dot(a) / a.squaredNorm(), 1e-15);
  const Eigen::Matrix3d R = k.relative_to_machine.topLeftCorner<3, 3>();
  EXPECT_LE((R.transpose() * R - Eigen::Matrix3d::Identity()).norm(), 1e-15);
  EXPECT_NEAR(R.determinant(), 1.0, 1e-15);
  EXPECT_LE((k.relative_to_machine * k.machine_to_relative - Eigen::Matrix4d::Identity()).norm(), 1e-12);
  EXPECT_LE((k.focal_to_machine * k.machine_to_focal - Eigen::Matrix4d::Identity()).norm(), 1e-12);
  EXPECT_NEAR(k.relative_points[1].y(), 0.0, 1e-14);
  for (const auto& q : k.relative_points) EXPECT_NEAR(q.z(), 0.0, 1e-12);  // 301.44 etc. are rounded
  // The coefficients satisfy the equation at every point (F = 0).
  const auto& c = k.coefficients;
  for (const auto& q : k.relative_points) {
    const double x = q.x(), y = q.y();
    EXPECT_NEAR(c[0] * x * x + c[1] * x * y + c[2] * y * y + c[3] * x + c[4] * y, 0.0, 1e-14);
  }
}

// An ellipse arc built from exact parameters: the length by Gauss-Kronrod against Legendre's
// incomplete elliptic integral of the second kind (std::ellint_2).
TEST(ConicArc, EllipseLengthMatchesEllipticIntegrals) {
  std::mt19937_64 rng(testing::test_seed());
  auto uni = [&](double a, double b) { return std::uniform_real_distribution<double>(a, b)(rng); };
  for (int i = 0; i < 200; ++i) {
    const double a = uni(1, 100), e = uni(0.05, 0.97), p = a * (1 - e * e), c = a * e;
    const double phi0 = uni(0, 2 * pi), sweep = uni(0.1, 2 * pi - 0.01);
    const ConicArc arc(Vec3(1, 2, 3), Vec3::UnitX(), Vec3::UnitY(), p, e, phi0, sweep);
    // Focus at the origin of the focal frame; the centre at (c, 0) (the polar axis points to it).
    // Eccentric angle E of a point: x - c = a cos E, y = b sin E; s from E = 0 is a (E(E - pi/2, e)...)
    // written with the angle t = E - pi/2 from the minor axis: ds = a sqrt(1 - e^2 sin^2 t) dt.
    const double b = std::sqrt(a * p);
    auto ecc_angle = [&](double u) {
      const Vec3 q = arc.focal_point(u);
      return std::atan2(q.y() / b, (q.x() - c) / a);
    };
    // Unwrap the eccentric angle along the arc (it increases with the focal angle).
    double E0 = ecc_angle(0.0), E1 = ecc_angle(sweep);
    while (E1 <= E0) E1 += 2 * pi;
    auto S = [&](double E) {  // arc length from t = 0 (E = pi/2) to E, any real E
      const double t = E - pi / 2;
      const double n = std::floor(t / pi + 0.5);
      return a * (2.0 * n * std::comp_ellint_2(e) + std::ellint_2(e, t - n * pi));
    };
    const double reference = S(E1) - S(E0);
    const LengthResult gk = gauss_kronrod_length(arc);
    ASSERT_NEAR(gk.length_mm, reference, tolerances::conic_length_relative * reference)
        << "a " << a << " e " << e << " phi0 " << phi0 << " sweep " << sweep;
  }
}

TEST(ConicArc, DerivativesMatchFiniteDifferences) {
  const ConicArc arc(Vec3(1, 2, 3), Vec3(0, 0.6, 0.8), Vec3(1, 0, 0), 2.25, 1.25, 2.5, 1.3);
  for (double u = 0.1; u < 1.2; u += 0.2) {  // inside the range: derivatives clamp u
    const auto d = arc.derivatives(u, 3);
    const double h = 1e-5;
    for (int k = 1; k <= 3; ++k) {
      const Vec3 fd = (arc.derivatives(u + h, 3)[k - 1] - arc.derivatives(u - h, 3)[k - 1]) / (2 * h);
      EXPECT_LE((fd - d[k]).norm(), 1e-6 * (1 + d[k].norm())) << "order " << k << " u " << u;
    }
  }
}

// Near a parabola or a circle, but measurably not one: no snapping.
TEST(ConicArc, NearlyParabolicAndNearlyCircularEllipsesStayEllipses) {
  auto fit = [](double a, double b, double t0, double t1) {
    std::array<Vec3, 5> r;
    for (int j = 0; j < 5; ++j) {
      const double t = t0 + (t1 - t0) * j / 4.0;
      r[static_cast<std::size_t>(j)] = to_space(a * std::cos(t), b * std::sin(t));
    }
    return conic_through_points(r);
  };
  // 1 - e^2 = b^2 / a^2 = 1e-7, near the vertex (x = a): close to the parabola y^2 = 2 p (a - x).
  const double a = 1e4, b = a * std::sqrt(1e-7);
  const auto k1 = fit(a, b, -0.0057, 0.0057);  // 0.16 mm along the axis, 0.036 mm across
  EXPECT_EQ(k1.type, ConicType::ellipse);
  EXPECT_NEAR(1 - k1.eccentricity * k1.eccentricity, 1e-7, 1e-12);
  // e^2 = 1e-8: b / a = 1 - 5e-9.
  const auto k2 = fit(10.0, 10.0 * std::sqrt(1 - 1e-8), 0.3, 2.5);
  EXPECT_EQ(k2.type, ConicType::ellipse);
  EXPECT_NEAR(k2.eccentricity, 1e-4, 1e-6);
}

// ---- seeded random conics in space

struct Generated {
  ConicType type;
  std::array<Vec3, 5> points;
  Eigen::Matrix3d Q;     // canonical plane -> space rotation
  Vec3 origin;           // canonical centre (vertex for a parabola) in space
  double a = 0, b = 0, e = 0, p = 0, size = 0;
  bool left = false;     // hyperbola: the left branch
  double length = 0;     // reference length r1 -> r5 (through the points)
  // Geometric distance of a space point from the conic, approximated by |f| / |grad f|, and from its plane.
  [[nodiscard]] std::pair<double, double> distance(const Vec3& x) const {
    const Vec3 q = Q.transpose() * (x - origin);
    double f = 0, gx = 0, gy = 0;
    if (type == ConicType::parabola) {  // x^2 = 2 p y
      f = q.x() * q.x() - 2 * p * q.y();
      gx = 2 * q.x();
      gy = -2 * p;
    } else if (type == ConicType::hyperbola) {
      f = q.x() * q.x() / (a * a) - q.y() * q.y() / (b * b) - 1;
      gx = 2 * q.x() / (a * a);
      gy = -2 * q.y() / (b * b);
    } else {
      f = q.x() * q.x() / (a * a) + q.y() * q.y() / (b * b) - 1;
      gx = 2 * q.x() / (a * a);
      gy = 2 * q.y() / (b * b);
    }
    return {std::abs(f) / std::hypot(gx, gy), std::abs(q.z())};
  }
};

// A plane curve with a known parametrisation, for the reference length by an independent route.
class PlaneCurve final : public Curve {
public:
  PlaneCurve(std::function<Eigen::Vector2d(double)> f, std::function<Eigen::Vector2d(double)> df, double t0, double t1)
      : f_(std::move(f)), df_(std::move(df)), t0_(t0), t1_(t1) {}
  double u_min() const noexcept override { return t0_; }
  double u_max() const noexcept override { return t1_; }
  Derivatives derivatives(double u, int order) const noexcept override {
    Derivatives d;
    const auto p = f_(u);
    d[0] = Vec3(p.x(), p.y(), 0);
    if (order >= 1) {
      const auto v = df_(u);
      d[1] = Vec3(v.x(), v.y(), 0);
    }
    return d;
  }
  std::vector<double> breakpoints() const override { return {t0_, t1_}; }

private:
  std::function<Eigen::Vector2d(double)> f_, df_;
  double t0_, t1_;
};

Generated generate(ConicType type, std::uint64_t seed, std::uint64_t index) {
  std::mt19937_64 rng(seed * 0x9E3779B97F4A7C15ULL + index + 0xC0'41C5ULL * (static_cast<std::uint64_t>(type) + 1));
  auto uni = [&](double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng); };
  Generated g;
  g.type = type;
  g.size = std::exp(uni(std::log(0.5), std::log(500.0)));
  {
    std::normal_distribution<double> n01;
    Eigen::Quaterniond q(n01(rng), n01(rng), n01(rng), n01(rng));  // uniform on SO(3) once normalised
    g.Q = q.normalized().toRotationMatrix();
  }
  // The pose's offset is of the order of the size: the five points are known only to the rounding
  // of their coordinates, and the fit's relative error grows with |coordinates| / size.
  g.origin = g.size * Vec3(uni(-2, 2), uni(-2, 2), uni(-2, 2));
  // Five parameters in order with a least gap, from t0 over a span.
  auto params = [&](double t0, double span) {
    std::array<double, 5> f{0, uni(0.1, 0.9), uni(0.1, 0.9), uni(0.1, 0.9), 1};
    std::sort(f.begin(), f.end());
    for (int i = 1; i < 5; ++i) f[static_cast<std::size_t>(i)] = std::max(f[static_cast<std::size_t>(i)], f[static_cast<std::size_t>(i - 1)] + 0.05);
    for (auto& v : f) v = t0 + span * v / f[4];
    return f;
  };
  std::function<Eigen::Vector2d(double)> pos, vel;
  std::array<double, 5> t{};
  switch (type) {
    case ConicType::circle:
    case ConicType::ellipse: {
      g.a = g.size;
      g.b = type == ConicType::circle ? g.a : g.a * uni(0.2, 0.95);
      g.e = std::sqrt(1 - g.b * g.b / (g.a * g.a));
      g.p = g.b * g.b / g.a;
      t = params(uni(0, 2 * pi), uni(0.6, 2 * pi - 0.4));
      const double a = g.a, b = g.b;
      pos = [a, b](double s) { return Eigen::Vector2d(a * std::cos(s), b * std::sin(s)); };
      vel = [a, b](double s) { return Eigen::Vector2d(-a * std::sin(s), b * std::cos(s)); };
      break;
    }
    case ConicType::parabola: {
      g.p = g.size * uni(0.2, 2.0);
      g.e = 1;
      const double w = g.p * uni(0.8, 4.0);
      t = params(uni(-3 * g.p, 3 * g.p - w), w);
      const double p = g.p;
      pos = [p](double s) { return Eigen::Vector2d(s, s * s / (2 * p)); };
      vel = [p](double s) { return Eigen::Vector2d(1, s / p); };
      break;
    }
    case ConicType::hyperbola: {
      g.a = g.size;
      g.b = g.a * uni(0.3, 2.5);
      g.e = std::sqrt(1 + g.b * g.b / (g.a * g.a));
      g.p = g.b * g.b / g.a;
      g.left = uni(0, 1) < 0.5;
      // Arcs far out along an asymptote are nearly straight and their parameters ill-determined
      // by five points: with t up to 3 and e = 1.68 a relative perturbation of 2e-16 of the
      // inputs moves p by 1e-9. The arcs here stay within |t| <= 2.5.
      t = params(uni(-1.5, 0.5), uni(0.6, 2.0));
      const double a = g.a, b = g.b, sgn = g.left ? -1.0 : 1.0;
      pos = [a, b, sgn](double s) { return Eigen::Vector2d(sgn * a * std::cosh(s), b * std::sinh(s)); };
      vel = [a, b, sgn](double s) { return Eigen::Vector2d(sgn * a * std::sinh(s), b * std::cosh(s)); };
      break;
    }
  }
  const bool reverse = uni(0, 1) < 0.5;  // either direction of travel
  if (reverse) std::reverse(t.begin(), t.end());
  for (std::size_t j = 0; j < 5; ++j) {
    const auto q = pos(t[j]);
    g.points[j] = g.origin + g.Q * Vec3(q.x(), q.y(), 0);
  }
  const PlaneCurve ref(pos, vel, std::min(t[0], t[4]), std::max(t[0], t[4]));
  g.length = gauss_kronrod_length(ref).length_mm;
  return g;
}

void run_random(ConicType type) {
  const auto seed = testing::test_seed();
  const auto count = testing::test_count(10000);
  double worst_param = 0, worst_curve = 0, worst_plane = 0, worst_end = 0, worst_length = 0;
  for (std::uint64_t i = 0; i < count; ++i) {
    const Generated g = generate(type, seed, i);
    const std::string what = testing::describe_case(seed, i) + " " + to_string(type);
    ConicThroughPoints k;
    try {
      k = conic_through_points(g.points);
    } catch (const InputError& e) {
      FAIL() << what << ": " << e.what();
    }
    ASSERT_EQ(k.type, type) << what << " e " << k.eccentricity;
    const double rel_p = std::abs(k.focal_parameter_mm - g.p) / g.p;
    double rel = rel_p;
    if (type == ConicType::ellipse || type == ConicType::hyperbola) {
      rel = std::max({rel, std::abs(k.eccentricity - g.e) / g.e, std::abs(k.a_mm - g.a) / g.a,
                      std::abs(k.b_mm - g.b) / g.b, std::abs(k.c_mm - g.a * g.e) / (g.a * g.e)});
      rel = std::max(rel, (k.centre - g.origin).norm() / g.size);
    }
    if (type == ConicType::circle) rel = std::max({rel, std::abs(k.a_mm - g.a) / g.a, (k.centre - g.origin).norm() / g.size});
    if (type == ConicType::parabola) rel = std::max(rel, (k.vertex - g.origin).norm() / g.size);
    worst_param = std::max(worst_param, rel);
    ASSERT_LE(rel, 1e-9) << what << " p " << rel_p << " e " << k.eccentricity << " vs " << g.e << " a " << k.a_mm << " vs " << g.a
                         << " centre off " << (k.centre - g.origin).norm() / g.size << " size " << g.size;

    const ConicArc arc = k.curve();
    const auto timing = angular_timing(k.theta15_rad, 1.0, AngularProblem::time_given, 1.0, 12);
    const AngularStepper stepper(arc, timing, g.points[4]);
    for (int s = 0; s < stepper.samples(); ++s) {
      const auto [d_curve, d_plane] = g.distance(stepper.sample(s).point);
      worst_curve = std::max(worst_curve, d_curve / g.size);
      worst_plane = std::max(worst_plane, d_plane / g.size);
      ASSERT_LE(d_curve, 1e-9 * g.size) << what << " step " << s;
      ASSERT_LE(d_plane, 1e-9 * g.size) << what << " step " << s;
    }
    const double end = (arc.point(arc.u_max()) - g.points[4]).norm() / k.extent_mm;
    worst_end = std::max(worst_end, end);
    ASSERT_LE(end, 1e-9) << what;
    const double len = gauss_kronrod_length(arc).length_mm;
    const double rel_len = std::abs(len - g.length) / g.length;
    worst_length = std::max(worst_length, rel_len);
    ASSERT_LE(rel_len, 1e-9) << what;
  }
  std::printf("%s, %llu cases: worst relative parameter %.2e, on curve %.2e, in plane %.2e, end %.2e, length %.2e\n",
              to_string(type), static_cast<unsigned long long>(count), worst_param, worst_curve, worst_plane, worst_end,
              worst_length);
}

TEST(ConicArcRandom, Ellipses) { run_random(ConicType::ellipse); }
TEST(ConicArcRandom, Circles) { run_random(ConicType::circle); }
TEST(ConicArcRandom, Parabolas) { run_random(ConicType::parabola); }
TEST(ConicArcRandom, Hyperbolas) { run_random(ConicType::hyperbola); }

// ---- motion

TEST(ConicArcMotion, ConstantFeedAdvancesEqualArcLengths) {
  const std::array<Vec3, 5> r{Vec3(108.5, 196.625, 295.5), Vec3(105, 198.65, 298.2), Vec3(104, 200, 300),
                              Vec3(105, 201.35, 301.8), Vec3(108.5, 203.375, 304.5)};
  const auto k = conic_through_points(r);
  const ConicArc arc = k.curve();
  const ArcLengthTable table(arc);
  const ConstantFeedStepper feed(arc, table, r[4], 600.0, 0.001);  // 0.01 mm per period
  double previous_u = 0.0;
  for (long i = 1; i + 1 < feed.samples(); ++i) {
    const auto m = feed.sample(i);
    ASSERT_GT(m.u, previous_u);
    previous_u = m.u;
    const double s = gauss_kronrod_length(arc, 0.0, m.u).length_mm;
    ASSERT_NEAR(s, 0.01 * static_cast<double>(i), 1e-12 * table.length_mm()) << "period " << i;
  }
  EXPECT_EQ(feed.sample(feed.samples() - 1).point, r[4]);
  EXPECT_NEAR(feed.time_s(), table.length_mm() / 10.0, 1e-12);
}

TEST(ConicArcMotion, PlannedAndOnTheFlyConstantFeedAgree) {
  const std::array<Vec3, 5> r{Vec3(96, 202.4, 303.2), Vec3(98, 200.6, 300.8), Vec3(100, 200, 300),
                              Vec3(102, 200.6, 300.8), Vec3(106, 205.4, 307.2)};
  const auto k = conic_through_points(r);
  const ConicArc arc = k.curve();
  const ArcLengthTable table(arc);
  const ConstantFeedStepper planned(arc, table, r[4], 1000.0, 0.01);
  const ConstantFeedStepper on_the_fly(arc, table, r[4], 1000.0, 0.01, 100'000'000, 0);
  ASSERT_EQ(planned.samples(), on_the_fly.samples());
  // The planned path chains u_after from period to period, the on-the-fly one calls u_of_s:
  // both resolve the arc length to 1e-13 of the length, so the points agree to that.
  for (long i = 0; i < planned.samples(); ++i) {
    EXPECT_NEAR(table.s_of_u(planned.sample(i).u), table.s_of_u(on_the_fly.sample(i).u), 1e-12 * table.length_mm());
    EXPECT_LE((planned.sample(i).point - on_the_fly.sample(i).point).norm(), 1e-12 * table.length_mm());
  }
  EXPECT_EQ(planned.sample(planned.samples() - 1).point, r[4]);
}

TEST(ConicArcMotion, FocalAngleStepsVaryTheSpeed) {
  const std::array<Vec3, 5> r{Vec3(105, 200, 300), Vec3(104, 201.08, 301.44), Vec3(103, 201.44, 301.92),
                              Vec3(100, 201.8, 302.4), Vec3(96, 201.08, 301.44)};
  const auto k = conic_through_points(r);
  const ConicArc arc = k.curve();
  const double L = length(arc);
  const auto timing = angular_timing(k.theta15_rad, L, AngularProblem::omega_given, 0.5, 4);
  const auto v = angular_speed_variation(arc, timing);
  // v = omega |dC/dphi| = omega p sqrt(1 - 2 e cos phi + e^2) / (1 - e cos phi)^2: slowest at the
  // near vertex r1 (phi = pi): 0.5 * 1.8 * 1.8 / 1.8^2 = 0.5 mm/s; fastest short of r5 (the radial
  // part of the velocity vanishes at the far vertex), found here from the formula on a fine grid.
  EXPECT_NEAR(v.min_mm_s, 0.5, 1e-12);
  double vmax = 0.0;
  for (int i = 0; i <= 100000; ++i) {
    const double phi = k.focal_angles_rad[0] + k.theta15_rad * i / 100000.0, g = 1 - 0.8 * std::cos(phi);
    vmax = std::max(vmax, 0.5 * 1.8 * std::sqrt(1 - 1.6 * std::cos(phi) + 0.64) / (g * g));
  }
  EXPECT_NEAR(v.max_mm_s, vmax, 1e-6 * vmax);
  EXPECT_LT(v.min_mm_s, v.max_mm_s);
  EXPECT_GT(v.relative_variation(), 0.1);
  EXPECT_NEAR(v.mean_mm_s, L / timing.time_s, 1e-12);
}

// ---- bad input: one test per rule

using testing::expect_input_error;

std::array<Vec3, 5> ellipse_points() {
  return {Vec3(105, 200, 300), Vec3(104, 201.08, 301.44), Vec3(103, 201.44, 301.92), Vec3(100, 201.8, 302.4),
          Vec3(96, 201.08, 301.44)};
}

TEST(ConicArcInput, CoincidentPoints) {
  auto r = ellipse_points();
  r[3] = r[1];
  expect_input_error([&] { (void)conic_through_points(r); }, "points-coincident", "r2 (104, 201.08, 301.44) and r4");
}

TEST(ConicArcInput, ThreeCollinearPoints) {
  const std::array<Vec3, 5> r{Vec3(0, 0, 0), Vec3(1, 1, 0), Vec3(2, 2, 0), Vec3(5, 1, 0), Vec3(6, 3, 0)};
  expect_input_error([&] { (void)conic_through_points(r); }, "points-collinear", "r1, r2 and r3 are collinear");
}

TEST(ConicArcInput, DegenerateIntersectingLines) {
  // r1, r2, r3 on y = 0 and r4, r5 on x = 10 - y: two intersecting lines.
  const std::array<Vec3, 5> r{Vec3(0, 0, 0), Vec3(2, 0, 0), Vec3(5, 0, 0), Vec3(8, 2, 0), Vec3(6, 4, 0)};
  expect_input_error([&] { (void)conic_through_points(r); }, "points-collinear", "two intersecting lines");
}

TEST(ConicArcInput, DegenerateParallelLines) {
  const std::array<Vec3, 5> r{Vec3(0, 0, 0), Vec3(2, 0, 0), Vec3(5, 0, 0), Vec3(8, 2, 0), Vec3(1, 2, 0)};
  expect_input_error([&] { (void)conic_through_points(r); }, "points-collinear", "two parallel lines");
}

TEST(ConicArcInput, FourPointsOnALine) {
  const std::array<Vec3, 5> r{Vec3(0, 0, 0), Vec3(2, 0, 0), Vec3(5, 0, 0), Vec3(8, 0, 0), Vec3(1, 2, 0)};
  expect_input_error([&] { (void)conic_through_points(r); }, "points-collinear", "4 of the five points lie on one line");
}

TEST(ConicArcInput, NotCoplanarStatesDistanceAndTolerance) {
  auto r = ellipse_points();
  r[4] += Vec3(0, 0.8, -0.6) * 0.01;  // 0.01 mm along the plane's normal
  expect_input_error([&] { (void)conic_through_points(r); }, "points-not-coplanar",
                     "r5 (96, 201.088, 301.434) is 0.01 mm from the plane of r1, r2, r3 (tolerance 9.18e-09 mm)");
  ConicOptions loose;
  loose.plane_tolerance_mm = 0.02;
  EXPECT_NO_THROW((void)conic_through_points(r, loose));
}

TEST(ConicArcInput, PointsNotInOrder) {
  auto r = ellipse_points();
  std::swap(r[2], r[3]);
  expect_input_error([&] { (void)conic_through_points(r); }, "points-order", "not in order along one arc of the ellipse");
}

TEST(ConicArcInput, PointsOnTwoBranches) {
  // x^2/16 - y^2/9 = 1: three points on the right branch, two on the left.
  const auto h = [](double x, double y) { return to_space(x, y); };
  const std::array<Vec3, 5> r{h(8.5, -5.625), h(5, -2.25), h(4, 0), h(-5, 2.25), h(-8.5, 5.625)};
  expect_input_error([&] { (void)conic_through_points(r); }, "hyperbola-branches", "r4 (95, 201.35, 301.8) lies on the other branch");
}

TEST(ConicArcInput, NonFiniteCoordinate) {
  auto r = ellipse_points();
  r[2].x() = std::numeric_limits<double>::quiet_NaN();
  expect_input_error([&] { (void)conic_through_points(r); }, "point-finite", "r3.x = nan");
}

TEST(ConicArcInput, NegativePlaneTolerance) {
  ConicOptions o;
  o.plane_tolerance_mm = -1;
  expect_input_error([&] { (void)conic_through_points(ellipse_points(), o); }, "plane-tolerance", "-1 mm");
}

}  // namespace
}  // namespace kontur
