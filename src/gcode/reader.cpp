// The G-code interpreter: the program read line by line through a fixed buffer, the words of a
// block run in LinuxCNC's order (feed mode, units, F, S/T/M, dwell, plane, offsets, distance
// modes, non-modal codes, motion, program end), and the Reader API.
#include "interpreter.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>

namespace kontur::gcode {
namespace {

// Modal groups of G codes (LinuxCNC numbering where it has one).
enum Group : int {
  g_nonmodal = 0, g_motion = 1, g_plane = 2, g_distance = 3, g_arc_distance = 4, g_feed_mode = 5, g_units = 6,
  g_cutter = 7, g_tool_length = 8, g_retract = 10, g_coordinate = 12, g_path = 13, g_spindle_mode = 14,
  g_lathe = 15, g_spline_end = 16, g_count_groups = 17
};

// The modal group of a supported G code (times 10), -1 if unknown; `unsupported` names a feature
// Kontur deliberately does not run.
int g_group(int g, const char*& unsupported) {
  unsupported = nullptr;
  switch (g) {
    case 40: case 100: case 280: case 281: case 300: case 301: case 530: case 920: case 921: case 922: case 923:
      return g_nonmodal;
    case 0: case 10: case 20: case 30: case 24: case 34: case 50: case 51: case 52: case 62:
    case 730: case 800: case 810: case 820: case 830:
      return g_motion;
    case 53: return g_spline_end;
    case 170: case 180: case 190: return g_plane;
    case 900: case 910: return g_distance;
    case 901: case 911: return g_arc_distance;
    case 930: case 940: return g_feed_mode;
    case 200: case 210: return g_units;
    case 400: return g_cutter;
    case 430: case 431: case 432: case 490: return g_tool_length;
    case 980: case 990: return g_retract;
    case 540: case 550: case 560: case 570: case 580: case 590: case 591: case 592: case 593: return g_coordinate;
    case 610: case 611: case 640: return g_path;
    case 960: case 970: return g_spindle_mode;
    case 80: return g_lathe;
    // known, deliberately not supported
    case 330: case 331: unsupported = "spindle-synchronised motion (G33 threading, G33.1 rigid tapping)"; return -2;
    case 760: unsupported = "the threading cycle G76 (spindle-synchronised motion)"; return -2;
    case 740: case 840: unsupported = "tapping cycles G74/G84 (spindle-synchronised motion)"; return -2;
    case 850: case 860: case 870: case 880: case 890:
      unsupported = "canned cycles G85-G89 (only G73, G81, G82 and G83 are expanded)"; return -2;
    case 950: unsupported = "feed per revolution G95 (the feed would depend on the spindle)"; return -2;
    case 410: case 411: case 420: case 421: unsupported = "cutter radius compensation G41/G42"; return -2;
    case 70: unsupported = "lathe diameter mode G7 (X would be a diameter)"; return -2;
    case 382: case 383: case 384: case 385: unsupported = "probing G38.x"; return -2;
    case 171: case 181: case 191: unsupported = "the UVW planes G17.1/G18.1/G19.1"; return -2;
    default: return -1;
  }
}

enum MGroup : int { m_stop = 4, m_io = 5, m_tool = 6, m_spindle = 7, m_coolant = 8, m_override = 9, m_other = 11 };
int m_group(int m, const char*& unsupported) {
  unsupported = nullptr;
  switch (m) {
    case 0: case 1: case 2: case 30: case 60: return m_stop;
    case 3: case 4: case 5: return m_spindle;
    case 6: return m_tool;
    case 7: case 8: case 9: return m_coolant;
    case 48: case 49: case 50: case 51: case 52: case 53: return m_override;
    case 19: case 61: case 62: case 63: case 64: case 65: case 66: case 67: case 68: case 70: case 71: case 72: case 73:
      return m_io;
    default:
      if (m >= 100 && m <= 199) {
        unsupported = "user M codes M100-M199 (they run external programs)";
        return -2;
      }
      return -1;
  }
}


}  // namespace


void Reader::Impl::open(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) throw InputError("file", fmt::format("{}: no such file", path));
  if (!std::filesystem::is_regular_file(path, ec))
    throw InputError("file", fmt::format("{}: not a regular file", path));
  file = std::fopen(path.c_str(), "rb");
  if (!file) throw InputError("file", fmt::format("{}: cannot be opened", path));
  buf.resize(read_chunk);
  fill();
  check_text(0);
}

