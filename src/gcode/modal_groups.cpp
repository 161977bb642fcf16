// The tables of G and M codes by modal group, and the classification of a block's codes.
#include "modal_groups.hpp"

#include "message_format.hpp"

#include <algorithm>
#include <array>
#include <iterator>

namespace kontur::gcode::detail {
namespace {

struct GCodeEntry {
  int g10;                            // G code times 10
  int group;                          // GGroup, or -2: deliberately not supported
  const char* unsupported = nullptr;  // the feature, for group -2
};

constexpr const char* spindle_sync = "spindle-synchronised motion (G33 threading, G33.1 rigid tapping)";
constexpr const char* g85_g89 = "canned cycles G85-G89 (only G73, G81, G82 and G83 are expanded)";
constexpr const char* probing = "probing G38.x";
constexpr const char* uvw_planes = "the UVW planes G17.1/G18.1/G19.1";

// Sorted by code.
constexpr GCodeEntry g_codes[] = {
    {0, g_motion},        {10, g_motion},      {20, g_motion},       {24, g_motion},       {30, g_motion},
    {34, g_motion},       {40, g_nonmodal},    {50, g_motion},       {51, g_motion},       {52, g_motion},
    {53, g_spline_end},   {62, g_motion},
    {70, -2, "lathe diameter mode G7 (X would be a diameter)"},
    {80, g_lathe},        {100, g_nonmodal},   {170, g_plane},
    {171, -2, uvw_planes}, {180, g_plane},     {181, -2, uvw_planes}, {190, g_plane},      {191, -2, uvw_planes},
    {200, g_units},       {210, g_units},      {280, g_nonmodal},    {281, g_nonmodal},    {300, g_nonmodal},
    {301, g_nonmodal},    {330, -2, spindle_sync}, {331, -2, spindle_sync},
    {382, -2, probing},   {383, -2, probing},  {384, -2, probing},   {385, -2, probing},
    {400, g_cutter},      {410, g_cutter},     {411, g_cutter},     {420, g_cutter},
    {421, g_cutter},      {430, g_tool_length}, {431, g_tool_length}, {432, g_tool_length}, {490, g_tool_length},
    {530, g_nonmodal},    {540, g_coordinate}, {550, g_coordinate},  {560, g_coordinate},  {570, g_coordinate},
    {580, g_coordinate},  {590, g_coordinate}, {591, g_coordinate},  {592, g_coordinate},  {593, g_coordinate},
    {610, g_path},        {611, g_path},       {640, g_path},        {730, g_motion},
    {740, -2, "tapping cycles G74/G84 (spindle-synchronised motion)"},
    {760, -2, "the threading cycle G76 (spindle-synchronised motion)"},
    {800, g_motion},      {810, g_motion},     {820, g_motion},      {830, g_motion},
    {840, -2, "tapping cycles G74/G84 (spindle-synchronised motion)"},
    {850, -2, g85_g89},   {860, -2, g85_g89},  {870, -2, g85_g89},   {880, -2, g85_g89},   {890, -2, g85_g89},
    {900, g_distance},    {901, g_arc_distance}, {910, g_distance},  {911, g_arc_distance}, {920, g_nonmodal},
    {921, g_nonmodal},    {922, g_nonmodal},   {923, g_nonmodal},    {930, g_feed_mode},   {940, g_feed_mode},
    {950, -2, "feed per revolution G95 (the feed would depend on the spindle)"},
    {960, g_spindle_mode}, {970, g_spindle_mode}, {980, g_retract},     {990, g_retract},
};

struct MCodeEntry {
  int m;
  int group;
};
// Sorted by code; M100-M199 are handled apart (user M codes). Codes not here are ignored with a warning.
constexpr MCodeEntry m_codes[] = {
    {0, m_stop},  {1, m_stop},  {2, m_stop},  {3, m_spindle},  {4, m_spindle},  {5, m_spindle},  {6, m_tool},
    {7, m_coolant}, {8, m_coolant}, {9, m_coolant}, {19, m_io}, {30, m_stop},
    {48, m_override}, {49, m_override}, {50, m_override}, {51, m_override}, {52, m_override}, {53, m_override},
    {60, m_stop}, {61, m_io}, {62, m_io}, {63, m_io}, {64, m_io}, {65, m_io}, {66, m_io}, {67, m_io}, {68, m_io},
    {70, m_io}, {71, m_io}, {72, m_io}, {73, m_io},
};

constexpr bool sorted_g() {
  for (std::size_t i = 1; i < std::size(g_codes); ++i)
    if (!(g_codes[i - 1].g10 < g_codes[i].g10)) return false;
  return true;
}
constexpr bool sorted_m() {
  for (std::size_t i = 1; i < std::size(m_codes); ++i)
    if (!(m_codes[i - 1].m < m_codes[i].m)) return false;
  return true;
}
static_assert(sorted_g() && sorted_m(), "the code tables must be sorted");

// Every G code times 10 below this has a slot in g_index (G97 and below).
constexpr int g_index_size = 1000;
// g_index[g10]: the entry of g_codes for that code, -1 for none (a direct lookup, as fast as a switch).
constexpr std::array<short, g_index_size> make_g_index() {
  std::array<short, g_index_size> index{};
  for (auto& i : index) i = -1;
  for (std::size_t i = 0; i < std::size(g_codes); ++i) index[static_cast<std::size_t>(g_codes[i].g10)] = static_cast<short>(i);
  return index;
}
constexpr std::array<short, g_index_size> g_index = make_g_index();
static_assert(std::size(g_codes) < 32767 && g_codes[std::size(g_codes) - 1].g10 < g_index_size);

}  // namespace

CodeInfo g_code_info(int g10) noexcept {
  if (g10 < 0 || g10 >= g_index_size) return {};
  const short i = g_index[static_cast<std::size_t>(g10)];
  if (i < 0) return {};
  const GCodeEntry& e = g_codes[static_cast<std::size_t>(i)];
  return CodeInfo{e.group, e.unsupported};
}

CodeInfo m_code_info(int m) noexcept {
  const auto* it =
      std::lower_bound(std::begin(m_codes), std::end(m_codes), m, [](const MCodeEntry& e, int v) { return e.m < v; });
  if (it != std::end(m_codes) && it->m == m) return CodeInfo{it->group, nullptr};
  if (m >= 100 && m <= 199) return CodeInfo{-2, "user M codes M100-M199 (they run external programs)"};
  // Subprogram calls change the path: never ignored like a machine's own M code.
  if (m >= 97 && m <= 99) return CodeInfo{-3, "subprogram calls and returns (M97, M98, M99)"};
  return {};
}

BlockCodes classify_codes(const Words& w, const Diagnostics& diag, bool fanuc_cycles) {
  BlockCodes codes;
  codes.g.fill(-1);
  codes.m.fill(-1);
  for (int i = 0; i < w.g_count; ++i) {
    const int g = w.g[static_cast<std::size_t>(i)];
    const int col = w.g_column[static_cast<std::size_t>(i)];
    const std::string gn = g_name(g, w.g_leading_zero[static_cast<std::size_t>(i)] != 0);
    const CodeInfo info = fanuc_cycles && is_fanuc_cycle(g) ? CodeInfo{g_motion, nullptr} : g_code_info(g);
    const int grp = info.group;
    if (grp == -2) diag.fail(col, "unsupported", fmt::format("{}: {} is not supported by Kontur", gn, info.unsupported));
    if (grp < 0) diag.fail(col, "unknown-g-code", fmt::format("{}: unknown G code", gn));
    auto& slot = codes.g[static_cast<std::size_t>(grp)];
    // CAM safety lines write "G80 G00": G80 only cancels the cycle, the other code is the motion
    if (grp == g_motion && (slot == motion_none || g == motion_none) && slot >= 0) {
      if (slot == motion_none) {
        slot = g;
        codes.g_column[static_cast<std::size_t>(grp)] = col;
      }
      continue;
    }
    if (slot >= 0)
      diag.fail(col, "modal-group", fmt::format("{}: {} and {} in one block: both belong to modal group {}", gn,
                                                g_name(slot), gn, grp));
    slot = g;
    codes.g_column[static_cast<std::size_t>(grp)] = col;
  }
  for (int i = 0; i < w.m_count; ++i) {
    const int m = w.m[static_cast<std::size_t>(i)];
    const int col = w.m_column[static_cast<std::size_t>(i)];
    const CodeInfo info = m_code_info(m);
    const int grp = info.group;
    if (grp == -3)
      diag.fail(col, "unsupported",
                fmt::format("M{}: {} are not LinuxCNC's: read the program with --dialect fanuc, haas or mach3", m,
                            info.unsupported));
    if (grp < 0) {  // not in the tables: ignored (the executor warns)
      if (codes.ignored_m_count < static_cast<int>(codes.ignored_m.size())) {
        codes.ignored_m[static_cast<std::size_t>(codes.ignored_m_count)] = m;
        codes.ignored_m_column[static_cast<std::size_t>(codes.ignored_m_count++)] = col;
      }
      continue;
    }
    auto& slot = codes.m[static_cast<std::size_t>(grp)];
    const bool coolant_pair = grp == m_coolant && ((slot == 7 && m == 8) || (slot == 8 && m == 7));
    if (slot >= 0 && !coolant_pair && grp != m_io)
      diag.fail(col, "modal-group",
                fmt::format("M{}: M{} and M{} in one block: both belong to modal group {}", m, slot, m, grp));
    if (grp == m_coolant && slot >= 0) codes.coolant_mist_and_flood = true;
    slot = m;
  }
  return codes;
}

}  // namespace kontur::gcode::detail
