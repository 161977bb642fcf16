#include <algorithm>
#include <cstring>
#include <kontur/geometry/curve_piece.hpp>
#include <kontur/geometry/length.hpp>
#include <kontur/geometry/line_segment.hpp>
#include <kontur/geometry/polyline_fit.hpp>
#include <kontur/geometry/span_polynomial.hpp>
#include <kontur/program/line_smoother.hpp>
#include <kontur/tolerances.hpp>
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

double line_length(const LineSegment& l) { return (l.end() - l.start()).norm(); }

}  // namespace

bool LineSmoother::continues(const Move& move) const {
  const LineSegment* next = feed_line(move);
  if (next == nullptr || run_.size() >= tolerances::smooth_max_run_lines) return false;
  const Move& last_move = run_.back();
  const auto& last = static_cast<const LineSegment&>(*last_move.curve);
  const double tol = smoothing_tolerance(last_move);
  if (!(tol > 0.0) || tol != smoothing_tolerance(run_.front())) return false;
  const double la = line_length(last), lb = line_length(*next);
  if (la < tolerances::blend_min_line_mm || lb < tolerances::blend_min_line_mm) return false;
  // the line before becomes an inner line of the run (the first line may be of any length)
  if (run_.size() >= 2 && la > tolerances::smooth_max_line_tolerances * tol) return false;
  if ((next->start() - last.end()).norm() > 1e-12 * std::max(1.0, last.end().norm())) return false;
  const Vec3 t1 = (last.end() - last.start()) / la, t2 = (next->end() - next->start()) / lb;
  return t1.dot(t2) >= tolerances::smooth_max_turn_cos;
}

void LineSmoother::push(const Move& move, std::vector<Move>& out) {
  if (!enabled_) {
    out.push_back(move);
    return;
  }
  if (!run_.empty() && !continues(move)) flush(out);
  if (feed_line(move) != nullptr)
    run_.push_back(move);
  else
    out.push_back(move);
}

void LineSmoother::flush(std::vector<Move>& out) {
  const std::size_t n = run_.size();
  if (n < tolerances::smooth_min_lines) {
    for (Move& m : run_) out.push_back(std::move(m));
    run_.clear();
    return;
  }
  // The curve runs from the end of the first line to the start of the last one.
  auto vertices = std::make_shared<std::vector<Vec3>>();
  vertices->reserve(n - 1);
  for (std::size_t i = 1; i < n; ++i) vertices->push_back(static_cast<const LineSegment&>(*run_[i].curve).start());
  const auto& first = static_cast<const LineSegment&>(*run_.front().curve);
  const auto& last = static_cast<const LineSegment&>(*run_.back().curve);
  const Vec3 t0 = (first.end() - first.start()).normalized(), t1 = (last.end() - last.start()).normalized();
  const double tol = smoothing_tolerance(run_.front());
  const std::optional<PolylineFit> fit = fit_polyline(*vertices, t0, t1, tol);
  if (!fit) {
    for (Move& m : run_) out.push_back(std::move(m));
    run_.clear();
    return;
  }
  const std::shared_ptr<const Curve> curve = std::make_shared<SpanPolynomialCurve>(fit->curve);
  const std::shared_ptr<const std::vector<Vec3>> shared = vertices;
  const auto breakpoints = std::make_shared<const std::vector<double>>(curve->breakpoints());
  out.push_back(std::move(run_.front()));
  for (std::size_t i = 1; i + 1 < n; ++i) {
    Move m = std::move(run_[i]);
    m.curve = std::make_shared<CurvePiece>(curve, fit->vertex_u[i - 1], fit->vertex_u[i], breakpoints);
    m.length_mm = length(*m.curve);
    m.lines = ProgrammedLines{shared, i - 1, tol};
    out.push_back(std::move(m));
  }
  out.push_back(std::move(run_.back()));
  run_.clear();
}

}  // namespace kontur::program
