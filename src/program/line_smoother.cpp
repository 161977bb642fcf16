#include <algorithm>
#include <cstring>
#include <iterator>
#include <kontur/geometry/corner_blend_curve.hpp>
#include <kontur/geometry/curve_piece.hpp>
#include <kontur/geometry/differential.hpp>
#include <kontur/geometry/length.hpp>
#include <kontur/geometry/line_segment.hpp>
#include <kontur/geometry/polyline_fit.hpp>
#include <kontur/geometry/span_polynomial.hpp>
#include <kontur/program/line_smoother.hpp>
#include <kontur/tolerances.hpp>
#include <limits>
#include <memory>

namespace kontur::program {
namespace {

const LineSegment* feed_line(const Move& m) {
  if (std::strcmp(m.type, "line") != 0 || moves_extra_axes(m)) return nullptr;  // extra axes: as programmed
  return dynamic_cast<const LineSegment*>(m.curve.get());
}

// The tolerance a run through the end of `m` keeps [mm] (0: none).
double smoothing_tolerance(const Move& m) {
  if (m.exact_stop || !(m.corner_tolerance_mm > 0.0)) return 0.0;
  return std::max(m.corner_tolerance_mm, m.naive_cam_tolerance_mm);
}

const LineSegment& line_of(const Move& m) { return static_cast<const LineSegment&>(*m.curve); }

double line_length(const LineSegment& l) { return (l.end() - l.start()).norm(); }

// `next` starts where `last` ends (to rounding).
bool continues(const LineSegment& last, const LineSegment& next) {
  return (next.start() - last.end()).norm() <= 1e-12 * std::max(1.0, last.end().norm());
}

}  // namespace

bool LineSmoother::joins(const Move& move) const {
  const LineSegment* next = feed_line(move);
  if (next == nullptr) return false;
  const Move& last_move = run_.back();
  const auto& last = line_of(last_move);
  const double tol = smoothing_tolerance(last_move);
  if (!(tol > 0.0) || tol != smoothing_tolerance(run_.front())) return false;
  const double la = line_length(last), lb = line_length(*next);
  if (la < tolerances::blend_min_line_mm || lb < tolerances::blend_min_line_mm) return false;
  // the line before becomes an inner line of the run (the first line may be of any length)
  if (run_.size() >= 2 && la > tolerances::smooth_max_line_tolerances * tol) return false;
  if (!continues(last, *next)) return false;
  const Vec3 t1 = (last.end() - last.start()) / la, t2 = (next->end() - next->start()) / lb;
  const double turn_cos = t1.dot(t2);
  if (turn_cos >= tolerances::smooth_max_turn_cos) return true;
  // A sharper turn between lines short against the tolerance (the two lines of the vertex and the
  // one before, in the run or the line the run follows) is no corner of the part: a curve cutting
  // it along the longer line would stay well within the tolerance.
  if (turn_cos < tolerances::smooth_soft_corner_turn_cos) return false;
  const double la_prev = run_.size() >= 2 ? line_length(line_of(run_[run_.size() - 2])) : before_run_mm_;
  if (std::max({la_prev, la, lb}) > tolerances::smooth_soft_corner_line_tolerances * tol) return false;
  return unit_blend_deviation(t1, t2) * std::max(la, lb) <= tolerances::smooth_soft_corner_share * tol;
}

void LineSmoother::push(const Move& move, std::vector<Move>& out) {
  if (!enabled_) {
    out.push_back(move);
    return;
  }
  const LineSegment* line = feed_line(move);
  // the line the move follows, if it is a line that continues it [mm] (else infinite): kept as
  // before_run_mm_ if the move starts a run
  double before_mm = std::numeric_limits<double>::infinity();
  if (!run_.empty()) {
    const LineSegment& last = line_of(run_.back());
    if (line != nullptr && continues(last, *line)) before_mm = line_length(last);
    if (!joins(move))
      flush(out);
    else if (run_.size() >= tolerances::smooth_max_run_lines &&
             (beyond_mm_ >= tolerances::smooth_run_overlap_tolerances * smoothing_tolerance(run_.front()) ||
              run_.size() >= tolerances::smooth_max_run_lines + tolerances::smooth_run_overlap_max_lines))
      cut(out);
  }
  if (line != nullptr) {
    if (run_.size() >= tolerances::smooth_max_run_lines) beyond_mm_ += line_length(*line);
    if (run_.empty()) before_run_mm_ = before_mm;
    run_.push_back(move);
  } else {
    out.push_back(move);
  }
}

std::optional<LineSmoother::Fitted> LineSmoother::fit_run() const {
  const std::size_t n = run_.size();
  if (n < tolerances::smooth_min_lines) return std::nullopt;
  // A fresh run: the curve from the end of its first line (which stays a line) to the start of its
  // last one. A continued run: from where the curve before ended, near the start of its first line.
  auto vertices = std::make_shared<std::vector<Vec3>>();
  vertices->reserve(n);
  if (carry_) vertices->push_back(line_of(run_.front()).start());
  for (std::size_t i = 1; i < n; ++i) vertices->push_back(line_of(run_[i]).start());
  const auto& first = line_of(run_.front());
  const auto& last = line_of(run_.back());
  const Vec3 t1 = (last.end() - last.start()).normalized();
  Vec3 t0 = (first.end() - first.start()).normalized();
  PolylineFitOptions options;
  if (carry_) {
    t0 = carry_->tangent;
    options.start_point = carry_->point;
    options.start_curvature = carry_->curvature;
  }
  const double tol = smoothing_tolerance(run_.front());
  std::optional<PolylineFit> fit = fit_polyline(*vertices, t0, t1, tol, options);
  if (!fit) return std::nullopt;
  Fitted f{std::make_shared<SpanPolynomialCurve>(fit->curve), std::move(fit->vertex_u), vertices, tol};
  return f;
}

// Lines from..to (inclusive) of the run as pieces of the fitted curve.
void LineSmoother::emit_pieces(const Fitted& f, std::size_t from, std::size_t to, std::vector<Move>& out) {
  const auto breakpoints = std::make_shared<const std::vector<double>>(f.curve->breakpoints());
  const std::size_t offset = carry_ ? 0 : 1;  // line i runs over vertex_u[i - offset] .. [i - offset + 1]
  for (std::size_t i = from; i <= to; ++i) {
    Move m = std::move(run_[i]);
    const std::size_t k = i - offset;
    m.curve = std::make_shared<CurvePiece>(f.curve, f.vertex_u[k], f.vertex_u[k + 1], breakpoints);
    m.length_mm = length(*m.curve);
    m.lines = ProgrammedLines{f.vertices, k, f.tolerance_mm};
    out.push_back(std::move(m));
  }
}

void LineSmoother::as_programmed(std::vector<Move>& out) {
  std::size_t from = 0;
  if (carry_ && !run_.empty()) {
    // The curve before ended at carry_->point, within the tolerance of this first line's start:
    // the line runs from there (within the tolerance of the programmed line all along, a corner
    // for the blender) and the others as programmed.
    Move m = std::move(run_.front());
    const Vec3 start = line_of(m).start(), end = line_of(m).end();
    m.curve = std::make_shared<LineSegment>(carry_->point, end);
    m.length_mm = (end - carry_->point).norm();
    auto programmed = std::make_shared<std::vector<Vec3>>(std::vector<Vec3>{start, end});
    m.lines = ProgrammedLines{programmed, 0, carry_->tolerance_mm};
    out.push_back(std::move(m));
    from = 1;
  }
  for (std::size_t i = from; i < run_.size(); ++i) out.push_back(std::move(run_[i]));
  end_run();
}

void LineSmoother::end_run() {
  run_.clear();
  carry_.reset();
  beyond_mm_ = 0.0;
}

bool LineSmoother::straight() const {
  for (std::size_t i = 1; i < run_.size(); ++i) {
    const auto &a = line_of(run_[i - 1]), &b = line_of(run_[i]);
    const Vec3 ta = (a.end() - a.start()) / line_length(a), tb = (b.end() - b.start()) / line_length(b);
    if ((tb - ta).cwiseAbs().maxCoeff() > tolerances::plan_junction_smooth) return false;
  }
  return true;
}

std::optional<LineSmoother::Fitted> LineSmoother::fit_or_hand_on(std::vector<Move>& out) {
  if (straight()) {
    as_programmed(out);  // every junction already smooth for the planner: nothing to gain
    return std::nullopt;
  }
  std::optional<Fitted> f = fit_run();
  if (!f) split(out);
  return f;
}

void LineSmoother::flush(std::vector<Move>& out) {
  if (const std::optional<Fitted> f = fit_or_hand_on(out)) emit_whole(*f, out);
}

void LineSmoother::split(std::vector<Move>& out) {
  // The fit of the whole run failed somewhere: the halves are fitted apart (a programmed corner
  // between them, the last line of the first and the first of the second staying lines), and so on
  // down to runs too short to smooth, so that one stretch the fit cannot keep within the tolerance
  // leaves only itself as programmed.
  const std::size_t n = run_.size();
  if (n < 2 * tolerances::smooth_min_lines) {
    as_programmed(out);
    return;
  }
  std::vector<Move> second(std::make_move_iterator(run_.begin() + static_cast<std::ptrdiff_t>(n / 2)),
                           std::make_move_iterator(run_.end()));
  run_.resize(n / 2);
  flush(out);  // the first half (continuing a cut run's curve, if this run does)
  run_ = std::move(second);
  flush(out);  // the second half, a fresh run
}

void LineSmoother::emit_whole(const Fitted& f, std::vector<Move>& out) {
  const std::size_t n = run_.size();
  if (!carry_) out.push_back(std::move(run_.front()));  // a fresh run's first line stays a line
  emit_pieces(f, carry_ ? 0 : 1, n - 2, out);
  out.push_back(std::move(run_.back()));               // its last line stays a line
  end_run();
}

void LineSmoother::cut(std::vector<Move>& out) {
  // The run is fitted with the lines beyond the cut (the overlap), so that where it is cut the
  // curve bends as the lines do; the lines up to the cut are handed on as its pieces, the rest
  // start the next run, which continues the curve from the cut with its point, tangent and
  // curvature (curvature-continuous: the chains carry the speed through).
  const std::optional<Fitted> f = fit_or_hand_on(out);
  if (!f) return;
  const std::size_t last = tolerances::smooth_max_run_lines - 1;  // the last line handed on
  const std::size_t k_end = last + 1 - (carry_ ? 0 : 1);  // its end: vertex_u[k_end]
  const Derivatives d = f->curve->derivatives_left(f->vertex_u[k_end], 2);
  const Vec3 point = d[0], programmed = line_of(run_[last]).end();
  const double speed2 = d[1].squaredNorm();
  // The next run's first line starts at the programmed vertex: the curve's point there must be
  // within the tolerance's fitting share of it (so that, should the next fit fail, that line run
  // from the curve's point stays within the tolerance), else this run ends as a whole here.
  if (!(speed2 > 0.0) ||
      !((point - programmed).norm() <= tolerances::smooth_tolerance_share * f->tolerance_mm)) {
    emit_whole(*f, out);
    return;
  }
  if (!carry_) out.push_back(std::move(run_.front()));
  emit_pieces(*f, carry_ ? 0 : 1, last, out);
  const Vec3 tangent = unit_tangent(d), curvature = curvature_vector(d);
  run_.erase(run_.begin(), run_.begin() + static_cast<std::ptrdiff_t>(last + 1));
  beyond_mm_ = 0.0;  // (fewer lines left than the window holds)
  carry_ = Carry{point, tangent, curvature, f->tolerance_mm};
}

}  // namespace kontur::program
