#pragma once
// The two-level control of seed 002 (../shared/spec/methods.md section 1) in the main job. The
// upper level (SegmentWriter) turns the planner's setpoints into a stream of polynomial pieces in
// time, each spanning as many servo cycles as the tolerance allows; the lower level
// (lower_level/kontur_ll.c, freestanding C99) replays them one setpoint per cycle by forward
// differences. The format is docs/segments.md.
//
// How a piece is chosen: from the lower level's state at the piece's first cycle (for a
// continuation: the position, velocity and acceleration the previous piece ended with), the
// quintic in the cycle index that reaches the planner's exact position, velocity and acceleration
// at the piece's last cycle + 1 (Hermite conditions: continuous in position, velocity and
// acceleration from piece to piece). The writer runs the lower level's own code on each candidate
// and keeps the longest piece whose every setpoint lies within the tolerance of the planner's,
// then the fewest bytes that still do (a lower degree, binary32 values). So what a receiver makes
// is, bit for bit, what the writer checked.
#include <kontur/axes.hpp>
#include <kontur/machine.hpp>
#include <kontur/tolerances.hpp>
#include <array>
#include <kontur/trajectory/sampler.hpp>

#include <cstdint>
#include <deque>
#include <functional>
#include <istream>
#include <memory>
#include <ostream>
#include <string>
#include <vector>

namespace kontur::segments {

/// The limits of one axis the replayed setpoints must keep, as `kontur verify` measures them
/// (backward differences over the servo period).
struct AxisBounds {
  double max_velocity = 0.0;      ///< [mm/s] or [deg/s]
  double max_acceleration = 0.0;  ///< [mm/s^2] or [deg/s^2]
  double max_jerk = 0.0;          ///< [mm/s^3] or [deg/s^3]
};

/// How the stream is fitted.
struct SegmentOptions {
  /// Largest distance of a replayed tool point (X Y Z together) from the planner's [mm], and of
  /// each other axis [mm] or [deg]; the path speed gets this divided by the servo period [mm/s].
  double tolerance_mm = tolerances::segment_tolerance_mm;
  /// Longest piece [servo cycles] (1 .. 65535).
  int max_piece_cycles = tolerances::segment_max_piece_cycles;
  /// The limits of the layout's axes, in its order (empty: none). With them, no replayed
  /// setpoint's velocity, acceleration or jerk (backward differences) exceeds its limit where the
  /// planner's setpoints do not: a fit that would is cut shorter.
  std::vector<AxisBounds> bounds;
};

/// The bounds of `layout`'s axes on `machine`.
[[nodiscard]] std::vector<AxisBounds> axis_bounds(const Machine& machine, const AxisLayout& layout);

/// What a stream holds (the writer's, after finish(); the replay's, at the end).
struct SegmentStats {
  long setpoints = 0;        ///< setpoints it makes
  long pieces = 0;           ///< pieces (not counting the end record)
  long anchors = 0;          ///< pieces that set the whole state (the first, stops at rest, fallbacks)
  long float32_pieces = 0;   ///< pieces with binary32 values
  /// One-cycle anchors where no piece kept a limit the planner's setpoints keep (writer only).
  long limit_fallbacks = 0;
  std::uint64_t bytes = 0;   ///< bytes of the stream, header and end record included
  double max_error_mm = 0.0;        ///< largest distance of a replayed position from the planner's [mm] ([deg])
  double max_speed_error_mm_s = 0.0;  ///< the same for the path speed [mm/s]
  /// Pieces by degree 0..5 of their payload (a continuation of degree 2 carries no value).
  std::array<long, 6> by_degree{};
};

/// The upper level: a setpoint sink that writes the segment stream. Setpoints must carry their
/// derivatives (trajectory::Sampler with derivatives on; PipelineOptions::derivatives).
class SegmentWriter {
 public:
  /// Writes the header at once. Throws InputError for a tolerance below
  /// tolerances::segment_min_tolerance_mm or not finite, or a piece length out of range.
  SegmentWriter(std::ostream& out, double period_s, const AxisLayout& layout, SegmentOptions options = {});
  ~SegmentWriter();
  SegmentWriter(const SegmentWriter&) = delete;
  SegmentWriter& operator=(const SegmentWriter&) = delete;

  /// Takes the next setpoint (one per servo cycle, in order, from t = 0).
  void write(const trajectory::Setpoint& s);
  /// Fits what is held and writes the end record; nothing may be written after.
  void finish();
  /// What was written so far.
  [[nodiscard]] const SegmentStats& stats() const noexcept { return stats_; }

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  SegmentStats stats_;
};

/// The stream's header, as the lower level reads it.
struct SegmentHeader {
  AxisLayout layout = AxisLayout::xyz();  ///< the axes, in order
  double period_s = 0.0;                  ///< servo period [s]
  double tolerance_mm = 0.0;              ///< the position tolerance it was fitted to [mm]
  double speed_tolerance_mm_s = 0.0;      ///< the speed tolerance [mm/s]
};

/// Runs the lower level on the host over a stream read from `in` (`name` for messages): calls
/// `header` once, then `visit` for every setpoint (time accumulated by adding the period, as the
/// sampler does; positions, path speed and source line from the lower level). Throws InputError
/// naming the stream, the piece index and its byte offset for a damaged, truncated or reordered
/// stream (nothing after the damage is given).
SegmentStats replay_segments(std::istream& in, const std::string& name,
                             const std::function<void(const SegmentHeader&)>& header,
                             const std::function<void(const trajectory::Setpoint&)>& visit);

/// Newton's forward form to the power basis: binom(m, k) = sum_j newton_to_power[k][j] m^j
/// (Stirling numbers of the first kind over k!), k, j = 0..5.
inline constexpr std::array<std::array<double, 6>, 6> newton_to_power = {{
    {1, 0, 0, 0, 0, 0},
    {0, 1, 0, 0, 0, 0},
    {0, -1.0 / 2, 1.0 / 2, 0, 0, 0},
    {0, 2.0 / 6, -3.0 / 6, 1.0 / 6, 0, 0},
    {0, -6.0 / 24, 11.0 / 24, -6.0 / 24, 1.0 / 24, 0},
    {0, 24.0 / 120, -50.0 / 120, 35.0 / 120, -10.0 / 120, 1.0 / 120},
}};

/// The eight bytes a segment stream starts with.
inline constexpr char segment_stream_magic[9] = "KONTURSG";

}  // namespace kontur::segments
