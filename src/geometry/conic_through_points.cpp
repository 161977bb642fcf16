// Conic through five points (methods.md section 5; seed 001 section 3, program SOCADI).
#include "arc_checks.hpp"
#include "frame_matrices.hpp"

#include <kontur/geometry/conic_through_points.hpp>
#include <kontur/error.hpp>
#include <kontur/tolerances.hpp>

#include <Eigen/LU>
#include <Eigen/QR>
#include <Eigen/Geometry>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace kontur {

const char* to_string(ConicType type) noexcept {
  switch (type) {
    case ConicType::ellipse: return "ellipse";
    case ConicType::circle: return "circle";
    case ConicType::parabola: return "parabola";
    case ConicType::hyperbola: return "hyperbola";
  }
  return "?";
}

// ------------------------------------------------------------------------------- ConicArc

ConicArc::ConicArc(const Vec3& focus_mm, const Vec3& x_axis, const Vec3& y_axis, double focal_parameter_mm,
                   double eccentricity, double phi_start_rad, double sweep_rad)
    : focus_(focus_mm), x_(x_axis), y_(y_axis), p_(focal_parameter_mm), e_(eccentricity), phi0_(phi_start_rad),
      sweep_(sweep_rad) {
  if (!focus_mm.allFinite() || !(std::abs(x_axis.norm() - 1.0) <= 1e-9) || !(std::abs(y_axis.norm() - 1.0) <= 1e-9) ||
      !(std::abs(x_axis.dot(y_axis)) <= 1e-9))
    throw InputError("conic-arc", "conic arc: the focus must be finite and the axes unit and orthogonal");
  if (!(std::isfinite(p_) && p_ > 0.0) || !(std::isfinite(e_) && e_ >= 0.0) || !std::isfinite(phi0_) ||
      !(std::isfinite(sweep_) && sweep_ > 0.0))
    throw InputError("conic-arc", fmt::format("conic arc: p = {} mm, e = {}, phi0 = {} rad, sweep = {} rad: p and the "
                                              "sweep must be > 0, e >= 0, all finite",
                                              p_, e_, phi0_, sweep_));
  // 1 - e cos(phi) > 0 on the whole arc: its minimum is at a multiple of 2 pi inside, or at an end.
  const double two_pi = 2.0 * std::numbers::pi;
  const bool crosses_zero = std::floor((phi0_ + sweep_) / two_pi) > std::floor(phi0_ / two_pi) ||
                            std::fmod(phi0_, two_pi) == 0.0;
  const double cos_max = crosses_zero ? 1.0 : std::max(std::cos(phi0_), std::cos(phi0_ + sweep_));
  if (!(1.0 - e_ * cos_max > 0.0))
    throw InputError("conic-arc", fmt::format("conic arc: 1 - e cos(phi) reaches {} <= 0 on the arc (e = {}): the arc "
                                              "would run to infinity",
                                              1.0 - e_ * cos_max, e_));
}

double ConicArc::rho_mm(double phi_rad) const noexcept { return p_ / (1.0 - e_ * std::cos(phi_rad)); }

Vec3 ConicArc::focal_point(double u) const noexcept {
  const double phi = phi0_ + std::clamp(u, 0.0, sweep_);
  const double rho = rho_mm(phi);
  return {rho * std::cos(phi), rho * std::sin(phi), 0.0};
}

