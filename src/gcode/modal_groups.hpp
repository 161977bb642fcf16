#pragma once
// Internal: the G and M codes the executor knows, by modal group (LinuxCNC's numbering where it
// has one), as tables (modal_groups.cpp), and the classification of one block's codes into their
// groups with the checks every control makes: unknown codes, codes Kontur deliberately does not
// run, two codes of one group. Dialect-neutral: a dialect hands codes as numbers (times 10 for G).
#include "block_words.hpp"
#include "diagnostics.hpp"

#include <array>

namespace kontur::gcode::detail {

/// Modal groups of G codes.
enum GGroup : int {
  g_nonmodal = 0, g_motion = 1, g_plane = 2, g_distance = 3, g_arc_distance = 4, g_feed_mode = 5, g_units = 6,
  g_cutter = 7, g_tool_length = 8, g_retract = 10, g_coordinate = 12, g_path = 13, g_spindle_mode = 14,
  g_lathe = 15, g_spline_end = 16, g_group_count = 17
};
/// Modal groups of M codes.
enum MGroup : int { m_stop = 4, m_io = 5, m_tool = 6, m_spindle = 7, m_coolant = 8, m_override = 9, m_other = 11,
                    m_group_count = 12 };

/// Motion modes that are not G codes (block keywords), and G80 (no motion).
inline constexpr int motion_cip = 10000;
inline constexpr int motion_conic = 10001;
inline constexpr int motion_ct = 10002;  // Sinumerik CT: an arc tangent to the previous move
inline constexpr int motion_none = 800;  // G80

/// What the tables say about a code.
struct CodeInfo {
  int group = -1;                     ///< modal group; -1 unknown, -2 deliberately not supported, -3 refused
                                      ///< even among the M codes otherwise ignored (M97-M99)
  const char* unsupported = nullptr;  ///< the feature not supported (group -2)
};
/// The G code `g10` (times 10: G6.2 is 62).
[[nodiscard]] CodeInfo g_code_info(int g10) noexcept;
/// The M code `m`.
[[nodiscard]] CodeInfo m_code_info(int m) noexcept;

/// True for the drilling cycles G73, G81, G82, G83 and the Fanuc family's G84, G85, G86, G89 (times 10).
[[nodiscard]] constexpr bool is_canned_cycle(int motion) noexcept {
  return motion == 730 || motion == 810 || motion == 820 || motion == 830 || motion == 840 || motion == 850 ||
         motion == 860 || motion == 890;
}
/// True for the cycles only the Fanuc family's rules expand (DialectRules::fanuc_cycles).
[[nodiscard]] constexpr bool is_fanuc_cycle(int g10) noexcept {
  return g10 == 840 || g10 == 850 || g10 == 860 || g10 == 890;
}

/// The codes of one block by group: the code (G times 10) and its column, -1 where none.
struct BlockCodes {
  std::array<int, g_group_count> g{};
  std::array<int, g_group_count> g_column{};
  std::array<int, m_group_count> m{};
  bool coolant_mist_and_flood = false;  ///< M7 and M8 in one block
  /// M codes the tables do not know (machine-specific: M25, M40, M101 ...) and their columns: they
  /// do not move the axes; the executor warns once per code and ignores them.
  std::array<int, 8> ignored_m{};
  std::array<int, 8> ignored_m_column{};
  int ignored_m_count = 0;

  [[nodiscard]] int code(GGroup group) const noexcept { return g[static_cast<std::size_t>(group)]; }
  [[nodiscard]] int column(GGroup group) const noexcept { return g_column[static_cast<std::size_t>(group)]; }
  [[nodiscard]] int m_code(MGroup group) const noexcept { return m[static_cast<std::size_t>(group)]; }
};

/// Sorts the block's G and M codes into their groups; throws at an unknown or unsupported G code
/// or at two codes of one group (except "G80 G0" of CAM safety lines, and M7 with M8). M codes not
/// in the tables (machine-specific, user M100-M199) are listed in ignored_m. With `fanuc_cycles`
/// G84, G85, G86 and G89 are motion codes (group 1) instead of refused.
[[nodiscard]] BlockCodes classify_codes(const Words& w, const Diagnostics& diag, bool fanuc_cycles = false);

}  // namespace kontur::gcode::detail
