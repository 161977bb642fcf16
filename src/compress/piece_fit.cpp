#include <kontur/compress/piece_fit.hpp>
#include <kontur/error.hpp>
#include <kontur/geometry/conic_through_points.hpp>
#include <kontur/geometry/differential.hpp>
#include <kontur/geometry/golden_section.hpp>
#include <kontur/geometry/polyline_fit.hpp>
#include <kontur/tolerances.hpp>

#include "two_way_distance.hpp"

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

std::array<int, 3> plane_axes(int plane) noexcept {
  static constexpr std::array<std::array<int, 3>, 3> axes{{{0, 1, 2}, {2, 0, 1}, {1, 2, 0}}};
  return axes[static_cast<std::size_t>(std::clamp(plane, 0, 2))];
}

std::size_t spline_block_lines(const NurbsCurve& spline) noexcept {
  return spline.points().size() + static_cast<std::size_t>(spline.degree()) + 1;
}

namespace {

constexpr double two_pi = 2.0 * std::numbers::pi;


// A plane to measure an arc in: origin, two in-plane unit vectors and the normal.
struct Frame {
  Vec3 origin = Vec3::Zero(), e1 = Vec3::UnitX(), e2 = Vec3::UnitY(), n = Vec3::UnitZ();
};

// Does an arc (or a helix along frame.n) from v[a] to v[b] keep every vertex and every line a..b
// within `tol`? The arcs through the two ends form a family with their centres on the chord's
// bisector; the one through v[(a+b)/2] is tried first, and if it strays, the one whose largest
// deviation is least (golden-section search between the circles through the ends and each vertex).
// With `tangent` (a unit vector in the frame's plane), only the arc that starts along it is tried.
bool arc_fits(const std::vector<Vec3>& v, std::size_t a, std::size_t b, const Frame& f, double tol, Piece* out,
              const Vec3* tangent = nullptr) {
  const std::size_t mid = (a + b) / 2, count = b - a + 1;
  std::vector<Eigen::Vector2d> q(count);
  std::vector<double> h(count);
  for (std::size_t k = 0; k < count; ++k) {
    const Vec3 d = v[a + k] - f.origin;
    q[k] = Eigen::Vector2d(d.dot(f.e1), d.dot(f.e2));
    h[k] = d.dot(f.n);
  }
  const Eigen::Vector2d& pa = q.front();
  const Eigen::Vector2d& pb = q.back();
  const Eigen::Vector2d d1 = q[mid - a] - pa, d2 = pb - pa;
  const double cross = d1.x() * d2.y() - d1.y() * d2.x();
  const double chord = d2.norm();
  if (!(chord > 0.0) || std::abs(cross) <= 1e-12 * d1.squaredNorm() * chord) return false;
  const double dir = cross > 0.0 ? 1.0 : -1.0;  // counter-clockwise about n: +1
  // centres c(t) = m + t n on the bisector; n points to the left of the chord
  const Eigen::Vector2d m = 0.5 * (pa + pb), nrm = Eigen::Vector2d(-d2.y(), d2.x()) / chord;
  const double half2 = 0.25 * chord * chord;
  std::vector<double> swept(count), radial(count);
  // The largest deviation of the arc with centre parameter t (infinity if the vertices do not go
  // round it in order within a turn): at each vertex its distance from the helix; along each line
  // the arc's distance from the chord at its middle (the sagitta against the vertices' offsets).
  auto error = [&](double t) {
    const Eigen::Vector2d c = m + t * nrm;
    const double r = std::sqrt(half2 + t * t);
    if (!std::isfinite(r) || r > tolerances::compress_max_radius_chords * chord) return HUGE_VAL;
    double prev = std::atan2(pa.y() - c.y(), pa.x() - c.x());
    swept[0] = 0.0;
    radial[0] = 0.0;
    for (std::size_t k = 1; k < count; ++k) {
      const double ang = std::atan2(q[k].y() - c.y(), q[k].x() - c.x());
      double step = dir * (ang - prev);
      while (step <= -std::numbers::pi) step += two_pi;
      while (step > std::numbers::pi) step -= two_pi;
      if (!(step > 0.0)) return HUGE_VAL;
      swept[k] = swept[k - 1] + step;
      radial[k] = (q[k] - c).norm() - r;  // > 0: outside the arc
      prev = ang;
    }
    radial[count - 1] = 0.0;
    const double total = swept[count - 1];
    if (!(total < two_pi - 1e-6)) return HUGE_VAL;
    double worst = 0.0, rise = 0.0;
    for (std::size_t k = 1; k + 1 < count; ++k) {
      const double dh = h[k] - (h[0] + (h[count - 1] - h[0]) * swept[k] / total);
      worst = std::max(worst, std::hypot(radial[k], dh));
      rise = std::max(rise, std::abs(dh));
    }
    for (std::size_t k = 0; k + 1 < count; ++k) {
      const double half = 0.5 * (q[k + 1] - q[k]).norm();
      const double sag = r - std::sqrt(std::max(0.0, r * r - half * half));
      // the chord's offset from the arc along it, x in [0, 1]: d_k + (d_k+1 - d_k) x - 4 sag x (1 - x)
      const double d0 = radial[k], delta = radial[k + 1] - radial[k];
      double off = std::max(std::abs(d0), std::abs(radial[k + 1]));
      if (sag > 0.0) {
        const double x = (4.0 * sag - delta) / (8.0 * sag);
        if (x > 0.0 && x < 1.0) off = std::max(off, std::abs(d0 + delta * x - 4.0 * sag * x * (1.0 - x)));
      }
      worst = std::max(worst, off + rise);
    }
    return worst;
  };
  // the circle through the middle vertex
  const double tm = [&] {
    const Eigen::Vector2d w = m - q[mid - a];
    return (half2 - w.squaredNorm()) / (2.0 * nrm.dot(w));
  }();
  double t = tm;
  if (tangent != nullptr) {
    // the centre on the bisector and on the normal of the tangent at v[a]: (c - pa) . t = 0
    const Eigen::Vector2d t2(tangent->dot(f.e1), tangent->dot(f.e2));
    const double den = nrm.dot(t2);
    if (!(std::abs(den) > 1e-12)) return false;  // along the chord: a line
    t = -(m - pa).dot(t2) / den;
    // the arc must leave along the tangent, not against it
    const Eigen::Vector2d c = m + t * nrm, radius = pa - c;
    const Eigen::Vector2d along = dir * Eigen::Vector2d(-radius.y(), radius.x());
    if (!(along.dot(t2) > 0.0)) return false;
  }
  double e = error(t);
  if (tangent == nullptr && e > tol && e < tolerances::compress_arc_search_tolerances * tol && count > 3) {
    double lo = tm, hi = tm;
    for (std::size_t k = 1; k + 1 < count; ++k) {
      const Eigen::Vector2d w = m - q[k];
      const double den = 2.0 * nrm.dot(w);
      if (std::abs(den) < 1e-300) continue;
      const double tk = (half2 - w.squaredNorm()) / den;
      if (std::isfinite(tk)) {
        lo = std::min(lo, tk);
        hi = std::max(hi, tk);
      }
    }
    const auto [t_best, e_best] = golden_section_minimum(error, lo, hi, tolerances::compress_arc_search_steps, tol);
    if (e_best < e) {
      e = e_best;
      t = t_best;
    }
  }
  if (!(e <= tol)) return false;
  if (out != nullptr) {
    error(t);
    const Eigen::Vector2d c = m + t * nrm;
    const double r = std::sqrt(half2 + t * t);
    out->counter_clockwise = dir > 0.0;
    out->centre = f.origin + c.x() * f.e1 + c.y() * f.e2 + h[0] * f.n;
    out->deviation_mm = e;
    // the point halfway round (what a three-point arc is written through)
    const double half_way = std::atan2(pa.y() - c.y(), pa.x() - c.x()) + dir * 0.5 * swept[count - 1];
    out->via[0] = f.origin + (c.x() + r * std::cos(half_way)) * f.e1 + (c.y() + r * std::sin(half_way)) * f.e2 +
                  0.5 * (h[0] + h[count - 1]) * f.n;
    // the tangents at the ends (a helix's rise along the normal included)
    const double length = r * swept[count - 1];
    auto tangent_at = [&](const Eigen::Vector2d& p) {
      const Eigen::Vector2d radius = p - c, along = dir * Eigen::Vector2d(-radius.y(), radius.x()) / radius.norm();
      return Vec3(along.x() * f.e1 + along.y() * f.e2 + (h[count - 1] - h[0]) / length * f.n).normalized();
    };
    out->start_tangent = tangent_at(pa);
    out->end_tangent = tangent_at(pb);
  }
  return true;
}

bool planar_arc_fits(const std::vector<Vec3>& v, std::size_t a, std::size_t b, int plane, double tol, Piece* out,
                     const Vec3* tangent = nullptr) {
  const std::array<int, 3> ax = plane_axes(plane);
  Frame f;
  f.origin = v[a];
  f.e1 = Vec3::Unit(ax[0]);
  f.e2 = Vec3::Unit(ax[1]);
  f.n = Vec3::Unit(ax[2]);
  if (tangent != nullptr) {
    // the tangent in the plane; a helix would leave it by its rise: allowed up to the kink limit
    if (std::abs(tangent->dot(f.n)) > tolerances::compress_kink_rad) return false;
    const double rise = (v[b] - v[a]).dot(f.n), run = (v[b] - v[a]).norm();
    if (std::abs(rise) > tolerances::compress_kink_rad * run) return false;
  }
  if (!arc_fits(v, a, b, f, tol, out, tangent)) return false;
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
    out->start_tangent = out->end_tangent = d.normalized();
  }
  return true;
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
    // the reader's limit (tolerances::gcode_conic_plane_mm), with room for the written rounding
    options.plane_tolerance_mm = std::min(0.5 * tol, 0.5 * tolerances::gcode_conic_plane_mm);
    const ConicThroughPoints fit = conic_through_points(pts, options);
    const ConicArc arc = fit.curve();
    std::vector<Vec3> samples{v[a]};
    detail::append_samples(arc, std::max<std::size_t>(32, 8 * span), samples);
    const double e = detail::two_way_distance(std::span(v).subspan(a, b - a + 1), samples, tol);
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

// The last vertex (> a) up to which `fits` holds: the reach doubles from `first` while it holds
// (and, before it first holds, up to three times more: rounded coordinates can make the first few
// vertices of an arc collinear), then bisects; a if it never holds.
std::size_t farthest(std::size_t a, std::size_t first, std::size_t end, const std::function<bool(std::size_t)>& fits) {
  if (first > end) return a;
  std::size_t good = a, bad = end + 1, step = first - a;
  int misses = 0;
  for (std::size_t b = first;; b = std::min(end, a + step)) {
    if (fits(b)) {
      good = b;
      bad = end + 1;
    } else {
      bad = b;
      if (good > a || ++misses > 3) break;
    }
    if (b == end) break;
    step *= 2;
  }
  if (good == a) return a;
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

  // Greedy: from each vertex the piece that reaches farthest; where the last piece ended with a
  // tangent, the smooth pieces (a line along it, an arc leaving along it) are preferred while they
  // reach at least half as far: the path stays tangent-continuous, which a planner runs faster.
  std::optional<Vec3> tangent;  // the end tangent of the piece before (none: free)
  for (std::size_t a = 0; a < n;) {
    Piece best;
    best.kind = PieceKind::line;
    best.first = a;
    best.last = farthest(a, a + 1, n, [&](std::size_t b) { return line_fits(v, a, b, tol, nullptr); });
    if (best.last == a) best.last = a + 1;  // a single line always fits
    line_fits(v, a, best.last, tol, &best);
    // `into` becomes the piece `fits` makes from a to the farthest vertex (from a + min_lines on) if
    // that is farther than where `into` ends
    auto extend = [&](Piece& into, std::size_t min_lines, const std::function<bool(std::size_t, Piece*)>& fits) {
      const std::size_t b = farthest(a, a + min_lines, n, [&](std::size_t e) { return fits(e, nullptr); });
      if (b <= into.last) return;
      Piece p;
      p.first = a;
      p.last = b;
      fits(b, &p);
      into = p;
    };
    if (kinds.arcs)
      for (int plane = 0; plane < 3; ++plane)
        extend(best, 2, [&](std::size_t b, Piece* out) { return planar_arc_fits(v, a, b, plane, tol, out); });
    if (kinds.arcs_3d) extend(best, 2, [&](std::size_t b, Piece* out) { return arc_3d_fits(v, a, b, tol, out); });
    if (kinds.conics) extend(best, 4, [&](std::size_t b, Piece* out) { return conic_fits(v, a, b, tol, out); });
    if (tangent && kinds.arcs) {
      const Vec3 t_in = *tangent;
      Piece smooth;
      smooth.first = a;
      smooth.last = a;
      if (best.kind == PieceKind::line && best.start_tangent.dot(t_in) >= std::cos(tolerances::compress_kink_rad))
        smooth = best;
      for (int plane = 0; plane < 3; ++plane)
        extend(smooth, 1, [&](std::size_t b, Piece* out) { return planar_arc_fits(v, a, b, plane, tol, out, &t_in); });
      if (smooth.last > a && 2 * (smooth.last - a) >= best.last - a) best = smooth;
    }
    pieces.push_back(best);
    if (best.kind == PieceKind::line || best.kind == PieceKind::arc)
      tangent = best.end_tangent;
    else
      tangent.reset();
    // a corner of the programmed path (beyond smooth_max_turn) starts free
    if (tangent && best.last < n && tangent->dot((v[best.last + 1] - v[best.last]).normalized()) < tolerances::smooth_max_turn_cos)
      tangent.reset();
    a = best.last;
  }
  if (!kinds.splines) return pieces;

  // Splines over the stretches between sharp corners: a stretch's spline is kept where it needs
  // fewer blocks than the pieces it replaces; where the fit fails, each half is tried.
  std::vector<Piece> out;
  std::function<void(std::size_t, std::size_t)> over = [&](std::size_t i, std::size_t j) {
    const std::size_t a = pieces[i].first, b = pieces[j - 1].last;
    // the fewest blocks a spline could take: a control point per initial span, three more, the knots
    const std::size_t least = tolerances::compress_spline_initial_spans + 3 + 4;
    if (j - i >= 2 && least < j - i && b - a >= 4) {
      const std::vector<Vec3> sub(v.begin() + static_cast<long>(a), v.begin() + static_cast<long>(b) + 1);
      const Vec3 t0 = (v[a + 1] - v[a]).normalized(), t1 = (v[b] - v[b - 1]).normalized();
      PolylineFitOptions options;
      options.few_knots = true;
      options.max_control_points = j - i - 1 - (static_cast<std::size_t>(3) + 1);  // fewer lines than the pieces
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
