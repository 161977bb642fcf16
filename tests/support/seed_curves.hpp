#pragma once
// The curves of the seed documents (methods.md sections 1-3), shared by tests and benchmarks.
#include <kontur/geometry/nurbs.hpp>

namespace kontur::testing {

/// True lengths [mm] of the seed's examples 1 and 2 (methods.md section 2).
inline constexpr double seed_true_length_1 = 249.463109910705;
inline constexpr double seed_true_length_2 = 252.584228618995;

/// Seed 000/002 example `which` (1 or 2): cubic, knots (0,0,0,0,0.5,1,1,1,1), five points.
inline NurbsData seed_example(int which) {
  NurbsData d;
  d.degree = 3;
  d.knots = {0, 0, 0, 0, 0.5, 1, 1, 1, 1};
  if (which == 1)
    d.points = {{-100, -60, 0}, {-100, 0, 0}, {-40, 70, 0}, {60, 90, 0}, {30, 120, 0}};
  else
    d.points = {{0, 0, 0}, {-9.5, 115.8, 0}, {60, -35.8, 0}, {129.5, 115.8, 0}, {120, 0, 0}};
  return d;
}

/// Seed 004's G06.2 example as printed: 5 points, 8 knots, 9 weights (inconsistent).
inline NurbsData seed_004_inconsistent() {
  NurbsData d;
  d.degree = 3;
  d.points = {{0, 0, 1}, {25, 30, 6}, {50, 50, 16}, {65, 60, 22}, {77, 70, 30}};
  d.knots = {0, 0, 0, 0, 0.45, 0.636, 0.742, 1};
  d.weights = {1.6, 1.7, 0.7, 1.25, 0.6, 0.85, 1, 1.2, 1.2};
  return d;
}

}  // namespace kontur::testing
