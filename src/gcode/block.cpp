#include <kontur/gcode/block.hpp>
#include <kontur/geometry/length.hpp>
#include <kontur/geometry/span_polynomial.hpp>

namespace kontur::gcode {

const char* to_string(BlockType type) noexcept {
  switch (type) {
    case BlockType::rapid: return "rapid";
    case BlockType::line: return "line";
    case BlockType::arc: return "arc";
    case BlockType::helix: return "helix";
    case BlockType::circle_3d: return "circle_3d";
    case BlockType::nurbs: return "nurbs";
    case BlockType::bezier: return "bezier";
    case BlockType::conic: return "conic";
    case BlockType::dwell: return "dwell";
  }
  return "?";
}

const Curve* Block::curve() const noexcept {
  if (const auto* l = std::get_if<LineSegment>(&geometry)) return l;
  if (const auto* a = std::get_if<HelixArc>(&geometry)) return a;
  if (const auto* n = std::get_if<NurbsCurve>(&geometry)) return n;
  if (const auto* c = std::get_if<ConicArc>(&geometry)) return c;
  return nullptr;
}

std::optional<double> Block::length_mm() const {
  if (const auto* l = std::get_if<LineSegment>(&geometry)) return l->length_mm();
  if (const auto* a = std::get_if<HelixArc>(&geometry)) return a->length_mm();
  if (const auto* n = std::get_if<NurbsCurve>(&geometry)) {
    const SpanPolynomialCurve spans(*n);  // faster to integrate than the NURBS itself
    return gauss_kronrod_length(spans).length_mm;
  }
  if (const auto* c = std::get_if<ConicArc>(&geometry)) return gauss_kronrod_length(*c).length_mm;
  if (type == BlockType::dwell) return 0.0;
  return std::nullopt;
}

}  // namespace kontur::gcode
