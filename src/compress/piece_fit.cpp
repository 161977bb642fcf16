#include <kontur/compress/piece_fit.hpp>
#include <kontur/error.hpp>
#include <kontur/geometry/conic_through_points.hpp>
#include <kontur/geometry/differential.hpp>
#include <kontur/geometry/polyline_fit.hpp>
#include <kontur/tolerances.hpp>

#include "nearest_on_polyline.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <numbers>

namespace kontur::compress {

const char* to_string(PieceKind kind) noexcept {
  switch (kind) {
    case PieceKind::line: return "line";
    case PieceKind::arc: return "arc";
    case PieceKind::arc_3d: return "arc3d";
    case PieceKind::conic: return "conic";
    case PieceKind::spline: return "spline";
  }
  return "line";
}

std::size_t spline_block_lines(const NurbsCurve& spline) noexcept {
  return spline.points().size() + static_cast<std::size_t>(spline.degree()) + 1;
}

namespace {

constexpr double two_pi = 2.0 * std::numbers::pi;

// The axes of a principal plane: first, second (counter-clockwise from first to second about the
// normal) and the normal: G17 X Y (Z), G18 Z X (Y), G19 Y Z (X).
constexpr std::array<std::array<int, 3>, 3> plane_axes{{{0, 1, 2}, {2, 0, 1}, {1, 2, 0}}};

// A plane to measure an arc in: origin, two in-plane unit vectors and the normal.
struct Frame {
  Vec3 origin = Vec3::Zero(), e1 = Vec3::UnitX(), e2 = Vec3::UnitY(), n = Vec3::UnitZ();
};

// Does the arc (or helix along frame.n) from v[a] through v[(a+b)/2] to v[b] keep every vertex and
// every line a..b within `tol`? The circle is the one through the three points' projections.
bool arc_fits(const std::vector<Vec3>& v, std::size_t a, std::size_t b, const Frame& f, double tol, Piece* out) {
  const std::size_t mid = (a + b) / 2;
  auto uv = [&](const Vec3& p) { return Eigen::Vector2d((p - f.origin).dot(f.e1), (p - f.origin).dot(f.e2)); };
  auto h = [&](const Vec3& p) { return (p - f.origin).dot(f.n); };
  const Eigen::Vector2d pa = uv(v[a]), pm = uv(v[mid]), pb = uv(v[b]);
  const Eigen::Vector2d d1 = pm - pa, d2 = pb - pa;
  const double cross = d1.x() * d2.y() - d1.y() * d2.x();
  const double chord = d2.norm();
  if (!(chord > 0.0) || std::abs(cross) <= 1e-12 * d1.squaredNorm() * chord) return false;
  // centre = pa + c, |c| = |c - d1| = |c - d2|
  const double s1 = d1.squaredNorm(), s2 = d2.squaredNorm();
  const Eigen::Vector2d c(pa.x() + (d2.y() * s1 - d1.y() * s2) / (2.0 * cross),
                          pa.y() + (d1.x() * s2 - d2.x() * s1) / (2.0 * cross));
  const double r = (pa - c).norm();
  if (!std::isfinite(r) || r > tolerances::compress_max_radius_chords * std::max(chord, d1.norm())) return false;
  const double dir = cross > 0.0 ? 1.0 : -1.0;  // counter-clockwise about n: +1
  // Angles swept from v[a], in the direction of motion: strictly increasing, below a full turn.
  const std::size_t count = b - a + 1;
  std::vector<double> swept(count, 0.0), radial(count, 0.0);
  double prev = std::atan2(pa.y() - c.y(), pa.x() - c.x());
  for (std::size_t k = 1; k < count; ++k) {
    const Eigen::Vector2d p = uv(v[a + k]);
    const double ang = std::atan2(p.y() - c.y(), p.x() - c.x());
    double step = dir * (ang - prev);
    while (step <= -std::numbers::pi) step += two_pi;
    while (step > std::numbers::pi) step -= two_pi;
    if (!(step > 0.0)) return false;
    swept[k] = swept[k - 1] + step;
    radial[k] = std::abs((p - c).norm() - r);
    prev = ang;
  }
  const double total = swept[count - 1];
  if (!(total < two_pi - 1e-6)) return false;
  // Each vertex: off the circle, and off the helix's linear rise; each line: its chord's sagitta.
  const double ha = h(v[a]), hb = h(v[b]);
  std::vector<double> err(count, 0.0);
  double worst = 0.0;
  for (std::size_t k = 1; k + 1 < count; ++k) {
    const double dh = h(v[a + k]) - (ha + (hb - ha) * swept[k] / total);
    err[k] = std::hypot(radial[k], dh);
    if (err[k] > tol) return false;
  }
  for (std::size_t k = 0; k + 1 < count; ++k) {
    const double half = 0.5 * (uv(v[a + k + 1]) - uv(v[a + k])).norm();
    const double sag = r - std::sqrt(std::max(0.0, r * r - half * half));
    const double e = sag + std::max(err[k], err[k + 1]);
    if (e > tol) return false;
    worst = std::max(worst, e);
  }
  if (out != nullptr) {
    out->counter_clockwise = dir > 0.0;
    out->centre = f.origin + c.x() * f.e1 + c.y() * f.e2 + ha * f.n;
    out->deviation_mm = worst;
  }
  return true;
}

bool planar_arc_fits(const std::vector<Vec3>& v, std::size_t a, std::size_t b, int plane, double tol, Piece* out) {
  const auto& ax = plane_axes[static_cast<std::size_t>(plane)];
  Frame f;
  f.origin = v[a];
  f.e1 = Vec3::Unit(ax[0]);
  f.e2 = Vec3::Unit(ax[1]);
  f.n = Vec3::Unit(ax[2]);
  if (!arc_fits(v, a, b, f, tol, out)) return false;
  if (out != nullptr) {
    out->kind = PieceKind::arc;
    out->plane = plane;
  }
  return true;
}

bool arc_3d_fits(const std::vector<Vec3>& v, std::size_t a, std::size_t b, double tol, Piece* out) {
  const std::size_t mid = (a + b) / 2;
  const Vec3 d1 = v[mid] - v[a], d2 = v[b] - v[a];
  const Vec3 n = d1.cross(d2);
  if (!(n.norm() > 1e-12 * d1.norm() * d2.norm())) return false;
  Frame f;
  f.origin = v[a];
  f.n = n.normalized();
  f.e1 = d2.normalized();
  f.e2 = f.n.cross(f.e1);
  if (!arc_fits(v, a, b, f, tol, out)) return false;
  if (out != nullptr) {
    out->kind = PieceKind::arc_3d;
    out->via[0] = v[mid];
  }
  return true;
}

bool line_fits(const std::vector<Vec3>& v, std::size_t a, std::size_t b, double tol, Piece* out) {
  const Vec3 d = v[b] - v[a];
  const double len2 = d.squaredNorm();
  if (!(len2 > 0.0)) return false;
  double prev = 0.0, worst = 0.0;
  for (std::size_t k = a + 1; k < b; ++k) {
    const double t = (v[k] - v[a]).dot(d) / len2;
    if (!(t > prev) || t >= 1.0) return false;  // the lines must go forward along it
    const double e = (v[k] - v[a] - t * d).norm();
    if (e > tol) return false;
    worst = std::max(worst, e);
    prev = t;
  }
  if (out != nullptr) {
    out->kind = PieceKind::line;
    out->deviation_mm = worst;
  }
  return true;
}

// The two-way distance between a sampled curve and the lines a..b: every sample from the lines,
// every vertex from the samples' polyline.
double sampled_deviation(const std::vector<Vec3>& v, std::size_t a, std::size_t b, const std::vector<Vec3>& samples,
                         double tol) {
  const std::vector<Vec3> lines(v.begin() + static_cast<long>(a), v.begin() + static_cast<long>(b) + 1);
  detail::NearestOnPolyline to_lines(lines, tol), to_curve(samples, tol);
  double worst = 0.0;
  for (const Vec3& q : samples) worst = std::max(worst, to_lines.distance(q));
  for (const Vec3& p : lines) worst = std::max(worst, to_curve.distance(p));
  return worst;
}

bool conic_fits(const std::vector<Vec3>& v, std::size_t a, std::size_t b, double tol, Piece* out) {
  const std::size_t span = b - a;
  const std::array<std::size_t, 5> at{a, a + span / 4, a + span / 2, a + 3 * span / 4, b};
  for (std::size_t k = 1; k < 5; ++k)
    if (at[k] <= at[k - 1]) return false;
  std::array<Vec3, 5> pts;
  for (std::size_t k = 0; k < 5; ++k) pts[k] = v[at[k]];
  try {
    ConicOptions options;
    options.plane_tolerance_mm = 0.5 * tol;
    const ConicThroughPoints fit = conic_through_points(pts, options);
    const ConicArc arc = fit.curve();
    const std::size_t count = std::max<std::size_t>(32, 8 * span);
    std::vector<Vec3> samples(count + 1);
    for (std::size_t k = 0; k <= count; ++k)
      samples[k] = arc.point(arc.u_min() + (arc.u_max() - arc.u_min()) * static_cast<double>(k) / static_cast<double>(count));
    const double e = sampled_deviation(v, a, b, samples, tol);
    if (!(e <= tol)) return false;
    if (out != nullptr) {
      out->kind = PieceKind::conic;
      out->via = {pts[1], pts[2], pts[3]};
      out->deviation_mm = e;
    }
    return true;
  } catch (const InputError&) {
    return false;  // collinear, degenerate, off the plane, out of order: not a conic here
  }
}

// The last vertex (> a) up to which `fits` holds, searching by doubling the reach from `first`
// and bisecting; a if it does not hold at `first`.
std::size_t farthest(std::size_t a, std::size_t first, std::size_t end, const std::function<bool(std::size_t)>& fits) {
  if (first > end || !fits(first)) return a;
  std::size_t good = first, step = first - a;
  std::size_t bad = end + 1;
  while (good < end) {
    step *= 2;
    const std::size_t next = std::min(end, a + step);
    if (fits(next)) {
      good = next;
    } else {
      bad = next;
      break;
    }
  }
  while (bad - good > 1) {
    const std::size_t mid = good + (bad - good) / 2;
    if (fits(mid))
      good = mid;
    else
      bad = mid;
  }
  return good;
}

// Lines a..b turn by at most smooth_max_turn at each inner vertex.
bool smooth_turns(const std::vector<Vec3>& v, std::size_t k) {
  const Vec3 t1 = (v[k] - v[k - 1]).normalized(), t2 = (v[k + 1] - v[k]).normalized();
  return t1.dot(t2) >= tolerances::smooth_max_turn_cos;
}

}  // namespace

std::vector<Piece> fit_pieces(const std::vector<Vec3>& v, double tolerance_mm, const CurveKinds& kinds) {
  std::vector<Piece> pieces;
  if (v.size() < 2) return pieces;
  const std::size_t n = v.size() - 1;
  const double tol = tolerances::compress_fit_share * tolerance_mm;

  // Greedy: from each vertex the piece that reaches farthest.
  for (std::size_t a = 0; a < n;) {
    Piece best;
    best.kind = PieceKind::line;
    best.first = a;
    best.last = farthest(a, a + 1, n, [&](std::size_t b) { return line_fits(v, a, b, tol, nullptr); });
    if (best.last == a) best.last = a + 1;  // a single line always fits
    line_fits(v, a, best.last, tol, &best);
    auto consider = [&](std::size_t min_lines, const std::function<bool(std::size_t, Piece*)>& fits) {
      const std::size_t b = farthest(a, a + min_lines, n, [&](std::size_t e) { return fits(e, nullptr); });
      if (b > best.last) {
        Piece p;
        p.first = a;
        p.last = b;
        fits(b, &p);
        best = p;
      }
    };
    if (kinds.arcs)
      for (int plane = 0; plane < 3; ++plane)
        consider(2, [&](std::size_t b, Piece* out) { return planar_arc_fits(v, a, b, plane, tol, out); });
    if (kinds.arcs_3d) consider(2, [&](std::size_t b, Piece* out) { return arc_3d_fits(v, a, b, tol, out); });
    if (kinds.conics) consider(4, [&](std::size_t b, Piece* out) { return conic_fits(v, a, b, tol, out); });
    pieces.push_back(best);
    a = best.last;
  }
  if (!kinds.splines) return pieces;

  // Splines over the stretches between sharp corners: a stretch's spline is kept where it needs
  // fewer blocks than the pieces it replaces; where the fit fails, each half is tried.
  std::vector<Piece> out;
  std::function<void(std::size_t, std::size_t)> over = [&](std::size_t i, std::size_t j) {
    const std::size_t a = pieces[i].first, b = pieces[j - 1].last;
    // the fewest blocks a spline could take: a control point per initial span, three more, the knots
    const std::size_t least = (b - a) / tolerances::compress_spline_initial_lines + 3 + 4;
    if (j - i >= 2 && least < j - i && b - a >= 4) {
      const std::vector<Vec3> sub(v.begin() + static_cast<long>(a), v.begin() + static_cast<long>(b) + 1);
      const Vec3 t0 = (v[a + 1] - v[a]).normalized(), t1 = (v[b] - v[b - 1]).normalized();
      PolylineFitOptions options;
      options.few_knots = true;
      std::optional<PolylineFit> fit = fit_polyline(sub, t0, t1, tolerance_mm, options);
      if (fit && spline_block_lines(fit->curve) < j - i) {
        Piece p;
        p.kind = PieceKind::spline;
        p.first = a;
        p.last = b;
        p.deviation_mm = fit->max_deviation_mm;
        p.spline.emplace(std::move(fit->curve));
        out.push_back(std::move(p));
        return;
      }
      if (!fit && j - i >= 4) {
        const std::size_t h = (i + j) / 2;
        over(i, h);
        over(h, j);
        return;
      }
    }
    for (std::size_t k = i; k < j; ++k) out.push_back(pieces[k]);
  };
  // A line piece much longer than the run's lines on average stays a line: a spline with few
  // knots cannot run straight along it and turn at its ends.
  double mean = 0.0;
  for (std::size_t k = 0; k < n; ++k) mean += (v[k + 1] - v[k]).norm();
  mean /= static_cast<double>(n);
  auto long_line = [&](const Piece& p) {
    const double len = (v[p.last] - v[p.first]).norm();
    return p.kind == PieceKind::line && len > tolerances::smooth_max_line_tolerances * tolerance_mm &&
           len > tolerances::compress_spline_long_line_means * mean;
  };
  for (std::size_t i = 0; i < pieces.size();) {
    if (long_line(pieces[i])) {
      out.push_back(pieces[i++]);
      continue;
    }
    std::size_t j = i + 1;
    while (j < pieces.size() && smooth_turns(v, pieces[j].first) && !long_line(pieces[j])) ++j;
    over(i, j);
    i = j;
  }
  return out;
}

}  // namespace kontur::compress
