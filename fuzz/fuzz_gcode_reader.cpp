// libFuzzer target for the G-code reader: any bytes are a program; reading it must end with blocks
// or an InputError, never a crash, hang, leak, sanitizer report, or a non-finite point or length.
// Every dialect is fuzzed: the input's length modulo 8 picks one (7: detected from the text), so
// that every seed stays a whole program and a mutation that changes the length changes the dialect.
// Built with clang -fsanitize=fuzzer,address,undefined by fuzz/CMakeLists.txt (docs/gcode.md).
#include <kontur/error.hpp>
#include <kontur/gcode/reader.hpp>
#include <kontur/geometry/length.hpp>
#include <kontur/geometry/span_polynomial.hpp>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <optional>
#include <string>
#include <variant>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::string text(reinterpret_cast<const char*>(data), size);
  try {
    kontur::gcode::ReaderOptions options;
    options.max_loop_iterations = 10000;  // O-word loops: enough to explore, small enough not to time out
    const std::size_t pick = size % 8;
    if (pick < kontur::gcode::all_dialects.size()) options.dialect = kontur::gcode::all_dialects[pick];
    kontur::gcode::Reader reader("fuzz.ngc", std::move(text), options);
    kontur::gcode::Block b;
    long blocks = 0;
    while (reader.next(b) && ++blocks < 200000) {
      if (!b.start.allFinite() || !b.end.allFinite()) std::abort();
      // Every length must be finite. NURBS lengths are integrated to 1e-6 here instead of the 1e-13
      // of Block::length_mm: at 1e-13 a rational curve with a large weight ratio (R155 next to R1)
      // takes 0.2 s in a release build and over 10 s under the sanitizers, a libFuzzer timeout
      // that is the cost of kontur::gauss_kronrod_length, not a hang of the reader.
      if (blocks < 2000) {
        std::optional<double> len;
        if (const auto* n = std::get_if<kontur::NurbsCurve>(&b.geometry))
          len = kontur::gauss_kronrod_length(kontur::SpanPolynomialCurve(*n), 1e-6).length_mm;
        else
          len = b.length_mm();
        if (len && !std::isfinite(*len)) std::abort();
      }
      if (const kontur::Curve* c = b.curve()) {
        const kontur::Vec3 mid = c->point(0.5 * (c->u_min() + c->u_max()));
        if (!mid.allFinite()) std::abort();
      }
    }
  } catch (const kontur::InputError&) {
    // a malformed program: the expected outcome for most inputs
  }
  return 0;
}