void Reader::Impl::open_memory(std::string text) {
  memory = std::move(text);
  end = memory.size();
  input_eof = true;
  check_text(0);
}

void Reader::Impl::fill() {
  if (input_eof || !file) return;
  if (begin > 0) {
    std::memmove(buf.data(), buf.data() + begin, end - begin);
    buffer_offset += begin;
    end -= begin;
    begin = 0;
  }
  const std::size_t got = std::fread(buf.data() + end, 1, buf.size() - end, file);
  const std::size_t old_end = end;
  end += got;
  if (got == 0) input_eof = true;
  check_text(old_end);
}

void Reader::Impl::check_text(std::size_t from) const {
  const char* d = data();
  const void* z = std::memchr(d + from, 0, end - from);
  if (z) {
    const auto offset = buffer_offset + static_cast<std::size_t>(static_cast<const char*>(z) - d);
    throw InputError("not-text", fmt::format("{}: not a text file (NUL byte at offset {})", *name, offset));
  }
}

void Reader::Impl::seek(std::size_t offset, long line) {
  if (!file) {
    begin = offset;
  } else if (offset >= buffer_offset && offset <= buffer_offset + end) {
    begin = offset - buffer_offset;
  } else {
    if (std::fseek(file, static_cast<long>(offset), SEEK_SET) != 0)
      throw InputError("file", fmt::format("{}: cannot seek back for a loop or subroutine", *name));
    buffer_offset = offset;
    begin = end = 0;
    input_eof = false;
    fill();
  }
  line_no = line - 1;
  ctx.line = line_no;
}

bool Reader::Impl::read_line(std::string_view& out) {
  line_start = tell();
  const auto max_len = static_cast<std::size_t>(tolerances::gcode_max_line_length);
  for (;;) {
    const char* d = data();
    const void* nlp = std::memchr(d + begin, '\n', end - begin);
    if (nlp) {
      const auto stop = static_cast<std::size_t>(static_cast<const char*>(nlp) - d);
      out = std::string_view(d + begin, stop - begin);
      begin = stop + 1;
      break;
    }
    if (end - begin > max_len || input_eof) {
      if (begin == end) return false;
      out = std::string_view(d + begin, end - begin);
      begin = end;
      break;
    }
    fill();
  }
  ++line_no;
  ctx.line = line_no;
  if (out.size() > max_len)
    detail::fail_column(ctx, static_cast<int>(max_len) + 1, "line-length",
                        fmt::format("line longer than {} characters", max_len));
  if (!out.empty() && out.back() == '\r') out.remove_suffix(1);
  return true;
}

void Reader::Impl::process_line(std::string_view raw) {
  detail::normalize_line(raw, ctx, nl);
  if (nl.percent) {
    if (!seen_block && !tape) tape = true;
    else end_program();
    return;
  }
  if (nl.text.empty()) return;
  if (nl.block_delete && opt.block_delete) return;
  seen_block = true;
  if (nl.text[0] == 'O') {
    control_flow();
    return;
  }
  detail::parse_words(nl, ctx, params, w, assignments, assignment_count);
  for (std::size_t i = 0; i < assignment_count; ++i) {
    const auto& a = assignments[i];
    if (a.index > 0) params.set_numbered(a.index, a.value);
    else params.set_named(a.name, a.value);
  }
  if (w.empty()) return;
  execute();
}

void Reader::Impl::end_program() {
  finish_spline_at_end();
  ended = true;
}

void Reader::Impl::finish_spline_at_end() {
  if (circle_pending)
    detail::fail_column(ctx, circle_loc.column, "circle-end-missing",
                        fmt::format("{}: end point block missing at the end of the program: a 3-D circle takes two "
                                    "blocks (intermediate point, then end point)",
                                    g_name(circle_g, true)));
  if (spline == Spline::g62) finish_g62();
  if (spline == Spline::g52)
    fail_spline("g52-not-closed", "G5.2: NURBS block not closed by G5.3 at the end of the program");
}

