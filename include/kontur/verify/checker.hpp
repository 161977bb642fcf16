#pragma once
// An independent check of setpoints against the machine and the programmed path, computed from
// the setpoints alone (finite differences) and the path's geometry: nothing of the planner is
// trusted. It depends on the moves (program/move.hpp), the machine and the setpoints' type, never
// on the planner. It streams: setpoints are added one at a time, and it keeps only the last few
// (memory does not grow with the job). The core of `kontur verify`, of the pipeline's summary and
// of the tests that prove the planner.
#include <array>
#include <cstddef>
#include <functional>
#include <kontur/axes.hpp>
#include <kontur/geometry/length.hpp>
#include <kontur/geometry/curve.hpp>
#include <kontur/machine.hpp>
#include <kontur/program/move.hpp>
#include <kontur/trajectory/sampler.hpp>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace kontur::verify {

/// A setpoint to check: time [s], axis positions, source line and (if known) its move.
using Sample = trajectory::Setpoint;

/// The measures of one move: over the setpoints the checker matched to it.
struct BlockStats {
  long source_line = 0;
  long samples = 0;                     ///< setpoints on this move (0: shorter than a period, skipped)
  long first_sample = -1;               ///< index of its first setpoint (-1 if none)
  long last_sample = -1;                ///< index of its last setpoint (-1 if none)
  double t_first_s = 0.0;               ///< time of its first setpoint [s] (0 if none)
  double t_last_s = 0.0;                ///< time of its last setpoint [s] (0 if none)
  Vec3 first_point = Vec3::Zero();      ///< tool point of its first setpoint [mm]
  double max_path_error_mm = 0.0;       ///< largest distance of its setpoints from its path [mm]
  double max_chord_error_mm = 0.0;      ///< largest bow of its chords (both ends on it) [mm]
  double max_velocity_ratio = 0.0;      ///< over its setpoints k: max over axes of the difference ending at k / limit
  double max_acceleration_ratio = 0.0;  ///< the same for the second difference
  double max_jerk_ratio = 0.0;          ///< the same for the third difference
};

/// What the checker measured at one setpoint, handed to an Observer in time order.
struct SampleMeasure {
  std::size_t index = 0;                      ///< index of the setpoint
  double t_s = 0.0;                           ///< its time [s]
  AxisVector position = AxisVector::Zero(3);  ///< its axis positions [mm] / [deg], in the layout's order
  /// Backward differences per axis, as the limits are checked: (p_k - p_{k-1}) / T [mm/s], then
  /// the second [mm/s^2] and third [mm/s^3] differences over T^2 and T^3; zero where there are
  /// not enough earlier setpoints (k < 1, 2, 3).
  AxisVector velocity = AxisVector::Zero(3), acceleration = AxisVector::Zero(3), jerk = AxisVector::Zero(3);
  double velocity_ratio = 0.0, acceleration_ratio = 0.0, jerk_ratio = 0.0;  ///< max over axes / limit
  double path_error_mm = 0.0;                                               ///< distance from its move's path [mm]
  double chord_error_mm = 0.0;  ///< bow of the path from the chord ending here [mm] (0 at a move change)
  std::size_t move = 0;         ///< index into `moves` of the move it was matched to
};

/// Called once per setpoint, in order (only while every setpoint so far is finite).
using Observer = std::function<void(const SampleMeasure&)>;

