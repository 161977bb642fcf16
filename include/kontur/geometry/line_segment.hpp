#pragma once
// A straight segment as a Curve: C(u) = start + u (end - start), u in [0, 1].
#include <kontur/geometry/curve.hpp>

namespace kontur {

/// Straight line from `start` to `end` [mm]; a zero-length segment is allowed (a point).
class LineSegment final : public Curve {
public:
  LineSegment(const Vec3& start, const Vec3& end) noexcept : start_(start), end_(end) {}
  [[nodiscard]] double u_min() const noexcept override { return 0.0; }
  [[nodiscard]] double u_max() const noexcept override { return 1.0; }
  [[nodiscard]] Derivatives derivatives(double u, int order) const noexcept override;
  [[nodiscard]] std::vector<double> breakpoints() const override { return {0.0, 1.0}; }
  [[nodiscard]] int polynomial_degree() const noexcept override { return 1; }
  [[nodiscard]] double constant_speed() const noexcept override { return length_mm(); }
  /// Start point [mm].
  [[nodiscard]] const Vec3& start() const noexcept { return start_; }
  /// End point [mm].
  [[nodiscard]] const Vec3& end() const noexcept { return end_; }
  /// Length [mm].
  [[nodiscard]] double length_mm() const noexcept { return (end_ - start_).norm(); }

private:
  Vec3 start_, end_;
};

}  // namespace kontur
