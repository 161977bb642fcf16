#pragma once
// A smooth curve through a polyline within a tolerance: what the planner's smoothing of dense G01
// (program/line_smoother.hpp) runs instead of the programmed lines, and what `kontur compress`
// will write.
//
// The curve is a cubic B-spline parametrised by the polyline's arc length [mm], with a knot at
// every inner vertex (so each line of the polyline has its own span), starting at the first vertex
// and ending at the last one, tangent to given directions there and with zero curvature at both
// ends (it joins the lines around it smoothly). Its control points minimise
//   sum_k w_k |C(u_k) - D_k|^2 + l^4 int |C''|^2 du + l^6 int |C'''|^2 du
// over points D_k on every line (its start and its quarters), w_k the length each stands for: a
// smoothing spline whose smoothing length l starts long (tolerances::smooth_fit_length_tolerances
// times the tolerance) and is shortened where the curve strays: every line whose span comes
// farther than the tolerance from the polyline, or whose vertex is farther from the curve, has the
// weights of its points and its neighbours' raised (by how far it strays, up to
// tolerances::smooth_fit_weight_step; with few knots by that step), and the
// fit is solved again (a banded system), at most tolerances::smooth_fit_iterations times. With few
// knots (PolylineFitOptions) a span covers several lines, and knots are added where it strays.
#include <kontur/geometry/nurbs.hpp>
#include <optional>
#include <vector>

namespace kontur {

struct PolylineFit {
  NurbsCurve curve;  ///< cubic B-spline, u = arc length of the polyline from its first vertex [mm]
  std::vector<double>
      vertex_u;  ///< parameter of each vertex (its arc length): line i is the span [vertex_u[i], vertex_u[i+1]]
  double max_deviation_mm =
      0.0;             ///< largest distance of the sampled curve from the polyline, and of a vertex from the curve [mm]
  int iterations = 0;  ///< fits solved
};

/// How the fit places its knots.
struct PolylineFitOptions {
  /// false: a knot at every vertex, each line its own span (the planner's smoothing: a move per
  /// programmed line). true: as few knots as keep the tolerance (`kontur compress`: a control point
  /// per block written): first tolerances::compress_spline_initial_spans spans (knots at evenly
  /// spaced vertices), then one more at the middle vertex of every span that strays, fitted again,
  /// at most tolerances::compress_spline_knot_rounds times; the weights are raised as above where
  /// a straying span has no vertex left inside.
  bool few_knots = false;
  /// With few knots: give up (empty result) as soon as the fit would need more control points than
  /// this (0: no limit). A caller that writes the curve only if it is shorter than the lines says so.
  std::size_t max_control_points = 0;
  /// The dense fit only: the curve starts here [mm] instead of at the first vertex (a point
  /// within the tolerance of the first line: the end of the curve before, where a long run is
  /// continued), with the curvature vector `start_curvature` [1/mm] (across the start tangent)
  /// instead of zero, so that it continues that curve curvature-continuously. The deviation is
  /// still measured from the programmed polyline.
  std::optional<Vec3> start_point;
  Vec3 start_curvature = Vec3::Zero();
};

/// The fit of `vertices` (at least 5: four lines or more, none shorter than 1e-9 of the whole)
/// within `tolerance_mm` > 0, starting along `start_tangent` and ending along `end_tangent` (unit
/// vectors). Empty if no fit within the tolerance was found (the caller keeps the lines).
[[nodiscard]] std::optional<PolylineFit> fit_polyline(const std::vector<Vec3>& vertices, const Vec3& start_tangent,
                                                      const Vec3& end_tangent, double tolerance_mm,
                                                      const PolylineFitOptions& options = {});

}  // namespace kontur