void Reader::Impl::check_values() const {
  // ---- every value within the supported range (keeps all geometry finite)
  for (int c = 0; c < 26; ++c) {
    const char letter = static_cast<char>('A' + c);
    if (letter == 'G' || letter == 'M' || !w.has(letter)) continue;
    const double v = w.get(letter);
    const bool length_word = std::strchr("XYZIJKRQ", letter) != nullptr;
    const double limit = length_word ? tolerances::gcode_max_coordinate_mm : tolerances::gcode_max_value;
    if (!(std::abs(v) <= limit))
      fail(w.col(letter), "value-range", fmt::format("{}{}: beyond the supported range +-{}", letter, num(v), num(limit)));
  }
  for (int p = 0; p < 3; ++p)
    for (int a = 0; a < 3; ++a)
      if (w.has_indexed(p, a) &&
          !(std::abs(w.indexed[static_cast<std::size_t>(p)][static_cast<std::size_t>(a)]) <= tolerances::gcode_max_coordinate_mm))
        fail(w.indexed_column[static_cast<std::size_t>(p)][static_cast<std::size_t>(a)], "value-range",
             fmt::format("{}{}=: beyond the supported range", static_cast<char>('I' + a), p + 1));

}

void Reader::Impl::execute() {
  check_values();
  // A block that continues a spline being collected.
  if (spline != Spline::none && continue_spline()) return;
  if (spline == Spline::g62) finish_g62();
  if (circle_pending && !(has_axes() && w.g_count == 0 && w.keyword == Keyword::none)) {
    fail(block_column(), "circle-end-missing",
         fmt::format("{}: end point block missing: a 3-D circle takes two blocks (intermediate point, then the "
                     "end point with X Y Z alone)",
                     g_name(circle_g, true)));
  }

  // ---- classify the G and M codes, reject unknown, unsupported and conflicting ones
  std::array<int, g_count_groups> group_code;
  std::array<int, g_count_groups> group_col;
  group_code.fill(-1);
  for (int i = 0; i < w.g_count; ++i) {
    const int g = w.g[static_cast<std::size_t>(i)];
    const int col = w.g_column[static_cast<std::size_t>(i)];
    const std::string gn = g_name(g, w.g_leading_zero[static_cast<std::size_t>(i)] != 0);
    const char* unsupported = nullptr;
    const int grp = g_group(g, unsupported);
    if (grp == -2) fail(col, "unsupported", fmt::format("{}: {} is not supported by Kontur", gn, unsupported));
    if (grp < 0) fail(col, "unknown-g-code", fmt::format("{}: unknown G code", gn));
    auto& slot = group_code[static_cast<std::size_t>(grp)];
    // CAM safety lines write "G80 G00": G80 only cancels the cycle, the other code is the motion
    if (grp == g_motion && (slot == 800 || g == 800) && slot >= 0) {
      if (slot == 800) {
        slot = g;
        group_col[static_cast<std::size_t>(grp)] = col;
      }
      continue;
    }
    if (slot >= 0)
      fail(col, "modal-group", fmt::format("{}: {} and {} in one block: both belong to modal group {}", gn,
                                           g_name(slot), gn, grp));
    slot = g;
    group_col[static_cast<std::size_t>(grp)] = col;
  }
  std::array<int, 12> m_code;
  m_code.fill(-1);
  for (int i = 0; i < w.m_count; ++i) {
    const int m = w.m[static_cast<std::size_t>(i)];
    const int col = w.m_column[static_cast<std::size_t>(i)];
    const char* unsupported = nullptr;
    const int grp = m_group(m, unsupported);
    if (grp == -2) fail(col, "unsupported", fmt::format("M{}: {} are not supported by Kontur", m, unsupported));
    if (grp < 0) fail(col, "unknown-m-code", fmt::format("M{}: unknown M code", m));
    auto& slot = m_code[static_cast<std::size_t>(grp)];
    const bool coolant_pair = grp == m_coolant && ((slot == 7 && m == 8) || (slot == 8 && m == 7));
    if (slot >= 0 && !coolant_pair && grp != m_io)
      fail(col, "modal-group", fmt::format("M{}: M{} and M{} in one block: both belong to modal group {}", m, slot, m, grp));
    if (grp == m_coolant && slot >= 0) { modal.mist = modal.flood = true; }
    slot = m;
  }
  for (const char c : {'A', 'B', 'C', 'U', 'V', 'W'})
    if (w.has(c))
      fail(w.col(c), "unsupported",
           fmt::format("{}{}: rotary and extra axes (A B C U V W) are not supported: Kontur interpolates X Y Z", c,
                       num(w.get(c))));
  if (w.indexed_present != 0 && w.keyword == Keyword::none) {
    for (int p = 0; p < 3; ++p)
      for (int a = 0; a < 3; ++a)
        if (w.has_indexed(p, a))
          fail(w.indexed_column[static_cast<std::size_t>(p)][static_cast<std::size_t>(a)], "syntax",
               fmt::format("{}{}=: only in CIP or CONIC blocks", static_cast<char>('I' + a), p + 1));
  }

  const int nonmodal = group_code[g_nonmodal];
  const int motion_word = group_code[g_motion];
  if (w.keyword != Keyword::none && motion_word >= 0)
    fail(w.keyword_column, "modal-group",
         fmt::format("{}: {} and {} in one block: both are motion commands",
                     w.keyword == Keyword::cip ? "CIP" : "CONIC", g_name(motion_word),
                     w.keyword == Keyword::cip ? "CIP" : "CONIC"));
  const bool nonmodal_uses_axes = nonmodal == 100 || nonmodal == 280 || nonmodal == 300 || nonmodal == 920;
  if (nonmodal_uses_axes && (motion_word >= 0 && motion_word != 800))
    fail(group_col[g_nonmodal], "axis-words",
         fmt::format("{} and {} in one block: both use the axis words", g_name(nonmodal), g_name(motion_word)));

  // ---- feed mode, units, feed
  if (group_code[g_feed_mode] >= 0)
    modal.feed_mode = group_code[g_feed_mode] == 930 ? FeedMode::inverse_time : FeedMode::units_per_minute;
  if (group_code[g_units] >= 0) modal.units = group_code[g_units] == 200 ? Units::inch : Units::mm;
  if (w.has('F')) {
    const double f = w.get('F');
    if (f < 0.0) fail(w.col('F'), "feed-range", fmt::format("F{}: feed must be >= 0", num(f)));
    if (modal.feed_mode == FeedMode::units_per_minute) feed_mm_per_min = f * scale();
    else if (!(f > 0.0)) fail(w.col('F'), "feed-range", fmt::format("F{}: inverse-time feed must be > 0", num(f)));
  }
  // ---- spindle, tool, coolant (recorded)
  if (w.has('S')) {
    if (w.get('S') < 0.0) fail(w.col('S'), "spindle-range", fmt::format("S{}: spindle speed must be >= 0", num(w.get('S'))));
    modal.spindle_rpm = w.get('S');
  }
  if (w.has('T') && w.get('T') < 0.0) fail(w.col('T'), "tool-range", "T: tool number must be >= 0");
  if (m_code[m_tool] == 6) modal.tool = w.has('T') ? static_cast<int>(w.get('T')) : modal.tool;
  if (m_code[m_spindle] >= 0)
    modal.spindle = m_code[m_spindle] == 3 ? SpindleState::clockwise
                    : m_code[m_spindle] == 4 ? SpindleState::counter_clockwise : SpindleState::off;
  if (m_code[m_coolant] == 7) modal.mist = true;
  if (m_code[m_coolant] == 8) modal.flood = true;
  if (m_code[m_coolant] == 9) modal.mist = modal.flood = false;
  if (m_code[m_io] >= 0) warn(w.first_column, fmt::format("M{}: input/output and state codes are ignored", m_code[m_io]));

  // ---- dwell
  if (nonmodal == 40) {
    if (!w.has('P')) fail(group_col[g_nonmodal], "dwell", "G4: P (dwell time in seconds) missing");
    const double p = w.get('P');
    if (p < 0.0) fail(w.col('P'), "dwell", fmt::format("G4 P{}: dwell time must be >= 0", num(p)));
    Block b = make_block(BlockType::dwell, group_col[g_nonmodal]);
    b.start = b.end = to_machine(pos);
    b.dwell_s = p;
    emit(std::move(b));
  }
  // ---- plane, compensation, offsets, path control, distance modes
  if (group_code[g_plane] >= 0)
    modal.plane = group_code[g_plane] == 170 ? Plane::xy : group_code[g_plane] == 180 ? Plane::zx : Plane::yz;
  if (group_code[g_tool_length] >= 0) {
    const int g = group_code[g_tool_length];
    modal.tool_length_offset = g != 490;
    if (g == 430) {
      if (w.has('H')) {
        const double h = w.get('H');
        if (h < 0.0 || h != std::floor(h)) fail(w.col('H'), "tool-range", fmt::format("H{}: must be an integer >= 0", num(h)));
        modal.tool_length_h = static_cast<int>(h);
      } else {
        modal.tool_length_h = modal.tool;
      }
    }
  }
  if (group_code[g_coordinate] >= 0) {
    const int g = group_code[g_coordinate];
    const int index = g <= 590 ? (g - 540) / 10 + 1 : 6 + (g - 590);
    const Vec3 m = to_machine(pos);
    modal.work_offset = index;
    pos = to_program(m);
  }
  if (group_code[g_path] >= 0) {
    const int g = group_code[g_path];
    modal.path_control = g == 640 ? PathControl::blend : g == 610 ? PathControl::exact_path : PathControl::exact_stop;
    if (g == 640) {
      modal.blend_tolerance_mm = w.has('P') ? w.get('P') * scale() : 0.0;
      modal.naive_cam_tolerance_mm = w.has('Q') ? w.get('Q') * scale() : modal.blend_tolerance_mm;
      if (modal.blend_tolerance_mm < 0.0 || modal.naive_cam_tolerance_mm < 0.0)
        fail(group_col[g_path], "tolerance-range", "G64 P Q: tolerances must be >= 0");
    }
  }
  if (group_code[g_distance] >= 0)
    modal.distance = group_code[g_distance] == 900 ? DistanceMode::absolute : DistanceMode::incremental;
  if (group_code[g_arc_distance] >= 0)
    modal.arc_distance = group_code[g_arc_distance] == 901 ? DistanceMode::absolute : DistanceMode::incremental;
  if (group_code[g_retract] >= 0)
    modal.retract = group_code[g_retract] == 980 ? RetractMode::initial_z : RetractMode::r_plane;
  if (group_code[g_spindle_mode] == 960)
    warn(group_col[g_spindle_mode], "G96: constant surface speed is recorded, not simulated (the path feed is unchanged)");
  if (group_code[g_spline_end] >= 0)
    fail(group_col[g_spline_end], "g53-without-g52", "G5.3: no NURBS block is open (G5.2 missing)");

  // ---- non-modal codes
  bool machine_coordinates = false;
  switch (nonmodal) {
    case 100: g10(group_col[g_nonmodal]); break;
    case 280: case 300: home(nonmodal, group_col[g_nonmodal]); break;
    case 281: case 301: {
      const Vec3 m = to_machine(pos) / scale();
      const int base = nonmodal == 281 ? 5161 : 5181;
      for (int a = 0; a < 3; ++a) params.set_numbered(base + a, m[a]);
      break;
    }
    case 530: machine_coordinates = true; break;
    case 920: {
      if (!has_axes()) fail(group_col[g_nonmodal], "axis-words", "G92: axis words missing");
      const char letters[3] = {'X', 'Y', 'Z'};
      for (int a = 0; a < 3; ++a)
        if (w.has(letters[a])) {
          const double v = w.get(letters[a]) * scale();
          g92[a] = pos[a] + g92[a] - v;
          pos[a] = v;
        }
      g92_saved = g92;
      break;
    }
    case 921: case 922: {
      const Vec3 m = to_machine(pos);
      g92.setZero();
      if (nonmodal == 921) g92_saved.setZero();
      pos = to_program(m);
      break;
    }
    case 923: {
      const Vec3 m = to_machine(pos);
      g92 = g92_saved;
      pos = to_program(m);
      break;
    }
    default: break;
  }

  // ---- motion
  int motion = modal.motion_g10;
  if (motion_word >= 0) motion = motion_word;
  if (w.keyword == Keyword::cip) motion = motion_cip;
  if (w.keyword == Keyword::conic) motion = motion_conic;
  const bool starts_motion = motion_word >= 0 || w.keyword != Keyword::none;
  const int motion_col = motion_word >= 0 ? group_col[g_motion] : w.keyword != Keyword::none ? w.keyword_column : block_column();
  const bool axes_for_motion = has_axes() && !nonmodal_uses_axes;
  auto cycle_code = [](int m) { return m == 730 || m == 810 || m == 820 || m == 830; };
  const bool is_cycle = cycle_code(motion);
  if (is_cycle && !cycle_code(modal.motion_g10)) {
    cycle_old_z = pos.z();
    cycle_r_set = cycle_z_set = cycle_q_set = false;
  }
  if (motion_word >= 0 || w.keyword != Keyword::none) modal.motion_g10 = motion;

  if (axes_for_motion || starts_motion || (is_cycle && (w.has('R') || has_axes()))) {
    if (motion == motion_none) {
      if (axes_for_motion)
        fail(block_column(), "axis-words", "axis words without a motion command (G80 cancelled the motion mode)");
    } else if (axes_for_motion || motion == 52 || (motion == 62 && w.has('K')) || is_cycle ||
               w.keyword != Keyword::none) {
      move(motion, motion_col, machine_coordinates, motion_word);
    }
  }

  warn_unused_words(motion, nonmodal, group_code[g_path], group_code[g_tool_length], axes_for_motion || starts_motion);

  // ---- program end
  if (m_code[m_stop] == 2 || m_code[m_stop] == 30) {
    program_end_seen = true;
    end_program();
  }
}

