#pragma once
// Internal: the words of one block as every dialect hands them to the executor: a value per
// letter A..Z, the G and M codes in the order written, the indexed points I1= .. K3= and the
// block keyword (CIP, CONIC) of Kontur's circle and conic blocks. How a dialect spells them
// (comments, expressions, parameters, line numbers) is gone by then.
#include <array>
#include <cstdint>

namespace kontur::gcode::detail {

/// Block keywords of the Sinumerik style (and Kontur's conic); ct: Sinumerik's arc tangent to the
/// previous move.
enum class Keyword : std::uint8_t { none, cip, conic, ct };

/// A programmable frame instruction (Sinumerik TRANS / ROT / SCALE / MIRROR and their additive
/// A... forms): the block holds nothing else; its X Y Z give the offsets, angles, factors or the
/// mirrored axes, and frame_rpl the rotation in the plane (RPL=).
enum class FrameOp : std::uint8_t { none, trans, atrans, rot, arot, scale, ascale, mirror, amirror };

/// The words of one block.
struct Words {
  std::array<double, 26> value{};     // by letter A..Z
  std::array<int, 26> column{};       // raw column of the letter
  std::uint32_t present = 0;          // bit (letter - 'A')
  int g_count = 0;
  std::array<int, 16> g{};            // G codes times 10 (G6.2 -> 62)
  std::array<int, 16> g_column{};
  std::array<std::uint8_t, 16> g_leading_zero{};  // written with a leading zero (G06.2, G01)
  int m_count = 0;
  std::array<int, 8> m{};
  std::array<int, 8> m_column{};
  std::array<std::array<double, 3>, 3> indexed{};  // [point 0..2][I J K] of I1= .. K3=
  std::array<std::array<int, 3>, 3> indexed_column{};
  std::uint16_t indexed_present = 0;  // bit 3 * point + axis
  Keyword keyword = Keyword::none;
  int keyword_column = 0;
  long n_number = -1;
  int first_column = 0;  // raw column of the first word (0 if none)
  // Per-word distance overrides (Sinumerik X=AC(..) / X=IC(..)): bit (letter - 'A').
  std::uint32_t absolute_words = 0;
  std::uint32_t incremental_words = 0;
  FrameOp frame_op = FrameOp::none;
  int frame_column = 0;
  // Polar coordinates (Sinumerik AP= angle [deg], RP= radius) in the plane about the pole, and the
  // pole's definition (G110 relative to the position, G111 absolute, G112 relative to the pole:
  // pole_g 110 / 111 / 112, with X Y Z as the pole).
  std::uint8_t polar = 0;  // bit 0: AP given, bit 1: RP given
  double polar_angle = 0.0, polar_radius = 0.0;
  int polar_column = 0;
  int pole_g = 0;
  // Sinumerik AR=: the arc's opening angle [deg], with the end point or with the centre.
  bool has_arc_angle = false;
  double arc_angle = 0.0;
  double frame_rpl = 0.0;
  bool frame_has_rpl = false;

  void clear() noexcept {
    present = 0;
    g_count = 0;
    m_count = 0;
    indexed_present = 0;
    keyword = Keyword::none;
    n_number = -1;
    first_column = 0;
    absolute_words = 0;
    incremental_words = 0;
    frame_op = FrameOp::none;
    frame_has_rpl = false;
    polar = 0;
    polar_column = 0;
    pole_g = 0;
    has_arc_angle = false;
  }
  [[nodiscard]] bool has(char letter) const noexcept { return (present >> (letter - 'A')) & 1u; }
  [[nodiscard]] double get(char letter) const noexcept { return value[static_cast<std::size_t>(letter - 'A')]; }
  [[nodiscard]] int col(char letter) const noexcept { return column[static_cast<std::size_t>(letter - 'A')]; }
  [[nodiscard]] bool has_indexed(int point, int axis) const noexcept {
    return (indexed_present >> (3 * point + axis)) & 1u;
  }
  [[nodiscard]] bool empty() const noexcept {
    return present == 0 && g_count == 0 && m_count == 0 && indexed_present == 0 && keyword == Keyword::none &&
           frame_op == FrameOp::none && polar == 0 && pole_g == 0;
  }
  /// The word `letter` is absolute (AC) or incremental (IC) whatever the modal distance mode
  /// (`modal_absolute`) says.
  [[nodiscard]] bool absolute(char letter, bool modal_absolute) const noexcept {
    const std::uint32_t bit = 1u << (letter - 'A');
    if (absolute_words & bit) return true;
    if (incremental_words & bit) return false;
    return modal_absolute;
  }

  // Builders for a dialect (and for tests that feed the executor directly).
  /// Sets the value word `letter` (not G or M) at `column`.
  void set(char letter, double v, int col = 1) noexcept {
    const auto bit = static_cast<std::size_t>(letter - 'A');
    present |= 1u << bit;
    value[bit] = v;
    column[bit] = col;
  }
  /// Appends a G code given times 10 (G6.2 -> 62); false when the block has no room left.
  bool add_g(int code10, int col = 1, bool leading_zero = false) noexcept {
    if (g_count == static_cast<int>(g.size())) return false;
    const auto i = static_cast<std::size_t>(g_count++);
    g[i] = code10;
    g_column[i] = col;
    g_leading_zero[i] = leading_zero ? 1 : 0;
    return true;
  }
  /// Appends an M code; false when the block has no room left.
  bool add_m(int code, int col = 1) noexcept {
    if (m_count == static_cast<int>(m.size())) return false;
    const auto i = static_cast<std::size_t>(m_count++);
    m[i] = code;
    m_column[i] = col;
    return true;
  }
  /// Sets the indexed word I/J/K (axis 0..2) of point 0..2 (I1= is point 0, axis 0).
  void set_indexed(int point, int axis, double v, int col = 1) noexcept {
    indexed[static_cast<std::size_t>(point)][static_cast<std::size_t>(axis)] = v;
    indexed_column[static_cast<std::size_t>(point)][static_cast<std::size_t>(axis)] = col;
    indexed_present = static_cast<std::uint16_t>(indexed_present | (1u << (3 * point + axis)));
  }
};

}  // namespace kontur::gcode::detail
