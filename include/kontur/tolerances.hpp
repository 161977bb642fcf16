#pragma once
#include <cstddef>
#include <cstdint>
// Every numerical tolerance of Kontur, in one place, with what it means and how it relates to
// the others. Lengths are in [mm] unless stated; "relative" means relative to the quantity's
// own scale (a curve's extent, a length, a parameter range).

namespace kontur::tolerances {

// ---- geometry of curves
/// Maximum supported NURBS degree (order 10).
inline constexpr int max_degree = 9;
/// A NURBS move is planned on its span polynomials (fast) when they are within this distance of
/// the NURBS at the ends and 8 points of every span [mm], and within this many ulp of its largest
/// coordinate; otherwise on the NURBS itself. (The shared NURBS programs lose at most 31 ulp; the
/// polynomials of extreme weights, hundreds to thousands, and that noise shows as jerk.)
inline constexpr double span_polynomial_max_error_mm = 1e-11;
inline constexpr double span_polynomial_max_error_ulps = 64.0;
/// Largest derivative order evaluated by Curve::derivatives (point, first, second, third).
inline constexpr int max_derivative = 3;
/// Two knots closer than this, relative to the parameter range, count as equal when the end
/// multiplicities of a clamped knot vector are checked.
inline constexpr double knot_equal_relative = 1e-12;

// ---- extra axes (A B C U V W)
/// A move whose tool path (X Y Z) is at most this long [mm] while an extra axis moves runs as a
/// move of the extra axes alone: the feed applies to U V W's distance, else to A B C's angle
/// (LinuxCNC's rule), and the tool point stands at the move's start.
inline constexpr double extra_axes_tool_still_mm = 1e-9;

// ---- curve length
/// Default relative accuracy of Kontur's adaptive Gauss-Kronrod length.
inline constexpr double length_relative = 1e-13;
/// Smallest relative accuracy a length may be asked for: a panel's error estimate never goes
/// below 50 machine epsilons of its value (rounding of the sum), so a smaller request could
/// never be met. Requests below it are raised to it.
inline constexpr double min_length_relative = 2e-14;
/// Default relative accuracy asked of the Simpson-Runge method (seed 000).
inline constexpr double simpson_relative = 1e-10;
/// Largest number of interval halvings of the Simpson-Runge method (2^24 intervals).
inline constexpr int simpson_max_halvings = 24;
/// The adaptive Gauss-Kronrod integration takes a panel's error for the integrand's rounding noise
/// (and stops bisecting it) where bisection does not reduce it, it is below the first share of the
/// panel's |C'| scale, and both halves carry at least the second share of the larger half's error:
/// noise is spread over the panel, an unresolved feature sits in one half. (A NURBS ending with
/// weights 100, 100, 0.59, degree 9, has a spike of |C'| in the last 1e-3 of its span that the
/// panels did not resolve for a few levels; taken for noise, its length came out 1.4e-9 mm long,
/// the tool reached the curve's end early and stood there: jerk 3.4 times the limit.)
inline constexpr double gauss_kronrod_noise_relative = 1e-8;
inline constexpr double gauss_kronrod_noise_spread = 0.125;
/// Deepest bisection of an adaptive Gauss-Kronrod interval.
inline constexpr int gauss_kronrod_max_depth = 40;
/// Most evaluations of |C'| spent on one piece between breakpoints (the depth alone allows 2^40
/// panels where the integrand is noise everywhere, e.g. a degenerate rational span a micrometre
/// long): past it the remaining panels are accepted as they are, not converged. Cusps and spikes
/// of the shared programs take at most a few tens of thousands.
inline constexpr long gauss_kronrod_max_piece_evaluations = 2'000'000;
/// Relative accuracy of the inverse u(s) of the arc-length table.
inline constexpr double inverse_length_relative = 1e-13;
/// Largest number of Newton iterations of u(s); each falls back to bisection when it leaves the
/// bracket, so the iteration always ends.
inline constexpr int inverse_length_max_iterations = 60;
/// ArcLengthTable::u_after (one servo cycle's step) accepts a residual of its step's length
/// below this, relative to the step (a few ulps above the rounding of the step's integral).
inline constexpr double inverse_step_relative = 1e-14;
/// ArcLengthTable::u_after (one servo cycle's step): the 7-point Gauss length of the step is
/// accepted when its degree-7 companion (the same inner nodes and the step's ends) agrees with it
/// to this, relative; the Gauss value's own error (of order h^14 against h^8) is then of order
/// (1e-9)^(14/8) ~ 2e-16 of the step.
/// Otherwise the nested rules from 15 points on decide.
inline constexpr double step_gauss_agreement = 1e-9;
/// u_after stops after a Newton step from a residual below this, relative to the step: Newton's
/// error is then of order 1e-14 of the step times the relative change of |C'| over it.
inline constexpr double inverse_step_newton_stop = 1e-7;
/// The same for a Newton step with its second-order term (error of order (1e-5)^3 of the step).
inline constexpr double inverse_step_second_order_stop = 1e-5;
/// The sampler moves a setpoint along the tangent by the arc-length error of its parameter
/// (trajectory::Sampler::point_at_s) where that error exceeds this [mm]: below it the parameter's
/// rounding cannot show (1e-14 mm is 1e-5 mm/s^3 of jerk at T = 1 ms); above it, near a NURBS
/// weight of 100, one ulp of u moved the point 1e-10 mm and showed as jerk 1.2 times the limit.
inline constexpr double sample_arc_error_correct_mm = 1e-14;

// ---- forward differences (seed 002)
/// Drift of the forward-difference stepper after 10^6 steps, relative to the curve's extent,
/// that the tests and the documentation guarantee.
inline constexpr double forward_difference_drift_relative = 1e-9;


// ---- constraints of a path on a machine (plan/constraints.hpp), for both planners
/// A unit tangent component above this moves the path along that axis: on a machine without the
/// axis the path cannot be run (speed cap zero; the time-optimal reference refuses it). A smaller
/// component is rounding of a path that does not move the axis (over a 1000 mm move, 1e-9 mm).
inline constexpr double missing_axis_tangent = 1e-12;

// ---- time-optimal reference (plan/time_optimal.hpp)
/// Two unit tangents that differ by more than this (Euclidean norm) make a corner: a tangent
/// discontinuity that an acceleration-limited motion can only pass at rest (or, by the servo-period
/// rule, within one period's velocity jump). The online planner's junction rule uses the same 1e-9.
inline constexpr double time_optimal_corner_tangent = 1e-9;
/// A tangent component below this counts as zero in the axis constraints |t_i u + k_i x| <= A_i
/// (the constraint is then |k_i| x <= A_i; the neglected term t_i u is below 1e-12 A).
inline constexpr double time_optimal_tangent_zero = 1e-12;
/// Shortest grid interval the reference's refinement at sharp turns makes [mm] (1 nm), and the
/// deepest bisection of one interval: a near-cusp of a spline (radius 0.2 um in
/// G6_Curva_Delfino) is resolved to this.
inline constexpr double time_optimal_min_step_mm = 1e-6;
inline constexpr int time_optimal_max_refinement = 40;
/// Relative change of the total time of the reference between a grid and the grid of half its
/// step that the tests and the documentation guarantee (the discretisation error).
inline constexpr double time_optimal_grid_relative = 1e-4;

// ---- G-code programs (kontur/gcode); all in [mm] after unit conversion (1 in = 25.4 mm)
/// Arc radius check of a control (LinuxCNC's): the distances from the centre to the start and to
/// the end of a G2/G3 arc (or |R| and the I J K radius when both are given) may differ by the
/// absolute tolerance (gcode_arc_radius_absolute_mm in a mm program, gcode_arc_radius_absolute_inch
/// in an inch program), or by up to gcode_arc_radius_relative_cap times that where the difference
/// is within gcode_arc_radius_relative of the radius. The curve uses the start radius and its
/// radius changes linearly with the angle to the end radius (a slight spiral, as LinuxCNC does),
/// so that the arc ends exactly at the programmed end point; above gcode_arc_radius_warning_mm the
/// reader warns.
inline constexpr double gcode_arc_radius_absolute_mm = 0.0283;    // 2 * 0.01 * sqrt(2) [mm]
inline constexpr double gcode_arc_radius_absolute_inch = 0.00283; // 2 * 0.001 * sqrt(2) [in]
/// Relative part of the arc radius check (0.1 % of the radius).
inline constexpr double gcode_arc_radius_relative = 1e-3;
inline constexpr double gcode_arc_radius_relative_cap = 100.0;
/// A radius difference above this is read with a warning [mm].
inline constexpr double gcode_arc_radius_warning_mm = 0.005;
/// (An R-form arc whose chord exceeds 2 |R| by at most that tolerance is taken as a half circle.)
/// Two points closer than this are the same point: the end of a full circle, the first control point
/// of a G06.2 / G6.2 curve and the current position. (3-D circles and conics use the
/// arc_coincident_relative and arc_collinear_relative tests of circle/conic_through_points.)
inline constexpr double gcode_same_point_mm = 1e-4;
/// The five points of a CONIC block lie in one plane when the fourth and fifth are within this
/// distance of the plane of the first three [mm] (ConicOptions::plane_tolerance_mm): programs round
/// coordinates to 1e-3 mm.
inline constexpr double gcode_conic_plane_mm = 1e-3;
/// Retract distance between pecks of G73 and clearance above the hole bottom of G83 (as LinuxCNC:
/// 0.010 in), [mm].
inline constexpr double gcode_peck_clearance_mm = 0.254;
/// Longest accepted program line [characters]; longer lines are an error, so memory per line is bounded.
inline constexpr int gcode_max_line_length = 4096;
/// Largest number of LinuxCNC P turns of a G2/G3 arc (more is an error, not a hang).
inline constexpr int gcode_max_arc_turns = 10000;
/// Largest number of repeats L of a canned cycle.
inline constexpr int gcode_max_cycle_repeats = 10000;
/// Largest number of control points of one spline block (G06.2, G5.2): bounds the memory of the reader.
inline constexpr int gcode_max_spline_points = 100000;
/// Largest number of moves one canned-cycle block may expand into (repeats L times pecks).
inline constexpr int gcode_max_cycle_moves = 100000;
/// Largest coordinate, offset, radius or distance a program may reach [mm] (1 km): beyond it a
/// program is in error, which keeps every length and point finite.
inline constexpr double gcode_max_coordinate_mm = 1e6;
/// Largest feed F [mm/min or 1/min], dwell [s] and NURBS weight or knot magnitude a program may give.
inline constexpr double gcode_max_value = 1e9;
/// Default largest number of O-word loop iterations and subroutine calls of a whole program
/// (ReaderOptions::max_loop_iterations): more is taken as an endless loop.
inline constexpr long gcode_max_loop_iterations = 10000000;
/// Largest subroutine file read whole into memory (a LinuxCNC `o<name> call` of `name.ngc`) [bytes].
inline constexpr std::uintmax_t gcode_max_subroutine_file_bytes = 64u << 20;
/// Largest memory the blocks of a validated program may take to be kept for the second pass
/// (gcode::validate_program) [bytes]: a program within it is read once; a longer one is read again,
/// so that the memory stays bounded whatever the program's length.
inline constexpr std::size_t gcode_kept_blocks_bytes = 32u << 20;
/// Lines at the beginning of a program looked at to tell its dialect (gcode::detect_dialect): marks
/// such as a program number or a Sinumerik header come first.
inline constexpr int gcode_dialect_detection_lines = 400;
/// Largest number of pecks of one G73 / G83 hole (Q too small for the depth is an error).
inline constexpr int gcode_max_pecks = 10000;

// ---- cutter radius compensation (G41 / G42, gcode/cutter_compensation)
/// Two offset points closer than this [mm] are one (tangent moves: no corner arc, no trimming); a
/// move shorter in the plane than this is a move along the plane's normal (it keeps the offset).
inline constexpr double cutter_comp_same_point_mm = 1e-9;
/// Smallest radius [mm] of an offset arc: an arc whose offset radius is not larger is a gouge.
inline constexpr double cutter_comp_min_radius_mm = 1e-9;

// ---- arcs and conics through points (methods.md sections 4 and 5)
// Every test below is relative to the extent of the given points (their largest pairwise
// distance [mm]), so that the same input scaled by any factor gives the same verdict.
/// Two given points closer than this times the extent are coincident.
inline constexpr double arc_coincident_relative = 1e-9;
/// Three points are collinear when the smallest height of their triangle is below this times its
/// longest side. For three points |n| = |(r2 - r1) x (r3 - r1)| = 2 area and det G = |n|^2 (seed
/// (2.12)-(2.22)), so the test is |n| < arc_collinear_relative * longest^2: relative, never == 0.
inline constexpr double arc_collinear_relative = 1e-9;
/// Default largest distance of r4 and r5 from the plane of r1, r2, r3, times the extent. The user
/// may give a looser absolute tolerance (part programs round coordinates to 1e-3 or 1e-4 mm).
inline constexpr double conic_coplanar_relative = 1e-9;
/// When e^2 (= 1 - lambda_axis / lambda_transverse) or |1 - e^2| of the fitted conic is below
/// this, the best circle or parabola through the points is fitted too ...
inline constexpr double conic_snap_candidate_relative = 1e-6;
/// ... and the conic is a circle or a parabola when that curve passes within this times the
/// extent of the five points (rounding of exact data gives about 1e-15).
inline constexpr double conic_snap_fit_relative = 1e-11;
/// A conic is degenerate (a pair of lines or a point) when the discriminant that gives its
/// vertices, relative to its terms, is below this.
inline constexpr double conic_degenerate_relative = 1e-12;
/// Relative accuracy of the length of a conic arc (adaptive Gauss-Kronrod, asked 1e-13) that the
/// tests and the documentation guarantee.
inline constexpr double conic_length_relative = 1e-12;
/// The last step of the angular modes reaches the end point to this, relative to the extent.
inline constexpr double arc_end_point_relative = 1e-12;

// ---- motion planner: how each axis's budget is shared (kontur/plan)
// An axis's acceleration along a curve is t_i s'' + K_i s'^2 and its jerk
// t_i s''' + 3 K_i s' s'' + K'_i s'^3 (t the unit tangent, K = kappa n the curvature vector and
// K' its derivative along the path, all per axis); at a junction that is not smooth, setpoints a
// period apart see a direction jump as a velocity jump and a curvature jump as an acceleration jump.
// Each term gets a share of the axis's jerk limit; the shares of any one place add up to at most 1.
/// Share of an axis's jerk for the cross term 3 K_i v a (caps the path acceleration on curves).
inline constexpr double plan_cross_jerk_share = 0.2;
/// The shares of an axis's jerk the curvature-change term K'_i v^3 (it caps the speed on curves)
/// may take: a stretch chooses the one with the shortest estimated time, where the path keeps at
/// least plan_path_jerk_share_min of the axis's jerk (on the smoothed random_lines the curvature
/// change caps the speed, not the centripetal term). The first is the share where a junction's
/// jerk share leaves no room for more, and the one the planner's estimates take
/// (plan_curvature_rate_jerk_share); the corner blender's estimate of a blend takes the chain's
/// largest (plan::curve_speed_cap). Above plan_chain_curvature_rate_share_max only where the choice
/// weighs the speed changes at the piece's ends, or at a low of its chain's caps, which the motion
/// passes at its cap (MotionPlanner::raise_chain_lows): elsewhere inside a chain the length alone
/// decides, which would always take the largest and leave the path 0.1 of the jerk (0.7 inside
/// chains: performance/3D_Chips on XYZ.ini 1.5 % slower, random_lines 2.1 %).
inline constexpr double plan_curvature_rate_jerk_shares[] = {0.2, 0.4, 0.6, 0.7};
inline constexpr double plan_chain_curvature_rate_share_max = 0.6;
inline constexpr double plan_curvature_rate_jerk_share = plan_curvature_rate_jerk_shares[0];
inline constexpr double plan_path_jerk_share_min = 0.1;
/// Share of an axis's jerk a junction may use when its direction changes by less than
/// plan_small_corner (per axis, |t2 - t1|) or only its curvature jumps: its speed matters, and the
/// moves on both sides plan with the rest.
inline constexpr double plan_smooth_junction_jerk_share = 0.5;
/// ... and the share of a real corner (a near stop anyway, so the moves keep most of their jerk).
inline constexpr double plan_corner_jerk_share = 0.05;
/// A junction's jerk share also holds for the pieces after it that the motion can reach within
/// this many servo periods (passing each at its cap at the fastest): the setpoints' third
/// differences reach that far, and a piece shorter than that beside the junction (a line of 0.5 um
/// ahead of a smoothed run) would otherwise leave the next pieces their whole jerk right at it
/// (vcarve.ngc on XYZ_medium.ini: X at 1.005 times its jerk).
inline constexpr double plan_junction_share_reach_periods = 3.0;
/// A junction direction change (per axis, |t2 - t1|) below which a corner counts as small.
inline constexpr double plan_small_corner = 0.05;
/// Tangents or curvature vectors that agree to this (per axis; [1] and [1/mm]) make a smooth junction.
inline constexpr double plan_junction_smooth = 1e-9;
/// Share of an axis's acceleration the velocity jump of a corner (v |t2 - t1|_i / T, as setpoints a
/// period apart see it) may take in the online planner's junction limit; the centripetal
/// acceleration of the curves on either side of the corner keeps within the rest there (a piece's
/// cap may take up to 0.97 of it: plan_centripetal_shares).
inline constexpr double plan_corner_acceleration_share = 0.1;
/// ... reduced where the moves beside the corner can build up their acceleration within a period:
/// share = clamp(this - J T / A, 0, plan_corner_acceleration_share) per axis, so none once J T is
/// half of A (a corner is then a stop); unchanged (0.1) up to J T = 0.4 A (LinuxCNC's XYZ.ini: 0.1).
inline constexpr double plan_corner_step_jerk_ramp = 0.5;
/// Fractions of an axis's acceleration the centripetal part may take on a curve; the planner takes
/// the one that gives the shortest time for the piece (the rest is left for the path acceleration).
/// Above plan_chain_centripetal_share_max only where the choice weighs the speed changes at the
/// piece's ends (a corner, a stop or a jump of curvature beside it): inside a chain the length
/// alone decides, which would always take the largest share and leave the chain's profile little
/// acceleration (3D_Chips on XYZ.ini 1.5 % slower with 0.97 there). 0.97 on a circle alone
/// (single_circle, jerk = A / T): 1.671 -> 1.635 s; the reference 1.522 s.
inline constexpr double plan_centripetal_shares[] = {0.5, 0.7, 0.9, 0.97};
inline constexpr double plan_chain_centripetal_share_max = 0.9;
/// A curved piece alone in its chain (an arc between corners) speeds up and brakes with the
/// acceleration its centripetal part leaves at each speed: in bands up to these fractions of its cap
/// (the last its cap), each with the acceleration left at its top (plan/banded_profile.hpp). The
/// staircase lies under the acceleration left at each speed, which falls fastest near the cap:
/// the speed where the time-optimal reference brakes to and leaves a low point is about 0.94 of its
/// own there on performance/3D_Chips (jerk = A / T machine) with 5 bands (0.5, 0.7, 0.85, 0.95, 1).
/// These 9, measured against those 5 with bench/compare_runs.sh on every shared program: XYZ.ini
/// 70 runs faster, 1 slower by 0.03 % (performance/3D_Chips 59.150 -> 58.930 s); jerk = A / T 68
/// faster, none slower; about 7 % more instructions per run (13 bands: 0.1 % faster still, 17 %).
inline constexpr double plan_acceleration_band_tops[] = {0.4, 0.55, 0.7, 0.8, 0.88, 0.93, 0.97, 0.99, 1.0};
/// The look-ahead's braking under speed bands looks for the end speed that takes the longest
/// braking also on a grid of this many intervals (plan/banded_profile.hpp).
inline constexpr int plan_banded_braking_grid = 8;
/// Where that missed it and braking to a junction's speed does not fit, the move brakes to the
/// first of this many steps down from that speed that fits (Lookahead::pop, move_profile).
inline constexpr int plan_banded_braking_fallback_steps = 64;
/// The time a piece is estimated at, to choose its shares: its length at its cap plus a weight of
/// the time a change from rest to the cap takes, half of it for each end of the piece where its
/// chain starts or ends (a stop, a corner, a curvature jump), this for each end inside a chain.
/// Inside a chain the largest cap is taken: the look-ahead and the chain's profile speed up and
/// brake under the pieces' speed bands (more acceleration below the cap), so a high centripetal
/// share costs acceleration only near the cap. Until 2026-12-04 the weight was 0.01 (with both
/// ends weighed alike, 0.01-0.03 gave 3D_Chips 98.2-98.8 s then; 0.5 103.4 s; none 107.1 s, the
/// acceleration at the cap left too small), and on pieces of a few micrometres the change
/// outweighed the length: every piece of circle_small_segments took the smallest share (98 mm/s
/// on its circle, against 132 at the largest). With the bands, on XYZ.ini: 0 gives
/// circle_small_segments 1.816 s, 3D_Chips 91.53 s, random_lines (G20) 14.31 s; 0.001 gave
/// circle_small_segments 2.118 s and 0.01 2.126 s (3D_Chips 0.2 % and 1.6 % slower than 0).
inline constexpr double plan_share_choice_change_weight = 0.0;
/// Samples per span of a curve when its geometry (tangent, curvature, curvature change) is
/// bounded (more where the tangent turns by over 0.2 rad between samples), and the share of each
/// sampled quantity's range its maximum is raised by (a smooth peak between samples turned by
/// 0.2 rad lies about 1 % of the range above them; constant quantities stay exact; an arc
/// without change of radius gets the exact rise of its sinusoids between samples instead:
/// plan::path_geometry).
inline constexpr int plan_samples_per_span = 16;
/// An arc whose radius changes by at most this share of it (the rounding of its end point) is
/// bounded as a circle (plan::path_geometry).
inline constexpr double arc_radius_change_exact = 1e-9;
/// An arc without rise whose radius changes by at most this share of it per radian is a slight
/// spiral: its distance from a point is measured to its point at the point's angle
/// (HelixArc::distance_mm), at most 1 / cos(atan(0.03)) - 1 = 4.5e-4 of it above the true
/// distance (rgh's arcs of 0.23 mm, ends rounded to 0.1 um, change by up to 0.02 per radian).
inline constexpr double arc_slight_spiral_slope = 0.03;
/// Newton's (or bisection) steps toward the nearest point of a spiral's or a helix's turn
/// (HelixArc::distance_mm; a step of 1e-13 mm ends them sooner).
inline constexpr int arc_distance_iterations = 60;
/// nearer_distance (geometry/piece_distance.hpp) leaves the farther piece's distance out only where
/// its lower bound exceeds the nearer's distance by more than this share of (1 mm + |p| + the
/// bound): far beyond the rounding of either, so the result is exactly the smaller distance.
inline constexpr double piece_distance_bound_margin = 1e-9;
/// Parts of a spiral's whole turn searched for the nearest point each (HelixArc::distance_mm).
inline constexpr int arc_distance_spiral_parts = 8;
/// How many (|t_i|, |K_i|) pairs per axis a stretch keeps to bound its acceleration
/// (plan::PathGeometry::pairs): more pairs follow a curve's trade of tangent against curvature
/// more closely (with 16, a 270-degree arc of radius 20 mm keeps 0.92, 0.88 and 0.73 of
/// sqrt(1 - c^2) A at the shares c = 0.5, 0.7, 0.9, against at most 0.58, 0.42 and 0.23 of it with the
/// maxima alone: Constraints.ArcKeepsTheAccelerationItsTangentAndCurvatureLeaveTogether).
inline constexpr int plan_acceleration_pairs = 16;
inline constexpr double plan_sample_margin = 0.05;
/// A point where a curve's parametric speed |C'| is at most this share of its largest over the
/// span is stationary (a cusp, or a degenerate end such as a repeated control point): its
/// tangent and curvature are not sampled (they are rounding noise there), and the path stops
/// there (issue 20, cases 1-4 and 7). The grid on which |C'| is searched for such points.
inline constexpr double plan_stationary_speed_relative = 1e-6;
inline constexpr int plan_stationary_search_samples = 64;
/// Between a stationary point and the next cut, points where |C'| is at most this share of its
/// peak there are not sampled for the speed caps: their curvature is rounding noise (a cusp's
/// computed curvature reached 1e19 / mm within 1e-9 mm of it and the motion crawled for hours).
/// Far below plan_stationary_speed_relative: a large weight makes |C'| that small on a regular,
/// tightly turning stretch, whose curvature must be kept.
inline constexpr double plan_noise_speed_relative = 1e-9;
/// ... and within this many times the distance a stationary point's evaluation wanders 2^-48 ..
/// 2^-40 of the way from it (where the curve cannot have moved but by rounding).
inline constexpr double plan_stationary_noise_factor = 10.0;
/// Around a stationary point the curvature grows without bound (a cusp's is about 1 / sqrt(s)),
/// while the motion stops there: the stretch within this share of what the setpoints can show is
/// left out of the speed caps. The share is of the smallest of a T^2 / 4 and j T^3 / 8 over the
/// axes [mm] (the displacement whose second / third difference over the servo period T reaches the
/// acceleration a / jerk j), times plan_limit_safety: a turn that short moves no setpoint enough to
/// matter (issue 20: a degree-4 spline ending on a repeated point crawled for 9800 s).
inline constexpr double plan_stationary_blind_share = 0.1;
/// A sample of a stretch whose |K| or |dK/ds| is a local maximum above a neighbour's by more than
/// this factor is refined by golden section between its neighbours (a large NURBS weight makes a
/// peak narrower than the samples: issue 20, a jerk 3.1 times the limit).
inline constexpr double plan_peak_refine_ratio = 1.1;
/// The refinement (brent_minimum) stops once the peak's parameter is known to this share of the
/// bracket between the neighbours, or after this many evaluations. A smooth peak costs 11-25
/// evaluations (60 golden sections did before, to 3e-13 of the bracket: the peak's value is the
/// same to rounding); a peak 1e-6 of the bracket wide is found to 1e-8 of its height.
inline constexpr double plan_peak_refine_u = 1e-10;
inline constexpr int plan_peak_refine_evaluations = 100;
/// A sampled peak of |K| [1/mm] or |dK/ds| [1/mm^2] at most this is not refined: it is the rounding
/// noise of a straight stretch (on the 173 shared programs such peaks lie at 1e-43 .. 1e-24, the
/// next ones at 1e-17 and above), jagged from sample to sample, and refining it cost two fifths of
/// a whole run of short_segments. (A radius of 1e20 mm limits no machine.)
inline constexpr double plan_peak_refine_floor = 1e-20;
/// A span whose speed cap is below plan_piece_cap_ratio times the cap of one of its four quarters
/// (of its parameter range) is cut into them, and so on in each quarter (a tight turn in a span
/// then slows only a short stretch around it, issue 20), at most this many times deep and into at
/// most this many pieces.
inline constexpr int plan_span_max_depth = 30;
/// ... and in its first plan_span_fine_cut_depth levels already where one part's cap is over
/// plan_span_cut_cap_ratio times the whole's (since 2026-12-05): a piece runs at the smallest cap
/// of its stretch, so a span whose curvature peaks gently inside ran a third or more of it at the
/// peak's cap. Deeper, the cut keeps to plan_piece_cap_ratio, so that the pieces left go to a
/// near-cusp (at 1.1 on every level, a nearly closed quadratic Bezier took 6559 s instead of 2 s:
/// its 256 pieces were spent away from the cusp).
inline constexpr double plan_span_cut_cap_ratio = 1.1;
inline constexpr int plan_span_fine_cut_depth = 2;
inline constexpr int plan_span_max_pieces = 256;
/// A corner blend between two lines turns from zero curvature at its ends to its peak inside, and
/// its ends join the lines smoothly: it is cut once into this many equal parts of its parameter
/// where one part's cap is over plan_blend_cap_ratio times the whole's, so that the chain through
/// it brakes inside the blend instead of before it (naive_cam_corner1, blends of 13-17 mm whose
/// ends allow twice their apex's speed: 3.287 -> 3.200 s on the jerk = A / T machine, 3.343 ->
/// 3.275 s on XYZ.ini). Once only: cut again (or at 1.1), the many pieces of a run of blends
/// shortened what one held run of chains covers, and tangent_lines_smooth ran 20 % slower on XYZ.ini.
/// The blends at arcs (TransitionCurve) too, since a chain's manoeuvres brake under the speed bands
/// (before, the cut slowed tangent_helix by 2 %: its helix, chained with the cut blend, braked at
/// the acceleration left at its cap).
inline constexpr int plan_blend_parts = 8;
/// ... a blend at an arc only where each part takes at least this many servo periods at the whole
/// blend's cap (shorter parts cannot be braked in: spiral_tight_circular, a spiral of arcs with
/// blends of 0.05-0.3 mm, ran 2.7 % slower on the default machine with them cut).
inline constexpr double plan_blend_part_min_periods = 2.0;
inline constexpr double plan_blend_cap_ratio = 1.2;
/// The planner plans with every axis limit lowered by this share. The check differentiates the
/// setpoints: a position noise e [mm] (the arc-length inverse is accurate to about 1e-13 of a
/// move's length) shows as 8 e / T^3 of jerk, 1e-6 of the limit already at e = 1e-11 mm, T = 1 ms.
inline constexpr double plan_limit_safety = 1e-4;
/// A move of the tool (extra axes standing still) no longer than this many units in the last
/// place of its largest end coordinate is rounding: the planner takes it for a move of zero
/// length (skipped; the gap it leaves is within the checker's rounding allowance).
inline constexpr double plan_rounding_move_ulps = 4.0;
/// A speed profile whose phases, run to its end time, cover its distance to within this share are
/// stretched onto it exactly (trajectory::PathProfile); a larger difference is left to the clamp.
inline constexpr double profile_end_rescale_relative = 1e-9;
/// Neighbouring spans of a curve whose speed caps are within this factor are planned as one piece.
inline constexpr double plan_piece_cap_ratio = 1.5;
/// ... and only where running the merged piece at its smallest cap takes at most this share longer
/// than each stretch at its own (G6_Curva_Delfino: one tight quarter span at 3.6 mm/s among 190 mm
/// at the 4.8 mm/s feed slowed the whole move by 34 %).
inline constexpr double plan_piece_merge_time_loss = 0.01;
/// A piece whose path acceleration differs from the open chain's first piece's by more than this
/// factor starts a new chain (the look-ahead plans a chain with its smallest).
inline constexpr double plan_chain_limit_ratio = 4.0;
/// A piece also starts a new chain where keeping it would cost time: running the chain with it at
/// its new smallest cap takes more than plan_chain_close_time_loss longer than each piece at its own
/// cap, and more than plan_chain_close_change_share of the time a change of speed between the
/// chain's smallest and largest caps takes (a new chain starts and ends at zero acceleration, so
/// closing costs about such a change). Closing at a cap ratio of 1.2 instead was 2-3 % faster on
/// 3D_Chips and random_lines but 4 % slower on circle_small_segments; this is 3 % faster on the
/// first and the same on the circle.
inline constexpr double plan_chain_close_time_loss = 0.05;
inline constexpr double plan_chain_close_change_share = 0.1;
/// A chain's profile that follows its pieces' caps (plan/chain_profile.hpp): the speed may exceed
/// a cap by this share of the chain's largest cap (rounding), a phase that ends within this
/// distance [mm] of a junction is not held to the cap beyond it, and the greedy steps stop after
/// this many times the steps the S-curve at the smallest cap would last (the S-curve is kept then).
inline constexpr double chain_profile_speed_slack = 1e-12;
inline constexpr double chain_profile_boundary_mm = 1e-9;
inline constexpr double chain_profile_max_steps_per_flat = 4.0;
/// Easing the acceleration to zero, and a change of speed, at the smallest limits of the stretches
/// it runs through: those limits are looked up again at most this many times (a slower easing or
/// change runs further; a change still unsettled then takes the smallest over its whole range).
inline constexpr int chain_profile_ease_rounds = 4;
/// Speed levels of a chain's profile, as shares of its largest cap: the limits up to each level are
/// every stretch's of its lowest speed band that holds there (CapStretch::bands), so that a curved
/// stretch speeds up and brakes harder where it runs slower than its cap (a change of speed runs
/// under bands made of the levels between its speeds). 11 levels instead of 7 (0.5 .. 0.95):
/// 3D_Chips on XYZ.ini 91.157 -> 90.928 s, none of the shared runs slower, about 2.5 % more
/// instructions per run; 16: 90.906 -> 90.762 s (and 1.1002 -> 1.0992 of the reference on the
/// jerk = A / T machine), 16 runs faster on XYZ.ini and none slower, 2.2 % more instructions.
/// At most AccelerationBands::kMax - 1 levels.
inline constexpr double chain_profile_speed_levels[] = {0.3,  0.4, 0.5,   0.55, 0.6,   0.65, 0.7,  0.75,
                                                        0.8,  0.85, 0.875, 0.9, 0.925, 0.95, 0.975, 0.99};
/// Most pieces in one chain (pieces joined smoothly, planned with one S-curve): bounds the delay
/// before the look-ahead sees them.
inline constexpr std::size_t plan_chain_max_pieces = 256;
/// Chains that join smoothly (closed for their caps, not at a corner) are held and released
/// through one profile over all of them where that is faster than each through its own (their
/// junctions then carry the acceleration); where it is not, each half of them (of at least
/// plan_held_split_chains chains) is looked at the same way. A run is released after at most
/// plan_held_max_pieces moves' pieces (the parts of a cut blend or span count as one: cutting the
/// blends at arcs otherwise shortened the runs), and before a chain whose smallest path acceleration differs from
/// the run's first by more than plan_held_acceleration_ratio. On performance/3D_Chips (XYZ.ini),
/// without halves: 256 pieces and a ratio of 4 gave 62.9 s, 24 and 2 62.5 s (each chain alone:
/// 63.8 s; 12 or 16 pieces, or a ratio of 1.5, slower again); with halves 62.42 s (64 pieces and
/// halves from 4 chains: 62.37 s, but 3D_Chips and random_lines slower).
inline constexpr std::size_t plan_held_max_pieces = 24;
inline constexpr double plan_held_acceleration_ratio = 2.0;
inline constexpr std::size_t plan_held_split_chains = 2;

// ---- smoothing of dense G01 within the G64 tolerance (program/line_smoother.hpp, geometry/polyline_fit.hpp)
/// A run of lines is smoothed only where consecutive lines turn by at most 30 degrees (cosine of
/// the turn at least this): sharper corners keep their corner (blended or a near stop).
inline constexpr double smooth_max_turn_cos = 0.8660254037844387;
/// ... unless the lines around the vertex are short against the tolerance (a random walk of lines
/// 2.5 tolerances long turning by 35 degrees and more at every vertex: noise within the tolerance,
/// not corners of the part): a turn of up to 90 degrees (cosine at least this) joins the run where
/// the line before, the line after and the one before that are at most
/// smooth_soft_corner_line_tolerances tolerances long, and a corner blend trimming the longer of
/// the two lines whole would stray from them by at most smooth_soft_corner_share of the tolerance.
/// (Longer lines around a sharp turn are a corner of the part: a curve through it bends over them.)
inline constexpr double smooth_soft_corner_turn_cos = 0.0;
inline constexpr double smooth_soft_corner_line_tolerances = 4.0;
inline constexpr double smooth_soft_corner_share = 0.5;
/// Lines inside a smoothed run are at most this many times the tolerance long: longer lines stay
/// straight (they may start or end a run).
inline constexpr double smooth_max_line_tolerances = 50.0;
/// Fewest lines in a run that is smoothed (its first and last line stay lines; the curve between
/// them needs four lines or more to have a free control point).
inline constexpr std::size_t smooth_min_lines = 6;
/// Most lines held in one run: bounds the program stage's window (a longer run is cut there).
inline constexpr std::size_t smooth_max_run_lines = 2000;
/// A long run is fitted beyond its cut by lines of at least this many tolerances of arc length
/// (20 smoothing lengths; they are fitted again by the next run, which continues the curve from
/// the cut), so that at the cut the curve bends as the lines do: the zero curvature of a fit's end
/// reaches about 7 smoothing lengths into it (64 lines of 15 um left a 25 mm circle's curvature at
/// a tenth at the cut, and circle_small_segments still slowed to 40 mm/s there) ...
inline constexpr double smooth_run_overlap_tolerances = 600.0;
/// ... but by at most this many lines (the window's bound; and the cost: the overlap is fitted
/// twice). 250 lines of 15 um (circle_small_segments at 0.01 mm) are still 13 smoothing lengths;
/// on lines far shorter than the tolerance (random_lines_0.001in read in mm: lines of 1 um at
/// 0.01 mm) 1,000 lines cost 8 % of the run and gained nothing (its times 1 % shorter with 250).
inline constexpr std::size_t smooth_run_overlap_max_lines = 250;
/// Share of the tolerance the fitted curve is made to keep, measured on samples (the rest covers
/// what lies between samples).
inline constexpr double smooth_tolerance_share = 0.9;
/// Starting smoothing length of the fit, in tolerances (30: 0.3 mm at the default 0.01 mm).
inline constexpr double smooth_fit_length_tolerances = 30.0;
/// A line longer than this many tolerances gets more than one span in the fit (at most
/// smooth_fit_spans_per_line), so that the curve can turn near its ends and run straight between.
inline constexpr double smooth_fit_span_tolerances = 10.0;
inline constexpr int smooth_fit_spans_per_line = 8;
/// Fits tried before a run is left as lines.
inline constexpr int smooth_fit_iterations = 24;
/// Factor on the weights of the lines where a fit strays (the smoothing length there shrinks by
/// its fourth root: 2): the largest. The dense fit raises a line that strays by r times the target
/// by r^smooth_fit_weight_power, at least smooth_fit_weight_step_min, at most this (issue 12: with
/// the whole step everywhere the curve stayed far inside the tolerance around lines just beyond it;
/// on XYZ.ini random_lines_0.001in (G20) 14.166 -> 12.685 s, performance/3D_Chips 60.442 ->
/// 59.664 s; r^2 took up to 61 % more instructions on random_lines read in mm, r^4 18 %).
inline constexpr double smooth_fit_weight_step = 16.0;
inline constexpr double smooth_fit_weight_step_min = 2.0;
inline constexpr double smooth_fit_weight_power = 4.0;
/// ... squared while the fit strays by more than this many times its target (random_lines_0.001in
/// in mm, lines of a tenth of the tolerance: its first fits stray by 45 and 490 times the target,
/// and took 16 and 14 iterations; 802 instead of 878 M instructions per run, its times unchanged
/// to 0.1 %).
inline constexpr double smooth_fit_far_targets = 16.0;
// ---- G01 compression (kontur compress: compress/compressor.hpp; geometry/polyline_fit.hpp with few knots)
/// A spline with few knots starts with this many spans (knots at vertices evenly spaced).
inline constexpr std::size_t compress_spline_initial_spans = 4;
/// Rounds of knot insertion before the spline is given up, and fits per round.
inline constexpr int compress_spline_knot_rounds = 16;
inline constexpr int compress_spline_round_iterations = 4;
/// Smoothing length of the spline with few knots, in tolerances (the dense fit's is
/// smooth_fit_length_tolerances).
inline constexpr double compress_spline_length_tolerances = 1.0;
/// A line piece longer than this many times the run's mean line (and than
/// smooth_max_line_tolerances) is not put into a spline.
inline constexpr double compress_spline_long_line_means = 4.0;
/// Share of the tolerance the lines, arcs and conics are fitted within (the rest: the rounding of
/// the written coordinates and the sampling of the check).
inline constexpr double compress_fit_share = 0.97;
/// Decimals of the written coordinates: mm programs, inch programs.
inline constexpr int compress_decimals_mm = 4;
inline constexpr int compress_decimals_inch = 5;
/// An arc through the middle vertex that strays by less than this many tolerances is searched
/// for a better centre (golden section, at most compress_arc_search_steps evaluations).
inline constexpr double compress_arc_search_tolerances = 3.0;
inline constexpr int compress_arc_search_steps = 16;
/// Largest change of direction [rad] at the joint of two written pieces that counts as tangent
/// (the compressor prefers such smooth joints: a planner need not slow down there).
inline constexpr double compress_kink_rad = 1e-4;
/// Largest radius of a written arc, in multiples of its chord (a flatter arc is a line).
inline constexpr double compress_max_radius_chords = 1e4;
/// Samples per input line of the independent deviation check (at least), and the step of the
/// samples along a written curve in tolerances (at most).
inline constexpr int compress_check_samples_per_line = 8;
inline constexpr double compress_check_step_tolerances = 2.0;

/// The checker searches a setpoint's programmed lines this many lines before and after its own.
inline constexpr long check_smoothing_lines = 16;
/// The checker accepts a smoothed setpoint whose distance exceeds the tolerance by at most this, relative.
inline constexpr double smoothing_deviation_relative = 1e-9;

// ---- corner blending within the G64 tolerance (plan/corner_blend.hpp)
/// Lines shorter than this are not blended [mm] (their corners stay junctions): a blend on them
/// would bend within a fraction of a micrometre.
inline constexpr double blend_min_line_mm = 1e-4;
/// Corners that turn by more than 120 degrees (cosine of the turn below this) are not blended:
/// the blend would turn almost on the spot, and the motion nearly stops there anyway.
inline constexpr double blend_min_turn_cos = -0.5;
/// Largest share of each line a blend may trim: a line between two blended corners keeps at least
/// 10 % of its length as a straight middle.
inline constexpr double blend_max_trim_share = 0.45;
/// Where an arc meets a move, the two count as meeting where their ends lie at most this apart,
/// relative to the larger of 1 mm and the distance of the corner from the origin (an arc's end is
/// computed from its centre and angle).
inline constexpr double blend_arc_contiguous_relative = 1e-9;
/// Bisection steps of the corner blender's estimate of the time to cover a distance while speeding
/// up (an S-curve's phases inverted; 60 halve it to the last bit of a double).
inline constexpr int blend_estimate_bisections = 60;
/// Least share of the acceleration [squared] the estimate leaves a curved move speeding up at its
/// cap (its centripetal part takes the rest).
inline constexpr double blend_estimate_least_acceleration_share = 0.05;
/// Trim distances tried at a junction with an arc before it is left unblended (each tried one is
/// shrunk by the ratio of the tolerance to its deviation).
inline constexpr int blend_arc_attempts = 12;
/// Tangent scales of a blend of a junction with an arc (geometry/transition_curve.hpp) the blender
/// sizes and compares, taking the one that passes the junction fastest.
inline constexpr double blend_arc_tangent_scales[] = {1.0, 0.8, 0.9, 1.1, 1.25};
/// Samples of a blend of a junction with an arc (plus a golden-section search around the largest)
/// when the blender measures its largest distance from the programmed pieces to size it
/// (geometry/transition_curve.hpp; its distance varies slowly: the peak between samples is within
/// a few 1e-4 of it, inside the 1 - blend_tolerance_share the blender leaves).
inline constexpr int blend_arc_deviation_samples = 64;
/// The corner blender's family of blend shapes (geometry/corner_blend_curve.hpp: the third control
/// point on each line at e d from the corner, the second at (base + slope e) d), and the range of e
/// it searches for the fastest blend of each corner (golden sections, blend_shape_search_steps):
/// a small e lets the curvature rise slowly from the lines (the jerk of a stiff-less machine), a
/// large one keeps its peak low (the acceleration). Fitted to the fastest quintic of the form at
/// turns of 2 .. 120 degrees and jerks of 10 .. 10^4 times the acceleration per second.
inline constexpr double blend_shape_second_base = 0.57;
inline constexpr double blend_shape_second_slope = 0.2;
inline constexpr double blend_shape_third_min = 0.02;
inline constexpr double blend_shape_third_max = 0.5;
inline constexpr int blend_shape_search_steps = 12;
/// Share of the tolerance a blend is made to use (the rest covers the sampling of its deviation).
inline constexpr double blend_tolerance_share = 0.999;
/// Samples of a blend (plus a golden-section search around the largest) when the blender measures
/// its largest distance from the programmed lines to size it (geometry/corner_blend_curve.hpp).
inline constexpr int blend_deviation_samples = 256;
/// Samples of a blend (plus successive parabolic interpolation around every local maximum) when
/// the checker measures its distance from the programmed lines, its own way (verify::blend_deviation).
inline constexpr int check_blend_samples = 256;
/// A setpoint without a move id (a file) farther than this from the move its line and the
/// neighbouring moves suggest makes the checker search the nearest point of the whole path [mm].
/// The path tolerance of the check (1e-6 mm): a setpoint within it of its line's move stays on
/// that move, so the lower level's replay (within 1e-6 mm of the planner's setpoints) is not taken
/// to another move where the path crosses itself.
inline constexpr double check_resync_mm = 1e-6;
/// A breakpoint of a move where the unit tangent jumps by more than this is a corner to the
/// chord check (checker): the setpoints on either side are measured against chords through it, as
/// at a corner between two moves (a degree-1 or double-knot spline has corners inside one move).
inline constexpr double check_corner_tangent_jump = 1e-3;
/// The rounding the checker allows each setpoint's position before its finite differences
/// count against a limit, in units in the last place of the largest position of the difference:
/// a position is a sum of rounded terms (start plus a rounded distance along a rounded
/// direction), off by up to about 2 ulps, so a jerk difference (weights 1 3 3 1) may be off by 16.
/// With 1 ulp per position, a 8.9 mm line on Y with jerk 26.7 mm/s^3 at T = 125 us read as
/// 1.0000013 times its jerk (property seed 11218): one ulp there is 3.4e-5 of the limit.
inline constexpr double check_position_rounding_ulps = 2.0;
/// The checker's projection of a setpoint on its move searches finer than its 17 samples per span
/// only where the nearest point those samples find is farther than this [mm] (a setpoint on the
/// path is found within 1e-12 mm by them almost always; the path-error alarm is at 1e-6 mm) ...
inline constexpr double check_projection_search_above_mm = 1e-9;
/// ... and only in a sample interval whose arc length lets it hold a point nearer by more than
/// this share of the distance (and 1e-9 mm) ...
inline constexpr double check_projection_search_relative = 1e-3;
/// ... at most this many finer searches per setpoint, the nearest intervals first.
inline constexpr int check_projection_search_budget = 24;
/// The checker accepts a blend whose deviation exceeds its tolerance by at most this, relative.
inline constexpr double blend_deviation_relative = 1e-9;

// ---- the segment stream (segments/segment_stream.hpp, docs/segments.md)
/// Largest distance of a setpoint replayed by the lower level from the planner's [mm] ([deg] for
/// A B C): the default of `kontur run --format segments` (--segment-tolerance).
inline constexpr double segment_tolerance_mm = 1e-6;
/// Longest piece of the stream [servo cycles]: also what the writer holds before it must fit.
inline constexpr int segment_max_piece_cycles = 8192;
/// Share of the segment tolerance the fit uses (the rest covers the planner's own distance from
/// the path, ~1e-14 mm, so that a replay's check against the path stays within the tolerance).
inline constexpr double segment_tolerance_share = 0.999;
/// A piece of the stream ends within this share of the tolerance of the planner's setpoint (the
/// next piece starts from there).
inline constexpr double segment_end_share = 1e-3;
/// The smallest --segment-tolerance: a few hundred ulps of a 10 m coordinate, above the rounding
/// of the lower level's additions over a piece [mm].
inline constexpr double segment_min_tolerance_mm = 1e-9;

}  // namespace kontur::tolerances