void Reader::Impl::warn_unused_words(int motion, int nonmodal, int path, int tool_length, bool moved) {
  std::string used = "FSTN";  // always meaningful
  auto add = [&](const char* letters) { used += letters; };
  const bool cycle = motion == 730 || motion == 810 || motion == 820 || motion == 830;
  if (moved || nonmodal == 100 || nonmodal == 280 || nonmodal == 300 || nonmodal == 920) add("XYZ");
  if (moved) {
    if (motion == 20 || motion == 30) add("IJKRP");
    if (motion == 50 || motion == 51) add("IJPQ");
    if (motion == 52) add("PL");
    if (motion == 62) add("KRPQ");
    if (cycle) add("RZPQL");
  }
  if (cycle) add("RPQL");  // sticky cycle words on a block without a hole
  if (nonmodal == 40) add("P");
  if (nonmodal == 100) add("LPR");
  if (path == 640) add("PQ");
  if (tool_length == 430) add("H");
  for (int c = 0; c < 26; ++c) {
    const char letter = static_cast<char>('A' + c);
    if (letter == 'G' || letter == 'M' || !w.has(letter) || used.find(letter) != std::string::npos) continue;
    warn(w.col(letter), fmt::format("{}{}: not used by any code of this block (ignored)", letter, num(w.get(letter))));
  }
}