Derivatives ConicArc::derivatives(double u, int order) const noexcept {
  const double phi = phi0_ + std::clamp(u, 0.0, sweep_);
  const double c = std::cos(phi), s = std::sin(phi);
  // x = p cos / g, y = p sin / g with g = 1 - e cos; derivatives of a quotient f = N / g from
  // (f g)^(k) = N^(k) (Leibniz), solved for f^(k).
  const double g = 1.0 - e_ * c, g1 = e_ * s, g2 = e_ * c, g3 = -e_ * s;
  const double nx[4] = {p_ * c, -p_ * s, -p_ * c, p_ * s};
  const double ny[4] = {p_ * s, p_ * c, -p_ * s, -p_ * c};
  double fx[4] = {0, 0, 0, 0}, fy[4] = {0, 0, 0, 0};
  fx[0] = nx[0] / g;
  fy[0] = ny[0] / g;
  if (order >= 1) {
    fx[1] = (nx[1] - fx[0] * g1) / g;
    fy[1] = (ny[1] - fy[0] * g1) / g;
  }
  if (order >= 2) {
    fx[2] = (nx[2] - 2.0 * fx[1] * g1 - fx[0] * g2) / g;
    fy[2] = (ny[2] - 2.0 * fy[1] * g1 - fy[0] * g2) / g;
  }
  if (order >= 3) {
    fx[3] = (nx[3] - 3.0 * fx[2] * g1 - 3.0 * fx[1] * g2 - fx[0] * g3) / g;
    fy[3] = (ny[3] - 3.0 * fy[2] * g1 - 3.0 * fy[1] * g2 - fy[0] * g3) / g;
  }
  Derivatives d;
  d[0] = focus_ + fx[0] * x_ + fy[0] * y_;
  for (int k = 1; k <= std::min(order, 3); ++k) d[k] = fx[k] * x_ + fy[k] * y_;
  if (pinned_) {
    // offset(u) = start_offset + s(x) (end_offset - start_offset), x = u / sweep, with the quintic
    // smooth step s = x^3 (10 - 15 x + 6 x^2): s' = s'' = 0 at both ends
    const double x = std::clamp(u, 0.0, sweep_) / sweep_;
    const Vec3 jump = end_offset_ - start_offset_;
    const double sx[4] = {x * x * x * (10.0 - 15.0 * x + 6.0 * x * x), 30.0 * x * x * (1.0 - x) * (1.0 - x),
                          60.0 * x * (1.0 - x) * (1.0 - 2.0 * x), 60.0 * (1.0 - 6.0 * x + 6.0 * x * x)};
    d[0] += start_offset_ + sx[0] * jump;
    double scale = 1.0;
    for (int k = 1; k <= std::min(order, 3); ++k) {
      scale /= sweep_;
      d[k] += sx[k] * scale * jump;
    }
    if (u <= 0.0) d[0] = start_;
    if (u >= sweep_) d[0] = end_;
  }
  return d;
}

void ConicArc::pin_ends(const Vec3& start_mm, const Vec3& end_mm) noexcept {
  pinned_ = false;
  start_offset_ = start_mm - point(0.0);
  end_offset_ = end_mm - point(sweep_);
  start_ = start_mm;
  end_ = end_mm;
  pinned_ = true;
}

// ------------------------------------------------------------------------------- the fit

namespace {

using Vec2 = Eigen::Vector2d;

double sign_of(double v) noexcept { return v < 0.0 ? -1.0 : 1.0; }

// The kind of the pair of lines through the five points when three of them (i, j, k) are collinear.
std::string degenerate_kind(const std::array<Vec3, 5>& r, std::size_t i, std::size_t j, std::size_t k) {
  std::array<std::size_t, 2> rest{};
  std::size_t m = 0;
  for (std::size_t q = 0; q < 5; ++q)
    if (q != i && q != j && q != k) rest[m++] = q;
  const Vec3 d1 = (r[j] - r[i]).normalized();
  // More than three on the line?
  int on_line = 3;
  for (const std::size_t q : rest)
    if (detail::triangle_flatness(r[i], r[j], r[q]) <= tolerances::arc_collinear_relative) ++on_line;
  if (on_line >= 4) return fmt::format("{} of the five points lie on one line: they determine no conic", on_line);
  const Vec3 d2 = (r[rest[1]] - r[rest[0]]).normalized();
  if (d1.cross(d2).norm() <= tolerances::arc_collinear_relative)
    return fmt::format("the conic through them degenerates into two parallel lines ({}, {}, {} on one, {}, {} on the "
                       "other)",
                       detail::point_name(i), detail::point_name(j), detail::point_name(k),
                       detail::point_name(rest[0]), detail::point_name(rest[1]));
  return fmt::format("the conic through them degenerates into two intersecting lines ({}, {}, {} on one, {}, {} on "
                     "the other)",
                     detail::point_name(i), detail::point_name(j), detail::point_name(k), detail::point_name(rest[0]),
                     detail::point_name(rest[1]));
}

[[noreturn]] void throw_degenerate(const char* kind) {
  throw InputError("conic-degenerate",
                   fmt::format("the conic through the five points is degenerate: {} (within the relative tolerance "
                               "{:g}); five points in general position, in order along one arc, are needed",
                               kind, tolerances::conic_degenerate_relative));
}

}  // namespace

