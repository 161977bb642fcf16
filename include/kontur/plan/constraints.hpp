#pragma once
// The constraints of a path on a machine, shared by the online planner (look-ahead, pieces,
// junctions) and the time-optimal reference: per-axis velocity, acceleration and jerk bounds along
// the path, the centripetal and curvature-change terms, the chord-error speed limit, corner and
// junction limits, and the rule for an axis the machine lacks (docs/planner.md, "Limits of a
// piece" and "Time-optimal reference").
//
// An axis the machine lacks: a stretch of path (or a point of it) whose unit tangent has a
// component above tolerances::missing_axis_tangent on that axis cannot be run, and its speed cap
// is zero (velocity_cap, speed_cap; the time-optimal reference refuses such a path with
// InputError "missing-axis", as it refuses every path it cannot run). An axis the machine lacks
// and the path does not move along bounds nothing: its curvature, curvature change and corner
// jumps are not looked at. Rotary axes do not carry the path.
#include <kontur/axes.hpp>
#include <kontur/geometry/curve.hpp>
#include <kontur/machine.hpp>
#include <kontur/plan/banded_profile.hpp>
#include <kontur/plan/scurve.hpp>
#include <kontur/tolerances.hpp>

#include <array>
#include <span>
#include <utility>

namespace kontur::plan {

/// The machine's linear axes by coordinate (X, Y, Z; nullptr where the machine has none).
using LinearAxes = std::array<const AxisLimits*, 3>;

/// The linear axes of `machine` (rotary axes are left out).
[[nodiscard]] LinearAxes linear_axes(const Machine& machine) noexcept;

/// The coordinate (0, 1, 2) of the first axis the machine lacks along which the tangent moves
/// (|t_i| > tolerances::missing_axis_tangent), or -1 if there is none. `tangent` may be a unit
/// tangent or a bound of its components' magnitudes.
[[nodiscard]] int missing_axis_moved(const Vec3& tangent, const LinearAxes& axes) noexcept;

/// The velocity part of the speed cap [mm/s]: the smallest of the feed [mm/s], the machine's max
/// feed and every axis's velocity along the tangent, V_i / |t_i|; zero if the tangent moves an axis
/// the machine lacks (missing_axis_moved).
[[nodiscard]] double velocity_cap(const Vec3& tangent, double feed_mm_s, const Machine& machine,
                                  const LinearAxes& axes) noexcept;

/// The chord-error speed limit [mm/s] at curvature `kappa` [1/mm]:
/// (2/T) sqrt(R^2 - (R - delta)^2) with R = 1 / kappa (infinity where kappa = 0).
[[nodiscard]] double chord_cap(double kappa, const Machine& machine) noexcept;

/// Curvature vector K = kappa n = dt/ds [1/mm] and its derivative along the path dK/ds [1/mm^2]
/// from a point's derivatives up to the third (zero where C' = 0). The online planner's form.
[[nodiscard]] std::pair<Vec3, Vec3> curvature_vector_and_rate(const Derivatives& d) noexcept;

/// Unit tangent and curvature vector K = kappa n [1/mm] from a point's derivatives up to the
/// second (zero where C' = 0): the same K as curvature_vector_and_rate, computed as the part of C''
/// across the tangent over |C'|^2 (the two differ in rounding; the time-optimal reference's form).
[[nodiscard]] std::pair<Vec3, Vec3> tangent_and_curvature(const Derivatives& d) noexcept;

/// One axis's acceleration constraint at a point in the variables of the time-optimal reference,
/// u = s_ddot and x = s_dot^2: |t u + k x| <= a, signed so that t >= 0 (a tangent component at or
/// below tolerances::time_optimal_tangent_zero counts as 0).
struct AccelerationRow {
  double t = 0.0;  ///< tangent component [1]
  double k = 0.0;  ///< curvature vector component [1/mm]
  double a = 0.0;  ///< the axis's acceleration limit [mm/s^2]
};

/// The acceleration constraints of a point with unit tangent t and curvature vector k [1/mm], one
/// per axis the machine has; returns how many of `rows` are set.
int acceleration_rows(const Vec3& t, const Vec3& k, const LinearAxes& axes, std::array<AccelerationRow, 3>& rows) noexcept;

/// Largest speed [mm/s] through a corner whose unit tangent jumps by `dt` when setpoints a servo
/// period T apart see the jump as an acceleration v |dt_i| / T within `acceleration_share` of each
/// axis's limit: min over the axes with |dt_i| > `ignore_below` of share A_i T / |dt_i| (infinity
/// if none). The time-optimal reference's servo-period corner rule (share 1; the online planner's
/// junction limit gives each axis its own share, lower where J T approaches A: junction_limit).
[[nodiscard]] double corner_acceleration_cap(const Vec3& dt, const Machine& machine, const LinearAxes& axes,
                                             double acceleration_share, double ignore_below) noexcept;

/// Per-axis bounds of the geometry of a stretch of path, as the limits need them: maxima over
/// samples (plan_samples_per_span per span), raised by tolerances::plan_sample_margin.
struct PathGeometry {
  Vec3 tangent = Vec3::Zero();         ///< max |t_i| of the unit tangent
  Vec3 curvature = Vec3::Zero();       ///< max |K_i| of the curvature vector K = kappa n [1/mm]
  Vec3 curvature_rate = Vec3::Zero();  ///< max |dK_i/ds| along the path [1/mm^2]
  double max_kappa = 0.0;              ///< largest curvature [1/mm] (for the chord error)
  /// The smallest sampled |K_i| [1/mm], |dK_i/ds| [1/mm^2] and curvature [1/mm]: not bounds, what a
  /// part of the stretch may get down to (zero where not known); split_move cuts a stretch into
  /// parts only where these could raise a part's cap enough.
  Vec3 curvature_low = Vec3::Zero();
  Vec3 curvature_rate_low = Vec3::Zero();
  double kappa_low = 0.0;
  /// |dq_e/ds| of each extra axis A B C [deg/mm] U V W [mm/mm] (they move linearly with the path
  /// distance: no curvature terms); ExtraAxes order.
  ExtraAxes extra_rate{};
  /// Per axis, pairs (|t_i|, |K_i|) of sampled points, raised by the same margins as the maxima:
  /// the axis's acceleration |t_i| a + |K_i| v^2 <= A_i need only hold at each pair, which is
  /// tighter than at (max |t_i|, max |K_i|) where the two peak apart. On a circle the tangent's
  /// component peaks where the curvature's vanishes: at a centripetal share c of A the path keeps
  /// about sqrt(1 - c^2) A of acceleration, not (1 - c) A. A pair dominated by another is dropped;
  /// while there are more than tolerances::plan_acceleration_pairs, neighbours are merged into
  /// their componentwise maximum (still a bound). None (n == 0): the maxima are the one pair.
  struct AxisPairs {
    std::array<double, tolerances::plan_acceleration_pairs> t{};  ///< |t_i|
    std::array<double, tolerances::plan_acceleration_pairs> k{};  ///< |K_i| [1/mm]
    int n = 0;
  };
  std::array<AxisPairs, 3> pairs{};
  /// The pairs of axis i, or the maxima as one pair where none were sampled ({t, k} each).
  [[nodiscard]] std::vector<std::array<double, 2>> axis_pairs(int i) const;
  /// The same written to `out` (room for plan_acceleration_pairs): how many.
  std::size_t axis_pairs_into(int i, std::span<std::array<double, 2>> out) const noexcept;
  /// Sets the pairs of axis i from any number of (|t_i|, |K_i|), reduced as above.
  void set_pairs(int i, std::vector<std::array<double, 2>> points);
  /// The same, sorting and reducing `points` in place (no allocation).
  void set_pairs_in_place(int i, std::span<std::array<double, 2>> points);
  /// The bounds of both stretches.
  void merge(const PathGeometry& other);
  /// Forget the curvature (a stretch the motion only stops in, or the straight comparison).
  void drop_curvature() noexcept;
};

/// Geometry bounds of a curve between parameters u0 < u1 (inside one span, or sampled per span).
/// Points where |C'| is at most `speed_floor` [mm per parameter unit] (or tiny against the
/// stretch's own samples) are stationary: their tangent and curvature are rounding noise and are
/// not sampled (split_move passes tolerances::plan_stationary_speed_relative times the curve's peak).
[[nodiscard]] PathGeometry path_geometry(const Curve& curve, double u0, double u1,
                                         int samples = tolerances::plan_samples_per_span, double speed_floor = 0.0);

/// The speed cap [mm/s] of a stretch: velocity_cap (the feed, the machine's max feed, every axis's
/// velocity along the tangent; zero if the stretch moves an axis the machine lacks), the
/// centripetal acceleration K_i v^2 <= share A_i, the curvature change
/// K'_i v^3 <= curvature_rate_share J_i and the chord-error limit (chord_cap).
[[nodiscard]] double speed_cap(const PathGeometry& g, double feed_mm_s, const Machine& machine,
                               double centripetal_share,
                               double curvature_rate_share = tolerances::plan_curvature_rate_jerk_share) noexcept;

/// The speed cap [mm/s] of a whole curve at a programmed feed [mm/s] (speed_cap of its geometry
/// sampled over its parameter range, a chain's largest centripetal and curvature-change shares): what
/// the corner blender's estimate of a blend's speed and of its moves' speeds uses
/// (program::BlendSpeed, wired by the pipeline).
[[nodiscard]] double curve_speed_cap(const Curve& curve, double feed_mm_s, const Machine& machine);

/// How path_limits chooses a stretch's centripetal and curvature-change shares: what lies at its
/// ends, and how much the speed changes there weigh against its length.
struct ShareChoice {
  /// The share of each axis's jerk the junctions at the stretch's ends take (see junction).
  double junction_jerk_share = 0.0;
  /// The weight of the speed changes at its ends: the estimated time adds 2 change_weight times
  /// the time one change loses (1: a stretch planned alone, speeding up and braking; the motion
  /// planner weighs each end of a piece inside a chain less, tolerances::plan_share_choice_change_weight;
  /// 0: the length alone decides).
  double change_weight = 1.0;
  /// It runs alone in its chain: both its ends are corners or stops, planned by its speed bands.
  bool alone = false;
  /// [mm/s] the speed its changes start from: the speed a junction at its ends allows (0: rest).
  double change_from_mm_s = 0.0;
  /// It is a low of its chain's caps, which the motion passes at the cap
  /// (MotionPlanner::raise_chain_lows).
  bool at_a_low = false;
};

/// The path limits of a stretch of length `length_mm`: its speed cap (speed_cap) and the largest
/// path acceleration and jerk that keep every axis within its limits at any speed up to the cap:
/// |t_i| a + K_i v^2 <= A_i, and |t_i| j + 3 K_i v a + K'_i v^3 <= (1 - junction_share) J_i, the
/// cross term taking at most plan_cross_jerk_share; junction_share is `choice`'s
/// junction_jerk_share. Of the centripetal shares in tolerances::plan_centripetal_shares and the
/// curvature-change shares in tolerances::plan_curvature_rate_jerk_shares (those that leave the
/// path at least plan_path_jerk_share_min of the jerk), the pair with the shortest estimated time
/// is taken: the length at the cap plus 2 change_weight times the time a change from
/// change_from_mm_s to the cap loses against running its distance at the cap. Shares above the
/// chain's largest (tolerances::plan_chain_centripetal_share_max and
/// plan_chain_curvature_rate_share_max) only where change_weight > 0 or at_a_low. A curved
/// stretch's change is estimated by its acceleration_bands (as the look-ahead and the chain profile
/// speed it up below its cap) where it is `alone` or at the smallest curvature-change share (at
/// larger ones the estimate, which does not weigh the braking at a smooth end, chose caps that ran
/// slower); a banded change longer than the stretch (half of it where change_weight >= 1) is
/// counted over the stretch, up to the speed it reaches there.
[[nodiscard]] PathLimits path_limits(const PathGeometry& g, double length_mm, double feed_mm_s,
                                     const Machine& machine, const ShareChoice& choice = {}) noexcept;

/// The speed bands of a curved stretch whose limits at its cap are `at_cap` (from path_limits or
/// path_limits_at with the same junction share): in the band up to top_k = f_k cap
/// (tolerances::plan_acceleration_band_tops) the path acceleration that keeps every axis within its
/// limits at speeds up to top_k (|t_i| a + |K_i| top_k^2 <= A_i at each pair, the cross term within
/// its share), the last band at_cap's; the path jerk what is left with the largest cross term
/// 3 K_i top_k a_k of the bands. Empty (n = 0) on a straight stretch or where the bands would not
/// raise the acceleration.
[[nodiscard]] AccelerationBands acceleration_bands(const PathGeometry& g, const PathLimits& at_cap,
                                                   const Machine& machine, double junction_jerk_share) noexcept;

/// The path limits of a stretch at a given speed cap [mm/s] (as path_limits, without choosing the
/// centripetal share): raising the junction share lowers only the jerk.
[[nodiscard]] PathLimits path_limits_at(const PathGeometry& g, double cap_mm_s, const Machine& machine,
                                        double junction_jerk_share) noexcept;

/// Geometry of a move as the planner sees it: the curve, its length and the largest speed the
/// program asks for.
struct MoveGeometry {
  const Curve* curve = nullptr;  ///< the path
  double length_mm = 0.0;        ///< its length [mm]
  double feed_mm_s = 0.0;        ///< programmed feed (or rapid speed) [mm/s]
};

/// The path limits of a whole move (path_limits over the geometry of all its spans, `samples`
/// per span, with smooth junctions at its ends).
[[nodiscard]] PathLimits move_limits(const MoveGeometry& move, const Machine& machine,
                                     int samples = tolerances::plan_samples_per_span);

/// What a junction of two stretches allows.
struct Junction {
  double velocity = 0.0;     ///< largest speed through it [mm/s] (infinity if smooth)
  double jerk_share = 0.0;   ///< share of each axis's jerk it uses (0 if smooth)
  /// Tangent and curvature continuous: no limit of its own (a chain goes on through it).
  [[nodiscard]] bool smooth() const noexcept { return jerk_share == 0.0; }
};

/// The junction of two stretches, from the end of the first (`end_in`: point and derivatives up to
/// the second, as the limit from the left) and the start of the second. Setpoints a servo period
/// T apart see a change of direction as a velocity jump, and a change of curvature as an
/// acceleration jump, within one period; each axis's jerk (as a finite difference of the
/// setpoints sees it) stays within `jerk_share` of its limit when
/// v |t1 - t2|_i / T^2 + v^2 |K1 - K2|_i / T <= jerk_share J_i, and the acceleration spike of a
/// corner within 1 - max centripetal share of its limit: v |t1 - t2|_i / T <= 0.1 A_i
/// (corner_acceleration_cap). Where tangent and curvature agree to plan_junction_smooth there is
/// no limit.
[[nodiscard]] double junction_limit(const Derivatives& end_in, const Derivatives& start_out,
                                    const Machine& machine, double jerk_share = 1.0) noexcept;

/// The junction with the share chosen by its kind: none if smooth, plan_corner_jerk_share for a
/// corner, plan_smooth_junction_jerk_share for a small corner or a curvature jump only.
[[nodiscard]] Junction junction(const Derivatives& end_in, const Derivatives& start_out,
                                const Machine& machine) noexcept;
/// The junction as the extra axes see it: their rates dq_e/ds (signed, ExtraAxes order) before and
/// after. A jump of a rate is a velocity jump v |dr_e| of that axis within one period, limited as
/// the tangent jump of a linear axis is (junction_limit's rule without the curvature term); equal
/// rates (to plan_junction_smooth) are smooth.
[[nodiscard]] Junction extra_axes_junction(const ExtraAxes& rate_in, const ExtraAxes& rate_out,
                                           const Machine& machine) noexcept;
/// The tighter of two junction limits (the smaller speed, the larger jerk share).
[[nodiscard]] Junction tighter(const Junction& a, const Junction& b) noexcept;

}  // namespace kontur::plan
