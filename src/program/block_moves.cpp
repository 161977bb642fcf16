#include <fmt/format.h>

#include <kontur/error.hpp>
#include <kontur/geometry/length.hpp>
#include <kontur/geometry/span_polynomial.hpp>
#include <kontur/program/block_moves.hpp>
#include <kontur/tolerances.hpp>
#include <algorithm>
#include <memory>
#include <cmath>
#include <limits>
#include <type_traits>
#include <variant>

namespace kontur::program {
namespace {

// Whether the span polynomials of `nurbs` are as good as the NURBS: their largest distance from
// it at the ends and 8 points of every span is within tolerances::span_polynomial_max_error_mm and
// within span_polynomial_max_error_ulps of the largest coordinate. The power basis of a high
// degree with extreme weights loses digits: a degree-9 span with weights 100 and 0.01 ended 4e-8 mm
// from its last control point; a degree-1 span with weights 100 and 0.0118 was evaluated with a
// noise of 8.6e-12 mm (4 800 ulp), which showed as jerk 1.2 times the limit at T = 169 us.
bool span_polynomials_exact(const NurbsCurve& nurbs, const SpanPolynomialCurve& poly) {
  double worst_mm = 0.0, scale_mm = 0.0;
  for (const SpanPolynomial& s : poly.spans())
    for (int k = 0; k <= 8; ++k) {
      const double u = k == 8 ? s.u_end : s.u_start + (s.u_end - s.u_start) * k / 8.0;
      const Vec3 a = k == 8 ? nurbs.derivatives_left(u, 0)[0] : nurbs.point(u);
      const Vec3 b = k == 8 ? poly.derivatives_left(u, 0)[0] : poly.point(u);
      worst_mm = std::max(worst_mm, (a - b).norm());
      scale_mm = std::max(scale_mm, a.cwiseAbs().maxCoeff());
    }
  const double ulp_mm = std::nextafter(scale_mm, std::numeric_limits<double>::infinity()) - scale_mm;
  return worst_mm <= tolerances::span_polynomial_max_error_mm &&
         worst_mm <= tolerances::span_polynomial_max_error_ulps * ulp_mm;
}

// The block's curve as a shared curve for the planner (NURBS as span polynomials: faster, unless
// they lose digits: span_polynomials_exact; then the NURBS itself).
std::shared_ptr<const Curve> shared_curve(const gcode::Block& b) {
  return std::visit(
      [](const auto& g) -> std::shared_ptr<const Curve> {
        using G = std::decay_t<decltype(g)>;
        if constexpr (std::is_same_v<G, std::monostate>) {
          return nullptr;
        } else if constexpr (std::is_same_v<G, NurbsCurve>) {
          auto poly = std::make_shared<SpanPolynomialCurve>(g);
          if (!span_polynomials_exact(g, *poly)) return std::make_shared<NurbsCurve>(g);
          return poly;
        } else {
          return std::make_shared<G>(g);
        }
      },
      b.geometry);
}

// Does the curve run along linear axis i (0 X, 1 Y, 2 Z): its ends apart along it, or its unit
// tangent's component above tolerances::missing_axis_tangent (the planner's rule for an axis the
// machine lacks, plan::missing_axis_moved) at the ends or at any of 64 points of a span?
bool curve_moves_along(const Curve& c, int i) {
  const auto e = static_cast<Eigen::Index>(i);
  if (c.point(c.u_min())[e] != c.point(c.u_max())[e]) return true;
  const std::vector<double> bp = c.breakpoints();
  constexpr int samples = 64;
  for (std::size_t k = 0; k + 1 < bp.size(); ++k)
    for (int q = 0; q <= samples; ++q) {
      const Vec3 d = c.derivatives(bp[k] + (bp[k + 1] - bp[k]) * q / samples, 1)[1];
      const double n = d.norm();
      if (n > 0.0 && std::abs(d[e]) > tolerances::missing_axis_tangent * n) return true;
    }
  return false;
}

}  // namespace

double corner_tolerance(const gcode::Block& b, const Machine& machine) {
  if (b.modal.path_control != gcode::PathControl::blend) return 0.0;
  return b.modal.blend_tolerance_mm > 0.0 ? b.modal.blend_tolerance_mm : machine.path_tolerance_mm;
}

Move move_of(const gcode::Block& b, const Machine& machine) {
  Move m;
  m.curve = shared_curve(b);
  m.source_line = b.location.line;
  m.type = gcode::to_string(b.type);
  if (!m.curve) return m;  // no motion (a dwell)
  // An axis the machine lacks cannot move: an extra axis whose end differs from its start, or a
  // linear axis the path runs along (LinuxCNC does not even read the letter of an axis its INI's
  // COORDINATES leave out; the planner's speed cap along it would be zero).
  const auto refuse = [&](char letter, double to) {
    std::string axes;
    for (const AxisLimits& a : machine.axes) {
      if (!axes.empty()) axes += ' ';
      axes += a.name;
    }
    throw InputError("axis-missing",
                     fmt::format("{}:{}: the block moves {} (to {}), but the machine {} ({}) has no {} axis (its axes: {})",
                                 b.location.file ? *b.location.file : std::string("?"), b.location.line, letter, to,
                                 machine.name, machine.source, letter, axes));
  };
  for (int e = 0; e < extra_axis_count; ++e) {
    const auto i = static_cast<std::size_t>(e);
    if (b.extra_start[i] == b.extra_end[i] || machine.axis(extra_axis_letters[e]) != nullptr) continue;
    refuse(extra_axis_letters[e], b.extra_end[i]);
  }
  for (int i = 0; i < 3; ++i)
    if (const char letter = "XYZ"[i]; machine.axis(letter) == nullptr && curve_moves_along(*m.curve, i))
      refuse(letter, b.end[i]);
  // The length, integrated once (lines and arcs: exact; NURBS and conics: the same quadrature of
  // the same curve as the block's length_mm, of the curve the planner runs).
  const bool exact = std::holds_alternative<LineSegment>(b.geometry) || std::holds_alternative<HelixArc>(b.geometry);
  const double tool_len = exact ? *b.length_mm() : length(*m.curve);  // [mm]
  // The path the feed applies to: the tool path, else U V W, else A B C (LinuxCNC's rule).
  m.extra_start = b.extra_start;
  m.extra_end = b.extra_end;
  const double len = path_length(tool_len, b.extra_start, b.extra_end, m.tool_still);  // [mm] or [deg]
  if (m.tool_still) m.curve = std::make_shared<LineSegment>(b.start, b.start);  // the tool point stands
  double feed = b.type == gcode::BlockType::rapid ? machine.rapid_feed_mm_s : b.feed.value / 60.0;  // [mm/s]
  // The reader scales F by the program's units; a move of A B C alone runs at F [deg/min].
  const bool rotary_only = m.tool_still && b.extra_start[3] == b.extra_end[3] && b.extra_start[4] == b.extra_end[4] &&
                           b.extra_start[5] == b.extra_end[5];
  if (rotary_only && b.type != gcode::BlockType::rapid && b.modal.units == gcode::Units::inch) feed /= 25.4;
  if (b.feed.mode == gcode::FeedMode::inverse_time && b.type != gcode::BlockType::rapid)
    // (a block of no length takes no time, as LinuxCNC drops it: any feed > 0 serves; issue 20, 15)
    feed = b.feed.duration_s() > 0.0 && len > 0.0 ? len / b.feed.duration_s() : machine.max_feed_mm_s;
  if (!(feed > 0.0))
    throw InputError("feed-missing",
                     fmt::format("{}:{}: a feed move with no feed: program an F word before it",
                                 b.location.file ? *b.location.file : std::string("?"), b.location.line));
  m.feed_mm_s = feed;
  m.exact_stop = b.modal.path_control != gcode::PathControl::blend;
  m.corner_tolerance_mm = corner_tolerance(b, machine);
  if (!m.exact_stop) m.naive_cam_tolerance_mm = b.modal.naive_cam_tolerance_mm;
  m.length_mm = len;
  return m;
}

}  // namespace kontur::program