/// Measured maxima and what they are measured against.
struct Report {
  long samples = 0;
  bool finite = true;                   ///< no NaN or infinity in any sample
  bool uniform_time = true;             ///< every step is one servo period (1e-9 relative)
  double max_velocity_ratio = 0.0;      ///< max over axes of |dx/dt| / limit (1 = at the limit)
  double max_acceleration_ratio = 0.0;  ///< the same for the second difference
  double max_jerk_ratio = 0.0;          ///< the same for the third difference
  /// The same three with each difference first lowered by what rounding the positions to doubles
  /// alone can make of it (1 unit in the last place per position: 2, 4 and 8 ulp of the largest
  /// |x| over T, T^2, T^3; 1 % of 50 000 mm/s^3 at 900 000 mm and T = 125 us, issue 20 case 10,
  /// nothing measurable near the origin): what passed() judges.
  double max_velocity_excess = 0.0, max_acceleration_excess = 0.0, max_jerk_excess = 0.0;
  char worst_velocity_axis = ' ', worst_acceleration_axis = ' ', worst_jerk_axis = ' ';
  double max_path_error_mm = 0.0;          ///< largest distance of a setpoint from its move's path [mm]
  double max_chord_error_mm = 0.0;         ///< largest distance of the path from a cycle's chord [mm]
  double start_error_mm = 0.0;             ///< distance of the first setpoint from the path's start [mm]
  /// Largest distance of the last setpoint from the path's end, and of a move's end from the next
  /// move's start (every block end; issue 20, case 8) [mm].
  double end_error_mm = 0.0;
  long end_error_line = 0;  ///< the line of the move that ends there (0: the last setpoint)
  /// Largest distance of an extra axis (A B C [deg], U V W [mm]) of a setpoint from where its move
  /// puts it (linear in the distance along the move; as programmed at the start and end) [mm] or
  /// [deg]; 0 for X Y Z layouts.
  double max_extra_axis_error = 0.0;
  char worst_extra_axis = ' ';  ///< the axis of max_extra_axis_error
  long blends = 0;                         ///< corner blends among the moves
  double max_blend_deviation_mm = 0.0;     ///< largest distance of a blend from its programmed corner's lines [mm]
  double blend_tolerance_mm = 0.0;         ///< the tolerance of the blend with the largest deviation / tolerance [mm]
  double max_blend_deviation_ratio = 0.0;  ///< largest deviation / tolerance of a blend
  long smoothed_lines = 0;  ///< moves that are smoothed lines (program/line_smoother.hpp)
  /// Largest distance of a setpoint on a smoothed line from the programmed lines [mm].
  double max_smoothing_deviation_mm = 0.0;
  /// The tolerance of the smoothed line with the largest distance / tolerance [mm].
  double smoothing_tolerance_mm = 0.0;
  /// Largest distance / tolerance of a setpoint on a smoothed line.
  double max_smoothing_deviation_ratio = 0.0;
  /// One per move, in the order of `moves` (empty when the check could not run: no setpoint,
  /// no move, or a setpoint not finite). Their maxima are the maxima above.
  std::vector<BlockStats> blocks;
  /// True if every measure is within the machine's limits (1e-6 relative) and tolerances (every
  /// blend within its corner's tolerance, tolerances::blend_deviation_relative; every setpoint on a
  /// smoothed line within the tolerance of the programmed lines, tolerances::smoothing_deviation_relative).
  [[nodiscard]] bool passed(const Machine& machine) const noexcept;
  /// What failed, one line each (empty if passed).
  [[nodiscard]] std::vector<std::string> failures(const Machine& machine) const;
};

/// Largest distance [mm] of a blend `curve` from the union of its programmed corner's pieces
/// `before` and `after` (each point's distance by PieceDistance: a line's exactly, an arc's by
/// HelixArc::distance_mm), measured by the checker's own method (independent of the blender's sizing):
/// tolerances::check_blend_samples samples, then successive parabolic interpolation around every
/// local maximum of the samples.
[[nodiscard]] double blend_deviation(const Curve& curve, const program::ProgrammedCorner& corner);

struct PathIndex;

namespace detail {
/// A piece of a curve between two parameters: its arc length L (the 7-point Gauss rule,
/// fixed_rule_length) and the radius sqrt(L^2 - chord^2) / 2 of the capsule around its chord
/// that holds it [mm].
struct IntervalBound {
  double length_mm = 0.0;
  double radius_mm = 0.0;
};
/// A move's curve sampled for the checker's projection, computed once per move (and kept for the
/// last few moves): 17 samples of every span, and the bound of each of its 16 sample intervals.
struct CurveSamples {
  std::size_t move = static_cast<std::size_t>(-1);
  std::vector<double> u;               // 17 per span
  std::vector<Vec3> point;             // C(u) [mm]
  std::vector<IntervalBound> bound;    // 16 per span
};
}  // namespace detail

