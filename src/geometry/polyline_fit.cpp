#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>
#include <algorithm>
#include <array>
#include <utility>
#include <cmath>
#include <kontur/geometry/differential.hpp>
#include <kontur/geometry/polyline_fit.hpp>
#include <kontur/geometry/span_polynomial.hpp>
#include <kontur/tolerances.hpp>
#include <limits>

namespace kontur {
namespace {

constexpr int degree = 3;

// Derivative `k` of a cubic polynomial (ascending coefficients) at x.
double derivative(const PolyCoeffs& c, int k, double x) noexcept {
  double r = 0.0;
  for (int e = degree; e >= k; --e) {
    double f = 1.0;
    for (int q = 0; q < k; ++q) f *= e - q;
    r = r * x + f * c[static_cast<std::size_t>(e)];
  }
  return r;
}

// A span of the spline (a line of the polyline, a part of a long one, or with few knots several
// lines): its start [mm of arc], length [mm], the lines it covers (first .. last), and the four
// basis functions that are non-zero on it (control points j .. j+3 for span j), in x = u - start.
struct Span {
  double start = 0.0, length = 0.0;
  std::size_t line = 0, last_line = 0;
  std::array<PolyCoeffs, degree + 1> basis{};
};

// A term w |sum_i b_i P_{first+i} - target|^2 of the energy. Its target is kept as the residual of
// the reference control points (target - sum_i b_i ctrl_{first+i}): the fit solves for corrections.
struct Term {
  std::size_t first = 0;
  std::array<double, degree + 1> b{};
  Vec3 residual = Vec3::Zero();
  double weight = 0.0;
};


// One fit with knots at the vertices marked in `knot_at` (knot_at[i]: a knot at vertex i, for
// 0 < i < n) and inside long lines; what it found: the fit, or the deviation of each span and the
// lines each covers (for the caller that adds knots).
struct Attempt {
  std::optional<PolylineFit> fit;
  std::vector<double> deviation;
  std::vector<std::pair<std::size_t, std::size_t>> span_lines;
};

Attempt fit_with_knots(const std::vector<Vec3>& v, const std::vector<double>& s, const std::vector<char>& knot_at,
                       bool few_knots, const Vec3& start_tangent, const Vec3& end_tangent, double tolerance_mm,
                       int iterations, const PolylineFitOptions& options = {}, bool free_end_curvature = false) {
  Attempt result;
  const std::size_t n = v.size() - 1;  // lines
  const double total = s[n];

  // Knots: the marked vertices, and inside a line that is long against the tolerance a few more
  // (a span must be able to turn near a vertex and run straight along the rest of its line). A
  // span covering several lines has a piece of each (its start and length), in `pieces`.
  std::vector<double> knots(4, 0.0);
  std::vector<Span> spans;
  struct Piece {
    std::size_t span, line;
    double start, length;
  };
  std::vector<Piece> pieces;
  std::vector<std::size_t> vertex_span(n);  // the span each vertex (but the last) starts or lies in
  std::vector<int> parts(n, 1);  // spans (or pieces of one) of each line; few knots: one
  if (!few_knots)
    for (std::size_t i = 0; i < n; ++i)
      parts[i] = std::clamp(
        static_cast<int>(std::ceil((s[i + 1] - s[i]) / (tolerances::smooth_fit_span_tolerances * tolerance_mm))), 1,
        tolerances::smooth_fit_spans_per_line);
  bool new_span = true;
  for (std::size_t i = 0; i < n; ++i) {
    const double len = s[i + 1] - s[i];
    const int q = parts[i];
    for (int k = 0; k < q; ++k) {
      const double start = s[i] + len * k / q;
      const double end = k + 1 == q ? s[i + 1] : s[i] + len * (k + 1) / q;
      if (new_span) {
        Span sp;
        sp.start = start;
        sp.line = i;
        spans.push_back(sp);
      }
      if (k == 0) vertex_span[i] = spans.size() - 1;
      Span& sp = spans.back();
      sp.length = end - sp.start;
      sp.last_line = i;
      pieces.push_back(Piece{spans.size() - 1, i, start, end - start});
      new_span = k + 1 < q || (i + 1 < n && (knot_at[i + 1] != 0 || q > 1 || parts[i + 1] > 1));
      if (new_span) knots.push_back(end);
    }
  }
  for (int i = 0; i < 4; ++i) knots.push_back(total);
  const std::size_t m = spans.size();
  result.deviation.assign(m, std::numeric_limits<double>::infinity());
  for (const Span& sp : spans) result.span_lines.emplace_back(sp.line, sp.last_line);
  if (m < 4) return result;  // fewer spans than the end conditions fix
  for (std::size_t j = 0; j < m; ++j) {
    const auto b = basis_polynomials(knots, degree, static_cast<int>(j) + degree, spans[j].start);
    for (std::size_t i = 0; i <= degree; ++i) spans[j].basis[i] = b[i];
  }

  // Control points: the first and last three fixed (end points, tangents, zero curvature), the
  // others start at the polyline's point at their Greville abscissa; the fit solves for the
  // corrections (small numbers: the system's rounding stays far below the tolerance).
  const std::size_t nc = m + 3;
  auto on_polyline = [&](double u) -> Vec3 {
    const auto it = std::upper_bound(s.begin(), s.end(), u);
    const std::size_t k =
        std::min<std::size_t>(n - 1, it == s.begin() ? 0 : static_cast<std::size_t>(it - s.begin()) - 1);
    const double f = std::clamp((u - s[k]) / (s[k + 1] - s[k]), 0.0, 1.0);
    return v[k] + f * (v[k + 1] - v[k]);
  };
  std::vector<Vec3> ctrl(nc);
  for (std::size_t i = 0; i < nc; ++i) ctrl[i] = on_polyline((knots[i + 1] + knots[i + 2] + knots[i + 3]) / 3.0);
  ctrl[0] = few_knots ? v[0] : options.start_point.value_or(v[0]);
  ctrl[1] = ctrl[0] + start_tangent * knots[4] / 3.0;
  ctrl[nc - 1] = v[n];
  ctrl[nc - 2] = v[n] - end_tangent * (total - knots[nc - 1]) / 3.0;
  // the dense fit also fixes the curvature at the ends (zero: it joins the lines around it); with
  // few knots a span is long, and a straight first span would leave the lines
  if (!few_knots && !free_end_curvature) {
    // C''(0) = 6 / k4 ((P2 - P1) / k5 - (P1 - P0) / k4) with |C'(0)| = 1: the start curvature
    ctrl[2] = ctrl[1] + start_tangent * knots[5] / 3.0;
    if (!options.start_curvature.isZero()) ctrl[2] += options.start_curvature * (knots[4] * knots[5] / 6.0);
    ctrl[nc - 3] = ctrl[nc - 2] - end_tangent * (total - knots[nc - 2]) / 3.0;
  }
  const std::size_t first_free = few_knots || free_end_curvature ? 2 : 3, free = nc - 2 * first_free;  // control points first_free .. nc - 1 - first_free

  // The terms that do not change between fits: the penalties (bending: 2-point Gauss, exact for
  // the linear second derivative; jerk: the third derivative is constant on a span) and the data
  // points (the start and quarters of each line's piece of each span, on the polyline at the same
  // arc length).
  // smoothing length [mm]: with few knots the spans themselves keep the curve smooth, and the
  // penalties only keep the system well posed
  const double l = (few_knots ? tolerances::compress_spline_length_tolerances : tolerances::smooth_fit_length_tolerances) *
                   tolerance_mm;
  std::vector<Term> penalties;
  penalties.reserve(3 * m);
  std::vector<Term> data;
  data.reserve(4 * m + 1);
  std::vector<char> data_at_vertex;
  data_at_vertex.reserve(4 * m + 1);
  for (std::size_t j = 0; j < m; ++j) {
    const Span& sp = spans[j];
    const double h = sp.length;
    for (const double g : {0.5 - 0.5 / std::sqrt(3.0), 0.5 + 0.5 / std::sqrt(3.0)}) {
      Term t{j, {}, Vec3::Zero(), std::pow(l, 4) * h / 2.0};
      for (std::size_t i = 0; i <= degree; ++i) t.b[i] = derivative(sp.basis[i], 2, g * h);
      penalties.push_back(t);
    }
    Term t{j, {}, Vec3::Zero(), std::pow(l, 6) * h};
    for (std::size_t i = 0; i <= degree; ++i) t.b[i] = derivative(sp.basis[i], 3, 0.5 * h);
    penalties.push_back(t);
  }
  for (std::size_t k = 0; k < pieces.size(); ++k) {
    const Piece& pc = pieces[k];
    const Span& sp = spans[pc.span];
    const int points = k + 1 == pieces.size() ? 5 : 4;  // the last piece: its end too
    for (int q = 0; q < points; ++q) {
      const double f = q / 4.0;
      Term d{pc.span, {}, on_polyline(pc.start + f * pc.length), pc.length / 4.0};
      for (std::size_t i = 0; i <= degree; ++i) d.b[i] = derivative(sp.basis[i], 0, pc.start - sp.start + f * pc.length);
      data.push_back(d);
      // a vertex: the start of a line's first piece, or the last piece's end
      data_at_vertex.push_back((q == 0 && pc.start == s[pc.line]) || q == 4 ? 1 : 0);
    }
  }

  for (auto* terms : {&penalties, &data})
    for (Term& t : *terms)
      for (std::size_t i = 0; i <= degree; ++i) t.residual -= t.b[i] * ctrl[t.first + i];

  // What the check of a fit needs and no fit changes: the basis values at each span's samples
  // (close enough that the curve between them stays near their chords), and the lines around
  // each piece of a line the samples are measured against (those within `reach` of arc, at least
  // one more on each side: a subset of the lines, so the true distance is no larger).
  const double reach = 4.0 * tolerance_mm;  // [mm of arc]
  struct Sample {
    std::size_t span, piece;
    std::array<double, degree + 1> b;
  };
  std::vector<Sample> sample_basis;
  std::vector<std::size_t> sample_start(m + 1);
  std::vector<std::pair<long, long>> window(pieces.size());  // lines first .. last around piece k
  for (std::size_t k = 0; k < pieces.size(); ++k) {
    const Piece& pc = pieces[k];
    const auto line = static_cast<long>(pc.line);
    long lo = line, hi = line;
    while (lo > 0 && s[static_cast<std::size_t>(lo)] > pc.start - reach) --lo;
    while (hi + 1 < static_cast<long>(n) && s[static_cast<std::size_t>(hi) + 1] < pc.start + pc.length + reach) ++hi;
    window[k] = {std::min(lo, line - 1), std::max(hi, line + 1)};
  }
  std::vector<std::size_t> piece_sample(pieces.size() + 1), line_piece(n + 1, 0);
  for (std::size_t k = pieces.size(); k-- > 0;) line_piece[pieces[k].line] = k;
  for (std::size_t j = 0, k = 0; j < m; ++j) {
    sample_start[j] = sample_basis.size();
    const Span& sp = spans[j];
    for (; k < pieces.size() && pieces[k].span == j; ++k) {
      piece_sample[k] = sample_basis.size();
      const Piece& pc = pieces[k];
      const int count = std::clamp(static_cast<int>(std::ceil(pc.length / (0.25 * tolerance_mm))), 4, 32);
      const bool last_piece = k + 1 == pieces.size() || pieces[k + 1].span != j;
      for (int q = 0; q <= count; ++q) {
        if (q == count && !last_piece) break;  // the next piece's first sample
        Sample smp{j, k, {}};
        for (std::size_t i = 0; i <= degree; ++i)
          smp.b[i] = derivative(sp.basis[i], 0, pc.start - sp.start + pc.length * q / count);
        sample_basis.push_back(smp);
      }
    }

  }
  sample_start[m] = sample_basis.size();
  piece_sample[pieces.size()] = sample_basis.size();

  // Weight factors of each span's data points: on the lines, and at the vertices. Where the curve
  // strays from the lines the first rise; where it passes a vertex too far, only the second: more
  // weight on the lines there would pull the curve further into the corner (lines 25 tolerances
  // long turning by 20 degrees: a sagitta of 1.1 tolerances, the curve must pass between).
  std::vector<double> factor(m, 1.0), vertex_factor(m, 1.0);
  std::vector<double> vertex_deviation(m);
  const double target = tolerances::smooth_tolerance_share * tolerance_mm;
  // the least square [mm^2] whose root is beyond the target (the root is monotone: a square is
  // beyond it exactly when its root is)
  double target2_beyond = target * target;
  while (std::sqrt(target2_beyond) > target) target2_beyond = std::nextafter(target2_beyond, 0.0);
  while (!(std::sqrt(target2_beyond) > target)) target2_beyond = std::nextafter(target2_beyond, std::numeric_limits<double>::infinity());
  std::vector<Vec3> points = ctrl;          // the fitted control points
  std::vector<double> deviation(m);
  std::vector<Vec3> samples(sample_basis.size());
  std::vector<double> own_d2(sample_basis.size());  // a sample's squared distance from its own line
  std::vector<double> raise(m);  // each line's factor on its weights in this iteration

  // The normal equations of the free control points: a banded matrix (three off-diagonals) whose
  // pattern never changes: built once (its lower triangle, which the LDL^T solver reads), analysed
  // once, and refilled each fit: the penalties' share is the same every time, the data's is
  // weighted anew.
  const auto nf = static_cast<Eigen::Index>(free);
  Eigen::SparseMatrix<double> a(nf, nf);
  Eigen::MatrixX3d rhs_penalty = Eigen::MatrixX3d::Zero(nf, 3), rhs(nf, 3);
  // (in its natural order: a banded matrix factors without fill-in, and AMD's reordering of it
  // cost a tenth of the smoothing of circle_small_segments)
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>, Eigen::Lower, Eigen::NaturalOrdering<int>> solver;
  std::vector<double> penalty_values;
  // Adds w |sum b_i P_i - target|^2 to the matrix (lower triangle) and `r`.
  auto add = [&](const Term& t, double weight, Eigen::MatrixX3d& r) {
    const Vec3& res = t.residual;
    for (std::size_t i = 0; i <= degree; ++i) {
      const std::size_t ci = t.first + i;
      if (ci < first_free || ci >= first_free + free) continue;
      const auto fi = static_cast<Eigen::Index>(ci - first_free);
      r.row(fi) += weight * t.b[i] * res.transpose();
      for (std::size_t k = 0; k <= degree; ++k) {
        const std::size_t ck = t.first + k;
        if (ck < ci || ck >= first_free + free) continue;  // lower triangle: row >= column
        // (column fi holds rows fi .. fi + degree in order: the entry's place without a search)
        a.valuePtr()[a.outerIndexPtr()[fi] + static_cast<Eigen::Index>(ck - ci)] += weight * t.b[i] * t.b[k];
      }
    }
  };
  if (free > 0) {
    std::vector<Eigen::Triplet<double>> pattern;
    pattern.reserve(4 * free);
    for (std::size_t c = 0; c < free; ++c)
      for (std::size_t r = c; r < std::min(free, c + degree + 1); ++r)
        pattern.emplace_back(static_cast<Eigen::Index>(r), static_cast<Eigen::Index>(c), 0.0);
    a.setFromTriplets(pattern.begin(), pattern.end());
    a.makeCompressed();
    for (const Term& t : penalties) add(t, t.weight, rhs_penalty);
    penalty_values.assign(a.valuePtr(), a.valuePtr() + a.nonZeros());
    solver.analyzePattern(a);
  }

  for (int iteration = 1; iteration <= iterations; ++iteration) {
    if (free > 0) {
      std::copy(penalty_values.begin(), penalty_values.end(), a.valuePtr());
      rhs = rhs_penalty;
      for (std::size_t q = 0; q < data.size(); ++q) {
        const Term& d = data[q];
        add(d, d.weight * (data_at_vertex[q] != 0 ? vertex_factor[d.first] : factor[d.first]), rhs);
      }
      solver.factorize(a);
      if (solver.info() != Eigen::Success) return result;
      const Eigen::MatrixX3d x = solver.solve(rhs);
      if (solver.info() != Eigen::Success || !x.allFinite()) return result;
      for (std::size_t i = 0; i < free; ++i)
        points[first_free + i] = ctrl[first_free + i] + x.row(static_cast<Eigen::Index>(i)).transpose();
    }

    // The curve at the samples; the distance of each from the lines around its span, and of each
    // inner vertex from the chords of the samples around it (the ends are on the curve).
    for (std::size_t q = 0; q < samples.size(); ++q) {
      const Sample& smp = sample_basis[q];
      Vec3 c = Vec3::Zero();
      for (std::size_t i = 0; i <= degree; ++i) c += smp.b[i] * points[smp.span + i];
      samples[q] = c;
    }
    std::fill(vertex_deviation.begin(), vertex_deviation.end(), 0.0);
    for (std::size_t i = 1; i < n; ++i) {
      const std::size_t j = vertex_span[i];  // the span that starts at vertex i, or has it inside
      const std::size_t k = line_piece[i];   // the first piece of line i
      double d = std::numeric_limits<double>::infinity();
      // the samples of the two pieces before the vertex and the two after (dense: the spans)
      const std::size_t q0 = piece_sample[k >= 2 ? k - 2 : 0], q1 = piece_sample[std::min(pieces.size(), k + 2)];
      for (std::size_t q = q0; q + 1 < q1; ++q) d = std::min(d, segment_distance(v[i], samples[q], samples[q + 1]));
      if (j > 0 && spans[j].start == s[i]) vertex_deviation[j - 1] = std::max(vertex_deviation[j - 1], d);
      vertex_deviation[j] = std::max(vertex_deviation[j], d);
    }
    // A sample's distance from the lines is the nearest of its window's lines, in squares; its own
    // line bounds it from above. First each span is judged: does a sample stray beyond the target?
    // Only samples whose own line is beyond it can, and each is measured until a line is within it.
    // Only when none strays (the fit is kept) is the largest distance measured exactly: the sample
    // farthest from its own line first, then only those whose own line is farther than the largest
    // so far, each until one of its lines is no farther (then it cannot raise the largest).
    const auto line_d2 = [&](std::size_t q, long i) {
      return segment_distance_squared(samples[q], v[static_cast<std::size_t>(i)], v[static_cast<std::size_t>(i) + 1]);
    };
    const auto own_line = [&](std::size_t q) { return static_cast<long>(pieces[sample_basis[q].piece].line); };
    // the nearest line's distance from sample q [mm^2], or one below `floor2` when that is below it
    const auto nearest_d2 = [&](std::size_t q, double floor2) {
      const std::size_t k = sample_basis[q].piece;
      const long own = own_line(q);
      double near2 = own_d2[q];
      for (long i = std::max(window[k].first, 0L); i <= std::min(window[k].second, static_cast<long>(n) - 1) &&
                                                   near2 >= floor2;
           ++i)
        if (i != own) near2 = std::min(near2, line_d2(q, i));
      return near2;
    };
    std::size_t farthest = 0;
    for (std::size_t q = 0; q < samples.size(); ++q) {
      own_d2[q] = line_d2(q, own_line(q));
      if (own_d2[q] > own_d2[farthest]) farthest = q;
    }
    bool strays = false;
    for (std::size_t j = 0; j < m; ++j) {
      deviation[j] = 0.0;  // within the target (its exact value is not needed)
      for (std::size_t q = sample_start[j]; q < sample_start[j + 1]; ++q)
        if (own_d2[q] >= target2_beyond) {
          const double near2 = nearest_d2(q, target2_beyond);
          if (near2 >= target2_beyond) {
            deviation[j] = std::sqrt(near2);  // beyond the target: the weights rise
            strays = true;
            break;
          }
        }
    }
    double worst = 0.0;
    if (!strays) {
      double d2 = samples.empty() ? 0.0 : nearest_d2(farthest, 0.0);
      for (std::size_t q = 0; q < samples.size(); ++q)
        if (q != farthest && own_d2[q] > d2) d2 = std::max(d2, nearest_d2(q, d2));
      worst = std::sqrt(d2);
    }
    for (std::size_t j = 0; j < m; ++j) {
      result.deviation[j] = std::max(deviation[j], vertex_deviation[j]);
      worst = std::max(worst, result.deviation[j]);
    }
    if (worst <= target) {
      result.fit = PolylineFit{NurbsCurve(NurbsData{degree, knots, points, {}}), s, worst, iteration};
      return result;
    }
    // More weight where the curve strays, and on the spans beside it: on the lines where it strays
    // from them, on the vertices where it passes one too far.
    // (far beyond the target, as a fit of lines much shorter than its smoothing length starts: the
    // step squared, which saves the iterations that would only approach it. Nearer, the dense fit
    // raises each line by how far it strays, (deviation / target)^smooth_fit_weight_power within
    // [smooth_fit_weight_step_min, smooth_fit_weight_step], and a neighbour by the largest of its
    // neighbours': a line just beyond the target no longer gets the whole step, which left its
    // stretch of the curve far inside the tolerance and bent it harder than needed.)
    const bool far = worst > tolerances::smooth_fit_far_targets * target;
    for (auto [dev, weights] : {std::pair{&deviation, &factor}, std::pair{&vertex_deviation, &vertex_factor}}) {
      std::fill(raise.begin(), raise.end(), 1.0);
      for (std::size_t j = 0; j < m; ++j) {
        if (!((*dev)[j] > target)) continue;
        const double step =
            far ? tolerances::smooth_fit_weight_step * tolerances::smooth_fit_weight_step
            : few_knots ? tolerances::smooth_fit_weight_step
                        : std::clamp(std::pow((*dev)[j] / target, tolerances::smooth_fit_weight_power),
                                     tolerances::smooth_fit_weight_step_min, tolerances::smooth_fit_weight_step);
        for (std::size_t k = j > 0 ? j - 1 : 0; k <= std::min(m - 1, j + 1); ++k) raise[k] = std::max(raise[k], step);
      }
      for (std::size_t j = 0; j < m; ++j) (*weights)[j] *= raise[j];
    }
  }
  return result;
}

}  // namespace

std::optional<PolylineFit> fit_polyline(const std::vector<Vec3>& v, const Vec3& start_tangent, const Vec3& end_tangent,
                                        double tolerance_mm, const PolylineFitOptions& options) {
  if (v.size() < 5 || !(tolerance_mm > 0.0)) return std::nullopt;
  const std::size_t n = v.size() - 1;  // lines
  std::vector<double> s(n + 1, 0.0);   // arc length at each vertex [mm]
  for (std::size_t i = 0; i < n; ++i) s[i + 1] = s[i] + (v[i + 1] - v[i]).norm();
  const double total = s[n];
  if (!std::isfinite(total)) return std::nullopt;
  for (std::size_t i = 0; i < n; ++i)
    if (!(s[i + 1] - s[i] > 1e-9 * total)) return std::nullopt;
  if (!options.few_knots) {
    const std::vector<char> every(n + 1, 1);
    std::optional<PolylineFit> fit = fit_with_knots(v, s, every, false, start_tangent, end_tangent, tolerance_mm,
                                                    tolerances::smooth_fit_iterations, options)
                                         .fit;
    if (fit) return fit;
    // A curve with zero curvature at its ends cannot follow lines that bend tightly right at them
    // (a spiral of lines 25 tolerances long turning by 20 degrees each): then one whose curvature
    // at the ends is free (a curvature jump for the planner there, instead of the whole run's
    // corners). Not where the curve continues a cut run, whose start is fixed.
    if (options.start_point) return std::nullopt;
    return fit_with_knots(v, s, every, false, start_tangent, end_tangent, tolerance_mm,
                          tolerances::smooth_fit_iterations, options, true)
        .fit;
  }

  // Few knots: one every few lines to begin with (at least four spans), then one more inside every
  // span that strays, until the fit keeps the tolerance; when no straying span has a vertex left
  // inside, the fit raises the weights there instead, as the dense fit does.
  std::vector<char> knot_at(n + 1, 0);
  const std::size_t step = std::max<std::size_t>(1, n / tolerances::compress_spline_initial_spans);
  for (std::size_t i = step; i + step / 2 < n; i += step) knot_at[i] = 1;
  for (int round = 0; round < tolerances::compress_spline_knot_rounds; ++round) {
    Attempt a = fit_with_knots(v, s, knot_at, true, start_tangent, end_tangent, tolerance_mm,
                               tolerances::compress_spline_round_iterations);
    if (a.fit) return a.fit;
    if (options.max_control_points > 0 && a.deviation.size() + 3 > options.max_control_points) return std::nullopt;
    const double target = tolerances::smooth_tolerance_share * tolerance_mm;
    bool added = false;
    for (std::size_t j = 0; j < a.deviation.size(); ++j) {
      if (!(a.deviation[j] <= target) && a.span_lines[j].second > a.span_lines[j].first) {
        knot_at[(a.span_lines[j].first + a.span_lines[j].second + 1) / 2] = 1;
        added = true;
      }
    }
    if (!added) break;
  }
  if (options.max_control_points > 0) {
    std::size_t spans = 1;
    for (std::size_t i = 1; i < n; ++i) spans += knot_at[i] != 0 ? 1 : 0;
    if (spans + 3 > options.max_control_points) return std::nullopt;
  }
  return fit_with_knots(v, s, knot_at, true, start_tangent, end_tangent, tolerance_mm, tolerances::smooth_fit_iterations)
      .fit;
}

}  // namespace kontur
