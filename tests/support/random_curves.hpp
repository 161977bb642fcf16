#pragma once
// Seeded random NURBS for property tests and benchmarks. The seed and the count come from the
// environment (KONTUR_TEST_SEED, KONTUR_TEST_COUNT) so that CI runs a few hundred cases and a
// developer can run millions; a failing case prints its seed and index.
#include <kontur/geometry/nurbs.hpp>

#include <cstdint>
#include <cstdlib>
#include <random>
#include <string>

namespace kontur::testing {

/// Value of an integer environment variable, or `fallback` if unset or not a number.
inline std::uint64_t env_or(const char* name, std::uint64_t fallback) {
  const char* v = std::getenv(name);
  if (v == nullptr || *v == '\0') return fallback;
  char* end = nullptr;
  const unsigned long long x = std::strtoull(v, &end, 10);
  return (end != nullptr && *end == '\0') ? static_cast<std::uint64_t>(x) : fallback;
}

/// Base seed of the random tests (KONTUR_TEST_SEED, default 20261122).
inline std::uint64_t test_seed() { return env_or("KONTUR_TEST_SEED", 20261122); }
/// Number of random cases (KONTUR_TEST_COUNT, default `fallback`).
inline std::uint64_t test_count(std::uint64_t fallback) { return env_or("KONTUR_TEST_COUNT", fallback); }

/// Options of the random curve generator.
struct RandomCurveOptions {
  int min_degree = 1, max_degree = 7;
  int min_points = 4, max_points = 60;
  bool rational = true;        ///< random weights in [0.2, 5]
  double size_mm = 100.0;      ///< control points in a cube of this size [mm]
  bool repeated_knots = true;  ///< inner knots repeated up to degree times now and then
  /// Knot vector starts at a random u0 in [-10, 10] (else at 0). An offset far above the range
  /// costs parameter resolution: a span of width du at u is resolved to eps |u| / du only.
  bool offset_knots = true;
};

/// A random valid NURBS: random degree, points, non-uniform clamped knots (on a random
/// parameter interval), optional weights. The same (seed, index) gives the same curve.
inline NurbsData random_nurbs(std::uint64_t seed, std::uint64_t index, const RandomCurveOptions& o = {}) {
  std::mt19937_64 rng(seed * 0x9E3779B97F4A7C15ULL + index);
  auto uni = [&](double a, double b) { return std::uniform_real_distribution<double>(a, b)(rng); };
  auto uint = [&](int a, int b) { return std::uniform_int_distribution<int>(a, b)(rng); };
  NurbsData d;
  d.degree = uint(o.min_degree, o.max_degree);
  const int n_points = uint(std::max(o.min_points, d.degree + 1), std::max(o.max_points, d.degree + 1));
  for (int i = 0; i < n_points; ++i) d.points.emplace_back(uni(-0.5, 0.5) * o.size_mm, uni(-0.5, 0.5) * o.size_mm, uni(-0.5, 0.5) * o.size_mm);
  if (o.rational)
    for (int i = 0; i < n_points; ++i) d.weights.push_back(std::exp(uni(std::log(0.2), std::log(5.0))));
  const double u0 = o.offset_knots ? uni(-10.0, 10.0) : 0.0, range = std::exp(uni(std::log(0.1), std::log(100.0)));
  const int inner = n_points - d.degree - 1;
  std::vector<double> in;
  while (static_cast<int>(in.size()) < inner) {
    const double k = u0 + range * uni(0.02, 0.98);
    int rep = 1;
    if (o.repeated_knots && uni(0.0, 1.0) < 0.15) rep = uint(1, d.degree);
    for (int r = 0; r < rep && static_cast<int>(in.size()) < inner; ++r) in.push_back(k);
  }
  std::sort(in.begin(), in.end());
  d.knots.assign(static_cast<std::size_t>(d.degree + 1), u0);
  d.knots.insert(d.knots.end(), in.begin(), in.end());
  d.knots.insert(d.knots.end(), static_cast<std::size_t>(d.degree + 1), u0 + range);
  return d;
}

/// "seed S index I" for failure messages.
inline std::string describe_case(std::uint64_t seed, std::uint64_t index) {
  return "KONTUR_TEST_SEED=" + std::to_string(seed) + " case " + std::to_string(index);
}

}  // namespace kontur::testing
