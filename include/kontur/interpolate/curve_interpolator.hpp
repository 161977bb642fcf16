#pragma once
// Interpolation along one curve at the servo period (seed 004, methods.md section 3): each
// cycle the parameter u advances so that the tool moves a planned distance ds = V T along the
// curve. The seed's first- and second-order Taylor updates leave a feed fluctuation (the distance
// actually travelled differs from ds); Kontur's default corrects the Taylor prediction by Newton
// steps on the arc length of the step, so the distance equals ds to ~1e-12 relative.
#include <kontur/geometry/curve.hpp>
#include <kontur/geometry/length.hpp>

#include <optional>

namespace kontur {

/// How the parameter is advanced each cycle.
enum class Interpolator {
  taylor_first_order,   ///< u += ds / |C'(u)|  (seed 004)
  taylor_second_order,  ///< u += ds / |C'| - ds^2 (C'.C'') / (2 |C'|^4)  (seed 004)
  arc_length_exact,     ///< the parameter of the cumulative arc length, u(s), from an arc-length
                        ///< table, Newton started at the second-order prediction (default)
};

/// Stable name: "taylor1", "taylor2", "exact".
[[nodiscard]] const char* to_string(Interpolator kind) noexcept;

/// Steps one curve from u_min to u_max by distances ds [mm]. The constructor builds what the
/// mode needs (the arc-length table of the exact mode: it allocates); advance() is noexcept,
/// allocation-free and has a bounded number of iterations.
class CurveInterpolator {
public:
  /// @param curve  the path (must outlive the interpolator)
  explicit CurveInterpolator(const Curve& curve, Interpolator kind = Interpolator::arc_length_exact);

  /// Back to the start of the curve.
  void reset() noexcept;
  /// Advances by a step of length ds_mm [mm] (> 0) along the curve; stops at u_max. Returns the
  /// new parameter.
  double advance(double ds_mm) noexcept;
  /// Current parameter.
  [[nodiscard]] double u() const noexcept { return u_; }
  /// Arc length travelled so far [mm] (exact mode: to 1e-13 of the length; Taylor modes: the sum
  /// of the planned steps, which is what they aim at, not what they travel).
  [[nodiscard]] double s_mm() const noexcept { return s_; }
  /// True once u_max is reached.
  [[nodiscard]] bool at_end() const noexcept { return u_ >= curve_->u_max(); }
  /// Current point [mm].
  [[nodiscard]] Vec3 point() const noexcept { return curve_->point(u_); }
  /// The interpolator's mode.
  [[nodiscard]] Interpolator kind() const noexcept { return kind_; }

private:
  [[nodiscard]] double taylor_step(double ds) const noexcept;

  const Curve* curve_;
  Interpolator kind_;
  std::optional<ArcLengthTable> table_;  // exact mode only
  double u_;
  double s_ = 0.0;
};

/// Feed limit [mm/s] from the chord (bow-height) error: at radius `radius_mm` and servo period
/// `period_s`, V <= (2/T) sqrt(R^2 - (R - delta)^2). Infinite for a straight line.
[[nodiscard]] double chord_limited_feed(double radius_mm, double tolerance_mm, double period_s) noexcept;

/// Statistics of stepping a whole curve at a constant feed: the seed's feed fluctuation.
struct FeedFluctuation {
  long cycles = 0;                    ///< number of full cycles (the last, shorter one excluded)
  double max_relative = 0.0;          ///< max |arc / (V T) - 1| over the cycles
  double mean_relative = 0.0;         ///< mean of |arc / (V T) - 1|
  double max_chord_error_mm = 0.0;    ///< largest bow height of a cycle's chord [mm]
  double final_gap_mm = 0.0;          ///< distance of the last setpoint before the end to the end point [mm]
};

/// Steps `curve` at feed `feed_mm_s` [mm/s] and period `period_s` [s] with the given interpolator
/// and measures the arc length of every cycle (adaptive Gauss-Kronrod, independent of the
/// interpolator) against V T, and the bow height of every cycle's chord.
[[nodiscard]] FeedFluctuation measure_feed_fluctuation(const Curve& curve, Interpolator kind, double feed_mm_s,
                                                       double period_s);

}  // namespace kontur