ConicArc ConicThroughPoints::curve() const {
  const Vec3 x = focal_to_machine.block<3, 1>(0, 0), y = focal_to_machine.block<3, 1>(0, 1);
  ConicArc arc(focus, x, y, focal_parameter_mm, eccentricity, focal_angles_rad[0], theta15_rad);
  arc.pin_ends(points[0], points[4]);  // from r1 to r5 exactly (they may lie off the conic's plane)
  return arc;
}

ConicThroughPoints conic_through_points(const std::array<Vec3, 5>& r, const ConicOptions& options) {
  ConicThroughPoints k;
  k.points = r;
  detail::check_finite(r);
  k.extent_mm = detail::check_distinct(r);
  for (std::size_t i = 0; i < 5; ++i)
    for (std::size_t j = i + 1; j < 5; ++j)
      for (std::size_t q = j + 1; q < 5; ++q) {
        const double flatness = detail::triangle_flatness(r[i], r[j], r[q]);
        if (!(flatness > tolerances::arc_collinear_relative))
          throw InputError("points-collinear",
                           fmt::format("{}, {} and {} are collinear (smallest height / longest side = {:.3g}, must "
                                       "exceed {:g}): {}",
                                       detail::point_name(i), detail::point_name(j), detail::point_name(q), flatness,
                                       tolerances::arc_collinear_relative, degenerate_kind(r, i, j, q)));
      }

  // ---- Relative frame, seed (3.18)-(3.31). The seed's (3.18) gives lambda without the minus
  // sign, which leaves e2 not orthogonal to e1; methods.md section 5.1 corrects it.
  const Vec3 a = r[1] - r[0], b = r[2] - r[0];
  k.lambda = -b.dot(a) / a.squaredNorm();
  const Vec3 e1 = a.normalized();
  Vec3 e2 = b + k.lambda * a;
  e2 = (e2 - e2.dot(e1) * e1).normalized();  // one more Gram-Schmidt pass, for the last bits
  const Vec3 e3 = e1.cross(e2);              // = (r2 - r1) x (r3 - r1) / |...|
  const detail::FrameMatrices relative = detail::frame_matrices(e1, e2, e3, r[0]);
  const Eigen::Matrix3d& R = relative.rotation;
  k.relative_to_machine = relative.to_machine;
  k.machine_to_relative = relative.to_frame;
  for (std::size_t j = 0; j < 5; ++j) k.relative_points[j] = relative.local(r[j]);
  k.relative_points[0] = Vec3::Zero();

  // ---- Coplanarity: the seed assumes it; Kontur checks the distance of r4 and r5 to the plane.
  k.plane_tolerance_mm =
      options.plane_tolerance_mm > 0.0 ? options.plane_tolerance_mm : tolerances::conic_coplanar_relative * k.extent_mm;
  if (!(std::isfinite(options.plane_tolerance_mm) && options.plane_tolerance_mm >= 0.0))
    throw InputError("plane-tolerance", fmt::format("plane tolerance {} mm: must be finite and >= 0 (0: default)",
                                                    options.plane_tolerance_mm));
  for (std::size_t j = 3; j < 5; ++j) {
    const double d = std::abs(k.relative_points[j].z());
    k.plane_distance_mm = std::max(k.plane_distance_mm, d);
    if (d > k.plane_tolerance_mm)
      throw InputError("points-not-coplanar",
                       fmt::format("{} {} is {:.6g} mm from the plane of r1, r2, r3 (tolerance {:.3g} mm): the five "
                                   "points must lie in one plane",
                                   detail::point_name(j), detail::format_point(r[j]), d, k.plane_tolerance_mm));
  }

  // ---- Coefficients by cofactors, seed (3.41)-(3.44): the 5x5 determinant with rows
  // (x^2, xy, y^2, x, y) of the general point and of r2..r5, expanded along its first row. The
  // coordinates are divided by the extent s first, so that the minors are of order one.
  const double s = k.extent_mm;
  Eigen::Matrix<double, 4, 5> M;
  for (int j = 0; j < 4; ++j) {
    const double x = k.relative_points[static_cast<std::size_t>(j + 1)].x() / s;
    const double y = k.relative_points[static_cast<std::size_t>(j + 1)].y() / s;
    M.row(j) << x * x, x * y, y * y, x, y;
  }
  std::array<double, 5> co{};
  for (int col = 0; col < 5; ++col) {
    Eigen::Matrix4d minor;
    for (int c = 0, m = 0; c < 5; ++c)
      if (c != col) minor.col(m++) = M.col(c);
    co[static_cast<std::size_t>(col)] = ((col % 2 == 0) ? 1.0 : -1.0) * minor.partialPivLu().determinant();
  }
  double big = 0.0;
  for (const double v : co) big = std::max(big, std::abs(v));
  if (!(big > 0.0) || !std::isfinite(big)) throw_degenerate("the five points determine no conic");
  for (double& v : co) v /= big;
  const double A = co[0], B = co[1], C = co[2], D = co[3], E = co[4];
  if (std::max({std::abs(A), std::abs(B), std::abs(C)}) <= tolerances::conic_degenerate_relative)
    throw_degenerate("a straight line (the equation has no second-degree terms)");

  // ---- Rotation, seed (3.45)-(3.53): cot 2 theta = (A - C) / B with theta in (0, pi/2). The
  // seed assumes B != 0; atan2 also covers B = 0 (theta = 0: axes already aligned).
  double theta = 0.5 * std::atan2(B, A - C);
  if (theta < 0.0) theta += 0.5 * std::numbers::pi;
  if (theta >= 0.5 * std::numbers::pi) theta -= 0.5 * std::numbers::pi;
  const double ct = std::cos(theta), st = std::sin(theta);
  const double Ar = A * ct * ct + B * st * ct + C * st * st;
  const double Cr = A * st * st - B * st * ct + C * ct * ct;
  const double Dr = D * ct + E * st;
  const double Er = -D * st + E * ct;
  k.rotation_rad = theta;
  const Vec2 dir_x(ct, st), dir_y(-st, ct);  // rotated axes in the relative frame

  // ---- Classification and the vertex form. Departure from the seed (3.54)-(3.99): the seed
  // completes the squares about the centre, which runs off to infinity as the conic approaches a
  // parabola (and every digit of the vertex is lost before). Kontur writes the conic about the
  // vertex nearest to r1, which stays finite for all three types:
  //   X^2 = 2 p xi - (1 - e^2) xi^2,   1 - e^2 = lambda_axis / lambda_transverse,
  // and classifies by the sign of 1 - e^2 (ellipse, hyperbola) and by fitting the parabola or
  // circle when it is nearly one (below); the seed's signs of A', C' and
  // U = (C' D'^2 + A' E'^2) / (4 A' C') are the same verdicts (U = disc / (4 lambda_axis)).
  const bool x_small = std::abs(Ar) <= std::abs(Cr);
  const double lam_small = x_small ? Ar : Cr, lam_big = x_small ? Cr : Ar;
  const double ratio = lam_small / lam_big;  // |ratio| <= 1; 1 - e^2 for an ellipse or hyperbola
  ConicType type = ratio > 0.0 ? ConicType::ellipse : ConicType::hyperbola;
  bool axis_is_x = x_small;  // focal axis along the rotated x axis (ellipse: the major axis)

  // A parabola (e = 1) or a circle (e = 0) is a single value of a continuous parameter, which
  // rounding never hits exactly. When 1 - e^2 or e^2 is small, the best parabola (circle) through
  // r1 and r2..r5 is fitted (least squares: the smallest singular vector of a 4 x 3 system; the
  // parabola's axis refined by two parabolic steps on sigma_min^2), and the conic is taken to be
  // one when it passes within tolerances::conic_snap_fit_relative of the extent of the points.
  std::array<Vec2, 4> pts2{};  // r2..r5 in scaled relative coordinates
  for (std::size_t j = 0; j < 4; ++j) pts2[j] = Vec2(k.relative_points[j + 1].x() / s, k.relative_points[j + 1].y() / s);
  // Least squares P w ~ 0 with the component `pivot` of w (the largest of the estimate) set to 1:
  // a 4 x 2 Householder QR solve. sigma: |P w| / |w|.
  auto refit = [&](auto&& row, int pivot, double* sigma) {
    Eigen::Matrix<double, 4, 3> P;
    for (int j = 0; j < 4; ++j) P.row(j) = row(pts2[static_cast<std::size_t>(j)]).transpose();
    Eigen::Matrix<double, 4, 2> Q2;
    for (int c = 0, m = 0; c < 3; ++c)
      if (c != pivot) Q2.col(m++) = P.col(c);
    const Eigen::Vector2d x = Q2.householderQr().solve(-P.col(pivot));
    Eigen::Vector3d w;
    for (int c = 0, m = 0; c < 3; ++c) w(c) = c == pivot ? 1.0 : x(m++);
    if (sigma != nullptr) *sigma = (P * w).norm() / w.norm();
    return w;
  };
  auto largest = [](double a0, double a1, double a2) {
    const double m0 = std::abs(a0), m1 = std::abs(a1), m2 = std::abs(a2);
    return m0 >= m1 && m0 >= m2 ? 0 : (m1 >= m2 ? 1 : 2);
  };
  Vec2 axis_dir = axis_is_x ? dir_x : dir_y, trans_dir = axis_is_x ? dir_y : dir_x;
  Eigen::Vector3d snap_w = Eigen::Vector3d::Zero();
  if (std::abs(ratio) <= tolerances::conic_snap_candidate_relative) {
    // lam_t X^2 + D_t X + D_a Y = 0 with the axis at angle alpha.
    const int pivot = axis_is_x ? largest(Cr, Er, Dr) : largest(Ar, Dr, Er);
    auto fit_at = [&](double alpha, double* sigma) {
      const Vec2 ax(std::cos(alpha), std::sin(alpha)), tr(-std::sin(alpha), std::cos(alpha));
      return refit([&](const Vec2& v) {
        const double X = v.dot(tr), Y = v.dot(ax);
        return Eigen::Vector3d(X * X, X, Y);
      }, pivot, sigma);
    };
    double alpha = std::atan2(axis_dir.y(), axis_dir.x());
    for (const double h : {1e-6, 1e-8}) {
      double f0 = 0.0, fm = 0.0, fp = 0.0;
      (void)fit_at(alpha, &f0);
      (void)fit_at(alpha - h, &fm);
      (void)fit_at(alpha + h, &fp);
      f0 *= f0;
      fm *= fm;
      fp *= fp;
      const double curvature = fp - 2.0 * f0 + fm;
      if (curvature > 0.0) alpha -= h * (fp - fm) / (2.0 * curvature);
    }
    const Eigen::Vector3d w = fit_at(alpha, nullptr);
    const Vec2 ax(std::cos(alpha), std::sin(alpha)), tr(-std::sin(alpha), std::cos(alpha));
    double worst = 0.0;  // |f| / |grad f| at the points
    for (const Vec2& v : pts2) {
      const double X = v.dot(tr), Y = v.dot(ax);
      worst = std::max(worst, std::abs(w(0) * X * X + w(1) * X + w(2) * Y) / std::hypot(2.0 * w(0) * X + w(1), w(2)));
    }
    if (worst <= tolerances::conic_snap_fit_relative) {
      type = ConicType::parabola;
      axis_dir = ax;
      trans_dir = tr;
      snap_w = w;
    }
  } else if (ratio > 0.0 && 1.0 - ratio <= tolerances::conic_snap_candidate_relative) {
    // lam (x^2 + y^2) + D x + E y = 0 in the relative frame.
    const Eigen::Vector3d w = refit([](const Vec2& v) { return Eigen::Vector3d(v.squaredNorm(), v.x(), v.y()); },
                                    largest(0.5 * (A + C), D, E), nullptr);
    double worst = 0.0;
    for (const Vec2& v : pts2)
      worst = std::max(worst, std::abs(w(0) * v.squaredNorm() + w(1) * v.x() + w(2) * v.y()) /
                                  std::hypot(2.0 * w(0) * v.x() + w(1), 2.0 * w(0) * v.y() + w(2)));
    if (worst <= tolerances::conic_snap_fit_relative) {
      type = ConicType::circle;
      snap_w = w;
    }
  }
  if (type == ConicType::hyperbola) {
    // The focal (transverse) axis is the one the curve meets: disc = D_a^2 + D_t^2 lam_a / lam_t > 0.
    const double disc_x = Dr * Dr + Er * Er * Ar / Cr, disc_y = Er * Er + Dr * Dr * Cr / Ar;
    if (std::max(disc_x, disc_y) <= tolerances::conic_degenerate_relative) throw_degenerate("two intersecting lines");
    axis_is_x = disc_x > disc_y;
    axis_dir = axis_is_x ? dir_x : dir_y;
    trans_dir = axis_is_x ? dir_y : dir_x;
  }
  double lam_a = axis_is_x ? Ar : Cr, lam_t = axis_is_x ? Cr : Ar;
  double D_a = axis_is_x ? Dr : Er, D_t = axis_is_x ? Er : Dr;
  double one_minus_e2 = lam_a / lam_t;
  if (type == ConicType::parabola) {
    lam_a = one_minus_e2 = 0.0;
    lam_t = snap_w(0);
    D_t = snap_w(1);
    D_a = snap_w(2);
  }
  if (type == ConicType::circle) one_minus_e2 = 1.0;

  k.type = type;
  k.rotated_coefficients = {Ar / (s * s), Cr / (s * s), Dr / s, Er / s};
  k.coefficients = {A / (s * s), B / (s * s), C / (s * s), D / s, E / s};

  Vec2 focus2, xi;     // focus and polar axis in the relative plane, scaled coordinates
  double p = 0.0, e = 0.0;
  Vec2 vertex2, centre2;
  if (type == ConicType::circle) {
    // e ~ 0: the focus is the centre and the axis direction is arbitrary; the seed's theta = 0
    // case puts the polar axis along the relative X axis.
    centre2 = Vec2(-0.5 * snap_w(1) / snap_w(0), -0.5 * snap_w(2) / snap_w(0));
    p = centre2.norm();  // the circle passes through r1, the origin
    e = 0.0;
    focus2 = centre2;
    xi = Vec2(1.0, 0.0);
    vertex2 = centre2 - p * xi;
  } else {
    // Complete the square across the axis: lam_t (X - X0)^2 + lam_a Y^2 + D_a Y - K = 0.
    const double X0 = -D_t / (2.0 * lam_t);
    const double disc = D_a * D_a + D_t * D_t * one_minus_e2;  // = D_a^2 + 4 lam_a K
    if (!(disc > tolerances::conic_degenerate_relative))
      throw_degenerate(type == ConicType::parabola  ? "two parallel lines"
                       : type == ConicType::ellipse ? "a single point (or no real curve)"
                                                    : "two intersecting lines");
    const double sq = std::sqrt(disc);
    // The vertex on r1's side of the centre: the root of lam_a Y^2 + D_a Y - K = 0 that stays
    // finite as lam_a -> 0, Y = 2 K / (D_a + sgn(D_a) sqrt(disc)); the slope there is sgn(D_a) sqrt(disc).
    const double K = D_t * D_t / (4.0 * lam_t);
    const double Yv = 2.0 * K / (D_a + sign_of(D_a) * sq);
    const double G = sign_of(D_a) * sq;
    xi = sign_of(-G / lam_t) * axis_dir;     // from the vertex into the curve
    p = sq / (2.0 * std::abs(lam_t));        // X^2 = 2 p xi - (1 - e^2) xi^2
    e = type == ConicType::parabola ? 1.0 : std::sqrt(std::max(0.0, 1.0 - one_minus_e2));
    vertex2 = X0 * trans_dir + Yv * axis_dir;
    focus2 = vertex2 + (p / (1.0 + e)) * xi;
    if (type == ConicType::ellipse) centre2 = vertex2 + (p / one_minus_e2) * xi;
    if (type == ConicType::hyperbola) centre2 = vertex2 + (p / one_minus_e2) * xi;  // 1 - e^2 < 0: behind the vertex
    if (type == ConicType::parabola) centre2 = vertex2;
  }
  k.eccentricity = e;
  k.focal_parameter_mm = p * s;
  if (type == ConicType::ellipse || type == ConicType::hyperbola) {
    k.a_mm = p * s / std::abs(one_minus_e2);
    k.b_mm = std::sqrt(k.a_mm * k.focal_parameter_mm);
    k.c_mm = k.a_mm * e;
  } else if (type == ConicType::circle) {
    k.a_mm = k.b_mm = p * s;
    k.c_mm = 0.0;
  }
  auto to_machine = [&](const Vec2& q) -> Vec3 { return r[0] + R * Vec3(q.x() * s, q.y() * s, 0.0); };
  k.focus = to_machine(focus2);
  k.vertex = to_machine(vertex2);
  k.centre = to_machine(centre2);
  const Vec3 xi3 = R * Vec3(xi.x(), xi.y(), 0.0);
  k.foci = {k.focus, k.focus};
  if (type == ConicType::ellipse) k.foci[1] = k.focus + 2.0 * k.c_mm * xi3;
  if (type == ConicType::hyperbola) k.foci[1] = k.focus - 2.0 * k.c_mm * xi3;
  k.axis_angle_rad = std::atan2(xi.y(), xi.x());

  // ---- Focal frame: origin at the focus, X' along xi (away from the near directrix), Z' the normal.
  const Vec3 xf = xi3.normalized(), zf = e3, yf = zf.cross(xf);
  const detail::FrameMatrices focal = detail::frame_matrices(xf, yf, zf, k.focus);
  k.focal_to_machine = focal.to_machine;
  k.machine_to_focal = focal.to_frame;
  for (std::size_t j = 0; j < 5; ++j) k.focal_points[j] = focal.local(r[j]);

  // ---- Hyperbola: the branch, decided once from r1's side of the centre along the axis; every
  // other point must be on the same side.
  if (type == ConicType::hyperbola) {
    // The vertex is on r1's side of the centre and xi points from it away from the centre, so
    // (q - centre) . xi >= a > 0 on r1's branch and <= -a on the other.
    auto on_r1_branch = [&](std::size_t j) {
      const Vec2 q(k.relative_points[j].x() / s, k.relative_points[j].y() / s);
      return (q - centre2).dot(xi) > 0.0;
    };
    // The seed's right / left (upper / lower) branch of its rotated frame: +1 / -1.
    k.branch = xi.dot(axis_dir) > 0.0 ? 1 : -1;
    for (std::size_t j = 1; j < 5; ++j)
      if (!on_r1_branch(j))
        throw InputError("hyperbola-branches",
                         fmt::format("{} {} lies on the other branch of the hyperbola than r1 (the branch is decided "
                                     "once, by r1): all five points must lie on one branch",
                                     detail::point_name(j), detail::format_point(r[j])));
  }

  // ---- Focal angles, seed (3.105)-(3.125): atan2 in (0, 2 pi]; with the normal oriented by
  // r1, r2, r3 the motion is counter-clockwise, and the seed's other branches become the check
  // that the swept angles from r1 increase: the points are in order along one arc.
  for (std::size_t j = 0; j < 5; ++j)
    k.focal_angles_rad[j] = detail::angle_in_0_2pi(std::atan2(k.focal_points[j].y(), k.focal_points[j].x()));
  const double two_pi = 2.0 * std::numbers::pi;
  for (std::size_t j = 0; j < 5; ++j) {
    double d = std::fmod(k.focal_angles_rad[j] - k.focal_angles_rad[0], two_pi);
    if (d < 0.0) d += two_pi;
    k.swept_angles_rad[j] = d;
  }
  for (std::size_t j = 1; j < 5; ++j)
    if (!(k.swept_angles_rad[j] > k.swept_angles_rad[j - 1]))
      throw InputError("points-order",
                       fmt::format("the points are not in order along one arc of the {}: going from r1 "
                                   "counter-clockwise about the normal of r1, r2, r3, {} comes at focal angle {:.6g} "
                                   "deg, not after {} at {:.6g} deg",
                                   to_string(type), detail::point_name(j), k.swept_angles_rad[j] * 180.0 / std::numbers::pi,
                                   detail::point_name(j - 1), k.swept_angles_rad[j - 1] * 180.0 / std::numbers::pi));
  k.theta15_rad = k.swept_angles_rad[4];
  return k;
}

}  // namespace kontur
