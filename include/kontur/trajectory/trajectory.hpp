#pragma once
// The trajectory: the planner's output, a queue of time segments. Each segment spans a time, has
// its motion law s(t) (an S-curve profile) and the piece of a move it runs along (curve, arc-length
// table, parameter and distance range), with dwells before or after it. The planner appends
// segments once the look-ahead has made them final; the Sampler (trajectory/sampler.hpp) reads
// them at the servo period and only marks what it has passed; the planner frees those
// (reclaim()), so the per-cycle path never frees memory.
#include <cstddef>
#include <deque>
#include <kontur/geometry/curve.hpp>
#include <kontur/geometry/length.hpp>
#include <kontur/program/move.hpp>
#include <kontur/trajectory/path_profile.hpp>
#include <memory>

namespace kontur::trajectory {

/// A stretch of time with one motion law along one piece of one move.
struct Segment {
  std::shared_ptr<const Curve> curve;           ///< the move's path [mm]
  std::shared_ptr<const ArcLengthTable> table;  ///< its arc-length table (s(u), u(s))
  double u0 = 0.0, u1 = 0.0;                    ///< parameter range of the piece
  double s0_mm = 0.0, s1_mm = 0.0;              ///< arc-length range of the piece on the curve [mm]
  /// The extra axes A B C [deg] U V W [mm] at the move's start and end, and the move's path length
  /// [mm] (or [deg]): they move linearly with the distance along the move (program::extra_at).
  ExtraAxes extra_start{}, extra_end{};
  double move_length_mm = 0.0;
  /// The tool point stands (only extra axes move): s runs over the extra axes' distance, u stays.
  bool tool_still = false;
  bool moves_extra = false;  ///< extra_start != extra_end
  /// The extra axes at distance `s_mm` along the move: exactly extra_start at 0 and extra_end at the end.
  [[nodiscard]] ExtraAxes extra_at(double s_mm) const noexcept {
    if (!moves_extra || !(move_length_mm > 0.0)) return extra_start;
    return extra_between(extra_start, extra_end, s_mm / move_length_mm);
  }
  program::MoveId move = program::no_move;      ///< the move it belongs to
  long source_line = 0;                         ///< that move's line
  double hold_before_s = 0.0;                   ///< dwell before the motion (a dwell ahead of the first move) [s]
  long hold_before_line = 0;                    ///< line of that dwell
  program::MoveId hold_before_move = program::no_move;  ///< the move its setpoints count to (the one before it)
  double hold_after_s = 0.0;                            ///< dwell after the motion [s]
  long hold_after_line = 0;                             ///< line of that dwell
  /// s(t) [mm] of the chain of pieces this one belongs to (pieces joined smoothly share one
  /// profile, so the speed changes across their junctions); this piece runs through its window.
  PathProfile profile;
  double window_t0_s = 0.0;   ///< start of the piece's window in the profile's time [s]
  double window_t1_s = 0.0;   ///< end of the window [s]
  double window_s0_mm = 0.0;  ///< the profile's distance at the window's start [mm]
  /// Speed at the start of its window [mm/s] (inside a chain it need not be 0).
  [[nodiscard]] double start_velocity() const noexcept { return profile.sample(window_t0_s).v; }
  /// Duration of the motion: the window [s].
  [[nodiscard]] double motion_s() const noexcept { return window_t1_s - window_t0_s; }
  /// Duration: hold before, motion, hold after [s].
  [[nodiscard]] double duration() const noexcept { return hold_before_s + motion_s() + hold_after_s; }
};

/// The queue of segments between the planner and the sampler. Segments are numbered from 0 in
/// the order appended (absolute indices, unchanged by reclaim()).
class Trajectory {
 public:
  // Planning side (may allocate and free).
  /// Appends a final segment.
  void append(Segment s) { segments_.push_back(std::move(s)); }
  /// No segment will follow.
  void close() noexcept { closed_ = true; }
  /// Frees the segments the sampler has passed.
  void reclaim() {
    while (first_ < done_before_ && !segments_.empty()) {
      segments_.pop_front();
      ++first_;
    }
  }

  // Sampling side: noexcept, allocation-free, never frees.
  /// True once close() was called: the segment before end_index() is the last.
  [[nodiscard]] bool closed() const noexcept { return closed_; }
  /// One past the index of the last segment appended.
  [[nodiscard]] std::size_t end_index() const noexcept { return first_ + segments_.size(); }
  /// Segment `index` (not reclaimed: index >= the argument of the last mark_done_before).
  [[nodiscard]] const Segment& segment(std::size_t index) const noexcept { return segments_[index - first_]; }
  /// The sampler no longer needs the segments before `index`.
  void mark_done_before(std::size_t index) noexcept { done_before_ = index; }
  /// Segments held (appended and not reclaimed).
  [[nodiscard]] std::size_t held() const noexcept { return segments_.size(); }

 private:
  std::deque<Segment> segments_;
  std::size_t first_ = 0;        // index of segments_.front()
  std::size_t done_before_ = 0;  // the sampler is past the segments before this index
  bool closed_ = false;
};

}  // namespace kontur::trajectory
