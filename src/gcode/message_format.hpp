#pragma once
// Internal: how numbers, points and G codes are written in messages (the same in every dialect's
// errors, so that a message names the word as the program wrote it).
#include <kontur/geometry/curve.hpp>

#include <fmt/format.h>

#include <string>

namespace kontur::gcode::detail {

/// "G1", "G6.2", or with `leading_zero` "G01", "G06.2", from a code times 10.
inline std::string g_name(int g10, bool leading_zero = false) {
  const int whole = g10 / 10, tenth = g10 % 10;
  const char* zero = leading_zero && whole < 10 ? "0" : "";
  if (tenth == 0) return fmt::format("G{}{}", zero, whole);
  return fmt::format("G{}{}.{}", zero, whole, tenth);
}

/// A value with 6 significant digits, no "-0".
inline std::string num(double v) {
  if (v == 0.0) v = 0.0;
  return fmt::format("{:.6g}", v);
}
/// "(x, y, z)".
inline std::string point_text(const Vec3& p) { return fmt::format("({}, {}, {})", num(p.x()), num(p.y()), num(p.z())); }

}  // namespace kontur::gcode::detail