void Reader::Impl::move(int motion, int col, bool machine_coordinates, int motion_word) {
  const Vec3 to = target(machine_coordinates);
  if (motion != 50 && motion != 51) prev_g5 = false;
  switch (motion) {
    case 0: line_move(BlockType::rapid, to, col, Feed{}); prev_g5 = false; return;
    case 10: line_move(BlockType::line, to, col, feed_move("G1")); prev_g5 = false; return;
    case 20: case 30: arc(motion == 20, to, col); prev_g5 = false; return;
    case 50: case 51: bezier(motion == 50, to, col); return;
    case 52: start_g52(col); return;
    case 62: start_g62(col, motion_word); return;
    case 24: case 34: circle_block(motion, col); return;
    case motion_cip: cip(to, col); return;
    case motion_conic: conic(to, col); return;
    case 730: case 810: case 820: case 830: cycle(motion, col); return;
    default: break;
  }
  fail(col, "internal", fmt::format("motion mode {} not handled", g_name(motion)));
}

void Reader::Impl::g10(int col) {
  if (!w.has('L')) fail(col, "g10", "G10: L missing (L2 or L20 set a work offset)");
  const double l = w.get('L');
  if (l == 1.0 || l == 10.0 || l == 11.0) {
    warn(col, fmt::format("G10 L{}: tool table entries are ignored (tool offsets are recorded, not applied)", num(l)));
    return;
  }
  if (l != 2.0 && l != 20.0) fail(w.col('L'), "g10", fmt::format("G10 L{}: unknown (L2 or L20 set a work offset)", num(l)));
  if (!w.has('P')) fail(col, "g10", "G10: P missing (coordinate system 1..9, 0 = the active one)");
  const double p = w.get('P');
  if (p != std::floor(p) || p < 0.0 || p > 9.0)
    fail(w.col('P'), "g10", fmt::format("G10 P{}: coordinate system must be 0..9", num(p)));
  const auto index = static_cast<std::size_t>(p == 0.0 ? modal.work_offset : static_cast<int>(p));
  const Vec3 m = to_machine(pos);
  const char letters[3] = {'X', 'Y', 'Z'};
  if (w.has('R')) {
    if (l == 20.0) fail(w.col('R'), "g10", "G10 L20: R (rotation) only with L2");
    work_rotation_deg[index] = w.get('R');
  }
  if (l == 2.0) {
    for (int a = 0; a < 3; ++a)
      if (w.has(letters[a])) work_offset[index][a] = w.get(letters[a]) * scale();
  } else {
    // L20: the offset that makes the current point have the given program coordinates
    Vec3 p_new = pos;
    for (int a = 0; a < 3; ++a)
      if (w.has(letters[a])) p_new[a] = w.get(letters[a]) * scale();
    const double ang = work_rotation_deg[index] * pi / 180.0;
    const Eigen::Matrix3d rot = Eigen::AngleAxisd(ang, Vec3::UnitZ()).toRotationMatrix();
    const Vec3 off = m - rot * (p_new + g92);
    for (int a = 0; a < 3; ++a)
      if (w.has(letters[a])) work_offset[index][a] = off[a];
  }
  if (static_cast<int>(index) == modal.work_offset) pos = to_program(m);
}

