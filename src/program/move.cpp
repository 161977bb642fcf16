#include <kontur/geometry/length.hpp>
#include <kontur/program/move.hpp>
#include <kontur/tolerances.hpp>
#include <cmath>

namespace kontur::program {

Move move_along(std::shared_ptr<const Curve> curve, double feed_mm_s, bool exact_stop, long source_line) {
  Move m;
  m.curve = std::move(curve);
  m.feed_mm_s = feed_mm_s;
  m.exact_stop = exact_stop;
  m.source_line = source_line;
  m.type = "curve";
  m.length_mm = m.curve ? length(*m.curve) : 0.0;
  return m;
}

ExtraAxes extra_at(const Move& m, double s_mm) noexcept {
  return m.length_mm > 0.0 ? extra_between(m.extra_start, m.extra_end, s_mm / m.length_mm) : m.extra_start;
}

double path_length(double tool_length_mm, const ExtraAxes& from, const ExtraAxes& to, bool& tool_still) noexcept {
  tool_still = false;
  if (tool_length_mm > tolerances::extra_axes_tool_still_mm || from == to) return tool_length_mm;
  tool_still = true;
  double linear = 0.0, rotary = 0.0;  // U V W [mm], A B C [deg]
  for (std::size_t i = 0; i < 3; ++i) rotary += (to[i] - from[i]) * (to[i] - from[i]);
  for (std::size_t i = 3; i < 6; ++i) linear += (to[i] - from[i]) * (to[i] - from[i]);
  return linear > 0.0 ? std::sqrt(linear) : std::sqrt(rotary);
}

}  // namespace kontur::program
