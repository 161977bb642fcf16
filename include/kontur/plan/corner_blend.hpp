#pragma once
// Corner blending within the G64 path tolerance (issue 5): a streaming stage between the program's
// moves and the planner. At a corner between two lines (G0 / G1) that is not tangent, where the
// first move does not stop exactly (G61 / G61.1) and the tolerance is positive, both lines are
// trimmed by a distance d and a quintic Bezier joins them: control points Q0, Q1, Q2 equally spaced
// on the incoming line and Q3, Q4, Q5 on the outgoing one, so the blend is tangent to both lines
// and has zero curvature at both ends (curvature-continuous, G2). d is the largest distance for
// which the blend stays within the tolerance of the two programmed lines, and at most 45 % of
// each line's length (a line between two blended corners keeps a straight middle).
// `kontur run`, `kontur verify` and the tests use the same stage, so they build the same path.
#include <kontur/geometry/curve.hpp>
#include <kontur/gcode/block.hpp>
#include <kontur/machine.hpp>
#include <kontur/plan/motion_planner.hpp>

#include <cstdint>
#include <optional>
#include <vector>

namespace kontur::plan {

/// The blend curve of a corner P between the incoming direction t1 and the outgoing t2 (unit
/// vectors), trimmed by d [mm] on each line: B(u) = P + d (alpha(u) t1 + beta(u) t2), u in [0, 1],
/// with alpha = (-3 + 5u - 5u^4 + 3u^5) / 3 and beta = (10u^3 - 10u^4 + 3u^5) / 3: the quintic
/// Bezier with Q_k = P - d (1 - k/3) t1 (k = 0..2) and Q_k = P + d (k - 2) / 3 t2 (k = 3..5).
/// B(0) = P - d t1, B(1) = P + d t2, B' = 5d/3 t1 and 5d/3 t2 there, B'' = 0 at both ends (exactly:
/// the polynomials have integer coefficients).
class CornerBlendCurve final : public Curve {
public:
  CornerBlendCurve(const Vec3& corner, const Vec3& t1, const Vec3& t2, double d_mm) noexcept
      : corner_(corner), t1_(t1), t2_(t2), d_(d_mm) {}
  [[nodiscard]] double u_min() const noexcept override { return 0.0; }
  [[nodiscard]] double u_max() const noexcept override { return 1.0; }
  [[nodiscard]] Derivatives derivatives(double u, int order) const noexcept override;
  [[nodiscard]] std::vector<double> breakpoints() const override { return {0.0, 1.0}; }
  /// The programmed corner point P [mm].
  [[nodiscard]] const Vec3& corner() const noexcept { return corner_; }
  /// The trim distance d on each line [mm].
  [[nodiscard]] double trim_mm() const noexcept { return d_; }

private:
  Vec3 corner_, t1_, t2_;
  double d_;
};

/// Largest distance of the blend with d = 1 mm from the two lines of the corner, for the turn
/// between unit directions t1 and t2 [mm per mm of d] (dense sampling and a golden-section search
/// around the largest sample). The deviation of a blend is d times this.
[[nodiscard]] double unit_blend_deviation(const Vec3& t1, const Vec3& t2);

/// The G64 tolerance at the end of block `b` [mm]: its P word if given, else the machine's
/// path tolerance; 0 under G61 / G61.1 (no blending).
[[nodiscard]] double corner_tolerance(const gcode::Block& b, const Machine& machine);

/// A move the blender hands on.
struct BlendedMove {
  MoveInput move;             ///< the move to plan (a trimmed line, a blend, or a move as given)
  std::uint64_t tag = 0;      ///< the caller's tag of the block it comes from (a blend: the outgoing block)
  bool blend = false;         ///< a corner blend (the rest below is set only then)
  Vec3 before = Vec3::Zero(); ///< start of the incoming programmed line [mm]
  Vec3 corner = Vec3::Zero(); ///< the programmed corner [mm]
  Vec3 after = Vec3::Zero();  ///< end of the outgoing programmed line [mm]
  double tolerance_mm = 0.0;  ///< the G64 tolerance the blend keeps [mm]
};

/// The streaming blender: holds back one line move until the next move is known.
class CornerBlender {
public:
  /// `enabled` false: every move is handed on as given (`kontur run --no-blend`). With a machine
  /// (kept by pointer), a corner is blended only where that is estimated to be faster: the blend of
  /// length ~2d at its speed cap against stopping at the corner and starting again within d on
  /// each side at the smallest axis jerk (tiny blends on very short lines bend so sharply that
  /// the jerk of the curvature change makes them slower than the stop).
  explicit CornerBlender(bool enabled = true, const Machine* machine = nullptr) noexcept
      : enabled_(enabled), machine_(machine) {}
  /// The next move of the program; `tolerance_mm` is the tolerance of the corner at its end
  /// (corner_tolerance of its block; 0 = no blend). The moves that are ready are appended to `out`,
  /// in order. A blend carries the source line, feed and tag of the outgoing move.
  void push(const MoveInput& move, double tolerance_mm, std::uint64_t tag, std::vector<BlendedMove>& out);
  /// A dwell or the end of the program: the move held back is handed on.
  void flush(std::vector<BlendedMove>& out);

private:
  struct Held {
    MoveInput move;
    Vec3 start = Vec3::Zero();       // where it starts now (trimmed by the blend before) [mm]
    Vec3 from = Vec3::Zero(), to = Vec3::Zero();  // the programmed line [mm]
    double tolerance_mm = 0.0;
    std::uint64_t tag = 0;
  };
  bool enabled_;
  const Machine* machine_;
  std::optional<Held> held_;
};

}  // namespace kontur::plan