/// The streaming check.
class Checker {
 public:
  ~Checker();
  Checker(const Checker&) = delete;
  Checker& operator=(const Checker&) = delete;
  /// Checks against the path `moves` (kept by reference: it may grow while setpoints are added, as
  /// long as every setpoint's move is already in it; all of it must be there for setpoints without
  /// a move id), `machine` and the positions' `layout`. `observer` (if set) receives every
  /// setpoint's measures, in order (for plots).
  Checker(const std::vector<program::Move>& moves, const Machine& machine, const AxisLayout& layout = AxisLayout::xyz(),
          Observer observer = {});
  /// The next setpoint, in time order. A setpoint with a move id is matched to that move; one
  /// without (read from a file, possibly another planner's, with block 0 or its own blends) to
  /// the next move with its source line, and among moves of one line (or where lines are not
  /// known) to the nearest of the next few. Where that move is farther than
  /// tolerances::check_resync_mm, the nearest point of the whole path is searched (a bounding-box
  /// tree over the moves): its distance is the setpoint's path error, and the matching goes on
  /// from that move (a path that comes back to a point it passed cannot lose the matching).
  void add(const Sample& s);
  /// The report, after the last setpoint (the end error, the blends, the worst axes).
  [[nodiscard]] Report finish();

 private:
  struct Axis {
    const AxisLimits* limits;
    int index;  // in the layout
    double max_v = 0.0, max_a = 0.0, max_j = 0.0;
    double excess_v = 0.0, excess_a = 0.0, excess_j = 0.0;  // less the rounding of the positions
  };
  [[nodiscard]] const std::vector<double>& spans_of(std::size_t move);
  [[nodiscard]] const detail::CurveSamples& samples_of(std::size_t move);
  // The parameter of the point of move n nearest to p (the projection, from u_hint).
  [[nodiscard]] double project_on(std::size_t n, const Vec3& p, double u_hint);
  // The move's corners, computed once: where its curve stands still (C' = 0: a cusp or a repeated
  // control point, where the planner stops) or its tangent jumps at a breakpoint (a double knot, a
  // degree-1 spline): the setpoints cut them as they cut a corner between two moves.
  [[nodiscard]] const std::vector<double>& corners_of(std::size_t move);
  std::vector<std::unique_ptr<ArcLengthTable>> tables_;  // per move with extra axes (distance of u)
  ExtraAxes last_extra_{};                               // extra axes of the last setpoint
  [[nodiscard]] std::size_t match(const Sample& s, const Vec3& p, double& u, double& d);
  // The largest distance of the setpoint's extra axes from where move m puts them at u (or, on a
  // move of the extra axes alone, from the straight line between its start and end); sets `axis`.
  [[nodiscard]] double extra_axis_error(const AxisVector& position, std::size_t m, double u, char& axis);
  // The nearest point of the whole path to p, if nearer than d: updates m, u, d.
  void nearest_on_path(const Vec3& p, std::size_t& m, double& u, double& d);

  const std::vector<program::Move>& moves_;
  const Machine& machine_;
  AxisLayout layout_;
  Observer observer_;
  double period_;
  std::vector<Axis> axes_;
  Report r_;
  bool measuring_ = true;                  // false once a setpoint is not finite
  std::array<AxisVector, 3> previous_{};   // positions of setpoints k-1, k-2, k-3
  Vec3 previous_point_ = Vec3::Zero();     // tool point of setpoint k-1 [mm]
  std::vector<std::size_t> search_stack_;  // nearest_on_path's nodes to visit (kept: no allocation per setpoint)
  double t_previous_ = 0.0;
  Vec3 last_point_ = Vec3::Zero();
  std::vector<std::vector<double>> breakpoints_;  // per move, computed once (the projection samples every span)
  std::vector<std::optional<std::vector<double>>> corners_;  // per move, computed once (corners_of)
  std::array<detail::CurveSamples, 16> samples_{};  // of the last moves projected on (samples_of)
  std::size_t samples_next_ = 0;                    // the entry replaced next
  std::unique_ptr<PathIndex> index_;              // built on the first setpoint that needs it
  std::size_t m_ = 0, m_prev_ = 0;
  double u_prev_ = 0.0;
  SampleMeasure sm_;
};

/// Checks `samples` (in time order) against `machine` and the path `moves`: a Checker fed every
/// sample.
[[nodiscard]] Report check(const std::vector<Sample>& samples, const std::vector<program::Move>& moves,
                           const Machine& machine, const Observer& observer = {});

}  // namespace kontur::verify
