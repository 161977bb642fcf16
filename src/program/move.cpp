#include <kontur/geometry/length.hpp>
#include <kontur/program/move.hpp>

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

}  // namespace kontur::program