void Reader::Impl::home(int g, int col) {
  const int base = g == 280 ? 5161 : 5181;
  Vec3 home_m(params.numbered(base) * scale(), params.numbered(base + 1) * scale(), params.numbered(base + 2) * scale());
  if (has_axes()) {
    const Vec3 via = target();
    line_move(BlockType::rapid, via, col, Feed{});
    Vec3 m = to_machine(pos);
    const char letters[3] = {'X', 'Y', 'Z'};
    for (int a = 0; a < 3; ++a)
      if (w.has(letters[a])) m[a] = home_m[a];
    line_move(BlockType::rapid, to_program(m), col, Feed{});
  } else {
    line_move(BlockType::rapid, to_program(home_m), col, Feed{});
  }
}

Reader::Reader(const std::string& path, ReaderOptions options) : impl_(std::make_unique<Impl>(path, options)) {
  impl_->open(path);
}
Reader::Reader(std::string_view name, std::string text, ReaderOptions options)
    : impl_(std::make_unique<Impl>(name, options)) {
  impl_->open_memory(std::move(text));
}
Reader::~Reader() = default;
Reader::Reader(Reader&&) noexcept = default;
Reader& Reader::operator=(Reader&&) noexcept = default;

bool Reader::next(Block& out) {
  Impl& r = *impl_;
  while (r.head == r.queue.size()) {
    r.queue.clear();
    r.head = 0;
    if (r.ended) return false;
    try {
      std::string_view raw;
      if (!r.read_line(raw)) {
        r.ended = true;
        if (!r.frames.empty()) {
          const auto& f = r.frames.back();
          static constexpr const char* names[] = {"sub", "endsub", "call", "return", "while", "endwhile", "do",
                                                  "repeat", "endrepeat", "if"};
          const auto k = static_cast<std::size_t>(f.kind);
          r.fail_column(f.line, 1, "o-word",
                        fmt::format("{} {}: the program ends inside it ({} missing)", f.label, k < 10 ? names[k] : "?",
                                    f.kind == Impl::OKind::if_ ? "endif" : f.kind == Impl::OKind::call ? "endsub" :
                                    f.kind == Impl::OKind::while_ ? "endwhile" : f.kind == Impl::OKind::do_ ? "while" : "endrepeat"));
        }
        r.end_program();
        if (!r.program_end_seen && !r.tape) r.warn(1, "the program ends without M2, M30 or '%'");
        continue;
      }
      r.process_line(raw);
    } catch (...) {
      r.ended = true;  // after an error the reader hands out nothing more
      r.queue.clear();
      r.head = 0;
      throw;
    }
  }
  out = std::move(r.queue[r.head++]);
  return true;
}
const std::vector<std::string>& Reader::warnings() const noexcept { return impl_->warnings; }
std::size_t Reader::warning_count() const noexcept { return impl_->warning_count; }
long Reader::lines_read() const noexcept { return impl_->line_no; }

}  // namespace kontur::gcode
