// The executor's block, step by step in LinuxCNC's order, with one small function per modal group.
#include "executor.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace kontur::gcode::detail {

const Words Executor::no_words{};

namespace {
const char* keyword_name(Keyword k) { return k == Keyword::cip ? "CIP" : k == Keyword::ct ? "CT" : "CONIC"; }
}  // namespace

void Executor::execute(const Words& words) {
  w = &words;
  xto = xpos;  // the extra axes stay unless a move of this block moves them
  check_values();
  // A block that continues a spline being collected.
  if (spline != Spline::none && continue_spline()) return;
  if (spline == Spline::g62) finish_g62();
  check_circle_end_block();
  if (w->frame_op != FrameOp::none) {
    programmable_frame();
    return;
  }
  if (w->pole_g != 0) {
    define_pole();
    return;
  }

  const BlockCodes codes = classify_codes(*w, diag, rules_.fanuc_cycles);
  check_words_allowed(codes);

  set_feed_mode(codes);
  set_units(codes);
  set_feed_rate();
  set_spindle_speed();
  set_tool(codes);
  set_spindle(codes);
  set_coolant(codes);
  warn_io_codes(codes);
  warn_ignored_m_codes(codes);
  if (codes.code(g_nonmodal) == 40) dwell(codes.column(g_nonmodal));
  set_plane(codes);
  set_cutter_comp(codes);
  set_tool_length(codes);
  set_work_system(codes);
  set_path_control(codes);
  set_distance_modes(codes);
  set_retract_mode(codes);
  set_spindle_mode(codes);
  reject_spline_end(codes);
  const bool machine_coordinates = run_nonmodal(codes);
  run_motion(codes, machine_coordinates);
  end_if_program_end(codes);
}

void Executor::before_control_flow(int column) {
  if (spline == Spline::g52) fail(column, "g52-open", "O-word inside an open G5.2 NURBS block (close it with G5.3 first)");
  if (spline == Spline::g62) finish_g62();
}

void Executor::end_program() {
  xto = xpos;
  finish_spline_at_end();
  ended_ = true;
}

void Executor::finish_spline_at_end() {
  if (circle_pending)
    fail(circle_loc.column, "circle-end-missing",
         fmt::format("{}: end point block missing at the end of the program: a 3-D circle takes two "
                     "blocks (intermediate point, then end point)",
                     g_name(circle_g, true)));
  if (spline == Spline::g62) finish_g62();
  if (spline == Spline::g52)
    fail_spline("g52-not-closed", "G5.2: NURBS block not closed by G5.3 at the end of the program");
}

// ---------------------------------------------------------------- checks before anything runs

void Executor::check_values() const {
  // every value within the supported range (keeps all geometry finite)
  for (int c = 0; c < 26; ++c) {
    const char letter = static_cast<char>('A' + c);
    if (letter == 'G' || letter == 'M' || !w->has(letter)) continue;
    const double v = w->get(letter);
    const bool length_word = std::strchr("XYZUVWIJKRQ", letter) != nullptr;  // A B C: angles [deg]
    const double limit = length_word ? tolerances::gcode_max_coordinate_mm : tolerances::gcode_max_value;
    if (!(std::abs(v) <= limit))
      fail(w->col(letter), "value-range", fmt::format("{}{}: beyond the supported range +-{}", letter, num(v), num(limit)));
  }
  for (int p = 0; p < 3; ++p)
    for (int a = 0; a < 3; ++a)
      if (w->has_indexed(p, a) &&
          !(std::abs(w->indexed[static_cast<std::size_t>(p)][static_cast<std::size_t>(a)]) <= tolerances::gcode_max_coordinate_mm))
        fail(w->indexed_column[static_cast<std::size_t>(p)][static_cast<std::size_t>(a)], "value-range",
             fmt::format("{}{}=: beyond the supported range", static_cast<char>('I' + a), p + 1));
}

void Executor::check_circle_end_block() const {
  if (circle_pending && !(has_axes() && w->g_count == 0 && w->keyword == Keyword::none))
    fail(block_column(), "circle-end-missing",
         fmt::format("{}: end point block missing: a 3-D circle takes two blocks (intermediate point, then the "
                     "end point with X Y Z alone)",
                     g_name(circle_g, true)));
}

void Executor::check_words_allowed(const BlockCodes& codes) const {
  if (w->indexed_present != 0 && w->keyword == Keyword::none) {
    for (int p = 0; p < 3; ++p)
      for (int a = 0; a < 3; ++a)
        if (w->has_indexed(p, a))
          fail(w->indexed_column[static_cast<std::size_t>(p)][static_cast<std::size_t>(a)], "syntax",
               fmt::format("{}{}=: only in CIP or CONIC blocks", static_cast<char>('I' + a), p + 1));
  }
  const int nonmodal = codes.code(g_nonmodal);
  const int motion_word = codes.code(g_motion);
  if (w->keyword != Keyword::none && motion_word >= 0)
    fail(w->keyword_column, "modal-group",
         fmt::format("{}: {} and {} in one block: both are motion commands",
                     keyword_name(w->keyword), g_name(motion_word), keyword_name(w->keyword)));
  const bool nonmodal_uses_axes = nonmodal == 100 || nonmodal == 280 || nonmodal == 300 || nonmodal == 920;
  // Fanuc's "G0 G91 G28 Z0": the motion code only sets the mode, the axis words are G28's.
  if (nonmodal_uses_axes && (motion_word >= 0 && motion_word != motion_none) && !rules_.motion_code_beside_nonmodal)
    fail(codes.column(g_nonmodal), "axis-words",
         fmt::format("{} and {} in one block: both use the axis words", g_name(nonmodal), g_name(motion_word)));
}

// ---------------------------------------------------------------- feed mode, units, feed (groups 5, 6)

void Executor::set_feed_mode(const BlockCodes& codes) {
  const int g = codes.code(g_feed_mode);
  if (g >= 0) modal.feed_mode = g == 930 ? FeedMode::inverse_time : FeedMode::units_per_minute;
}

void Executor::set_units(const BlockCodes& codes) {
  const int g = codes.code(g_units);
  if (g >= 0) modal.units = g == 200 ? Units::inch : Units::mm;
}

void Executor::set_feed_rate() {
  if (!w->has('F')) return;
  const double f = w->get('F');
  if (f < 0.0) fail(w->col('F'), "feed-range", fmt::format("F{}: feed must be >= 0", num(f)));
  if (modal.feed_mode == FeedMode::units_per_minute) feed_mm_per_min = f * scale();
  else if (!(f > 0.0)) fail(w->col('F'), "feed-range", fmt::format("F{}: inverse-time feed must be > 0", num(f)));
}

// ---------------------------------------------------------------- spindle, tool, coolant (recorded; M groups 6-8, 5)

void Executor::set_spindle_speed() {
  if (!w->has('S')) return;
  if (w->get('S') < 0.0) fail(w->col('S'), "spindle-range", fmt::format("S{}: spindle speed must be >= 0", num(w->get('S'))));
  modal.spindle_rpm = w->get('S');
}

void Executor::set_tool(const BlockCodes& codes) {
  if (w->has('T') && w->get('T') < 0.0) fail(w->col('T'), "tool-range", "T: tool number must be >= 0");
  // a tool the given table lacks (T0: no tool)
  if (w->has('T') && has_table_) {
    const double t = w->get('T');
    if (t != 0.0 && (t != std::floor(t) || t > 1e9 || tools_.find(static_cast<int>(t)) == nullptr))
      fail(w->col('T'), "tool-not-in-table", fmt::format("T{}: the tool is not in the tool table", num(t)));
  }
  // T selects (prepares) the tool, M6 loads the selected one (LinuxCNC: "T2" then "M6" loads tool 2)
  if (w->has('T')) selected_tool_ = static_cast<int>(std::min(w->get('T'), 1e9));
  if (codes.m_code(m_tool) == 6) modal.tool = selected_tool_;
}

void Executor::set_spindle(const BlockCodes& codes) {
  const int m = codes.m_code(m_spindle);
  if (m >= 0) modal.spindle = m == 3 ? SpindleState::clockwise : m == 4 ? SpindleState::counter_clockwise : SpindleState::off;
}

void Executor::set_coolant(const BlockCodes& codes) {
  if (codes.coolant_mist_and_flood) modal.mist = modal.flood = true;
  const int m = codes.m_code(m_coolant);
  if (m == 7) modal.mist = true;
  if (m == 8) modal.flood = true;
  if (m == 9) modal.mist = modal.flood = false;
}

void Executor::warn_ignored_m_codes(const BlockCodes& codes) {
  for (int i = 0; i < codes.ignored_m_count; ++i) {
    const int m = codes.ignored_m[static_cast<std::size_t>(i)];
    if (!warned_m_codes.insert(m).second) continue;  // once per code
    warn(codes.ignored_m_column[static_cast<std::size_t>(i)],
         fmt::format("M{}: {} M code, ignored (it does not move the axes; warned once)", m,
                     m >= 100 && m <= 199 ? "user" : "machine-specific"));
  }
}

void Executor::warn_io_codes(const BlockCodes& codes) {
  const int m = codes.m_code(m_io);
  if (m >= 0) warn(w->first_column, fmt::format("M{}: input/output and state codes are ignored", m));
}

// ---------------------------------------------------------------- plane, compensation, offsets, path, distance

void Executor::set_plane(const BlockCodes& codes) {
  const int g = codes.code(g_plane);
  if (g < 0) return;
  const Plane plane = g == 170 ? Plane::xy : g == 180 ? Plane::zx : Plane::yz;
  // LinuxCNC: no change of plane under cutter compensation (a G40 of the same block turns it off first)
  if (plane != modal.plane && modal.cutter_comp != CutterComp::off && codes.code(g_cutter) != 400)
    fail(codes.column(g_plane), "plane-under-compensation",
         fmt::format("{}: the plane cannot change while cutter radius compensation is on (G40 first)", g_name(g)));
  modal.plane = plane;
}

int Executor::register_word(char letter, const char* what) const {
  const double v = w->get(letter);
  if (v < 0.0 || v != std::floor(v) || v > 1e9)
    fail(w->col(letter), "tool-range", fmt::format("{}{}: {} must be an integer >= 0", letter, num(v), what));
  return static_cast<int>(v);
}

double Executor::tool_length_of(int n, int column, const std::string& word) const {
  if (n == 0) return 0.0;
  const auto wear = h_wear_.find(n);
  const double added = wear == h_wear_.end() ? 0.0 : wear->second;
  if (const Tool* t = tools_.find(n)) return t->length_mm + added;
  if (!has_table_) return added;  // no table: length 0 (recorded, as without one)
  fail(column, "tool-not-in-table", fmt::format("{}: tool {} is not in the tool table", word, n));
}

double Executor::tool_radius_of(int n, int column, const std::string& word) const {
  const auto wear = d_wear_.find(n);
  const double added = wear == d_wear_.end() ? 0.0 : wear->second;
  if (n == 0) return added;
  const Tool* t = tools_.find(n);
  if (t == nullptr && !has_table_)
    fail(column, "no-tool-table",
         fmt::format("{}: the radius of tool {} is unknown: no tool table given (--tool-table FILE or the INI's "
                     "[EMCIO] TOOL_TABLE; G41.1 / G42.1 D give the diameter in the block)",
                     word, n));
  if (t == nullptr) fail(column, "tool-not-in-table", fmt::format("{}: tool {} is not in the tool table", word, n));
  const double r = t->diameter_mm / 2.0 + added;
  if (r < 0.0) fail(column, "negative-radius", fmt::format("{}: the radius of tool {} is negative ({} mm)", word, n, num(r)));
  return r;
}

bool Executor::cutter_register_h(const BlockCodes& codes) const {
  const int g = codes.code(g_cutter);
  return rules_.fanuc_offset_registers && (g == 410 || g == 420) && !w->has('D') && w->has('H') &&
         codes.code(g_tool_length) < 0;
}

void Executor::set_cutter_comp(const BlockCodes& codes) {
  const int g = codes.code(g_cutter);
  if (g < 0) return;
  const int col = codes.column(g_cutter);
  if (g == 400) {
    // LinuxCNC: the move just after leaving compensation must be straight
    arc_not_allowed_ = arc_not_allowed_ || modal.cutter_comp != CutterComp::off;
    modal.cutter_comp = CutterComp::off;
    modal.cutter_radius_mm = 0.0;
    return;
  }
  const std::string name = g_name(g);
  if (modal.cutter_comp != CutterComp::off)
    fail(col, "compensation-on",
         fmt::format("{}: cutter radius compensation is already on (LinuxCNC: G40 before switching it on again)", name));
  if (modal.plane == Plane::yz)
    fail(col, "compensation-plane", fmt::format("{}: cutter radius compensation only in the XY (G17) or XZ (G18) plane", name));
  double radius = 0.0;
  if (g == 411 || g == 421) {  // the diameter in the block, in program units
    if (w->has('L'))
      fail(w->col('L'), "unsupported", fmt::format("{} L: the lathe tool orientation is not supported by Kontur", name));
    if (!w->has('D')) fail(col, "d-missing", fmt::format("{}: D (the cutter diameter) missing", name));
    const double d = w->get('D');
    if (d < 0.0) fail(w->col('D'), "negative-radius", fmt::format("{} D{}: the diameter must be >= 0", name, num(d)));
    radius = d * scale() / 2.0;
  } else if (w->has('D') || cutter_register_h(codes)) {
    // the Fanuc family: an H beside G41 / G42 without D (Fanuc 0M's offset number) names the register
    const char r = w->has('D') ? 'D' : 'H';
    const int n = register_word(r, "the tool number");
    radius = tool_radius_of(n, w->col(r), fmt::format("{} {}{}", name, r, n));
  } else {
    radius = tool_radius_of(modal.tool, col, fmt::format("{} (the current tool T{})", name, modal.tool));
  }
  modal.cutter_comp = g == 410 || g == 411 ? CutterComp::left : CutterComp::right;
  modal.cutter_radius_mm = radius;
}

void Executor::set_tool_length(const BlockCodes& codes) {
  const int g = codes.code(g_tool_length);
  if (g < 0) return;
  const int col = codes.column(g_tool_length);
  if (g == 490) {
    modal.tool_length_offset = false;
    apply_tool_length(0.0);
    return;
  }
  modal.tool_length_offset = true;
  if (g == 430) {
    const int h = w->has('H') ? register_word('H', "the tool number") : modal.tool;
    modal.tool_length_h = h;
    apply_tool_length(tool_length_of(h, w->has('H') ? w->col('H') : col, fmt::format("G43 H{}", h)));
  } else if (g == 431) {  // the length in the block (LinuxCNC's dynamic offset), program units
    if (!w->has('Z')) fail(col, "axis-words", "G43.1: Z (the tool length) missing");
    if (w->has('X') || w->has('Y') || extra_word() != 0)
      fail(col, "axis-words", "G43.1: only Z (the tool length) is applied by Kontur");
    apply_tool_length(w->get('Z') * scale());
  } else {  // G43.2 H: adds another tool's length
    if (!w->has('H')) fail(col, "h-missing", "G43.2: H (the tool whose length is added) missing");
    const int h = register_word('H', "the tool number");
    apply_tool_length(tool_length_ + tool_length_of(h, w->col('H'), fmt::format("G43.2 H{}", h)));
  }
}

void Executor::apply_tool_length(double mm) {
  const Vec3 m = to_machine(pos);
  tool_length_ = mm;
  modal.tool_length_mm = mm;
  pos = to_program(m);
}

void Executor::set_work_system(const BlockCodes& codes) {
  const int g = codes.code(g_coordinate);
  if (g < 0) return;
  const int index = g <= 590 ? (g - 540) / 10 + 1 : 6 + (g - 590);
  const Vec3 m = to_machine(pos);
  const ExtraAxes xm = extra_to_machine(xpos);
  modal.work_offset = index;
  pos = to_program(m);
  xpos = xto = extra_to_program(xm);
}

void Executor::set_path_control(const BlockCodes& codes) {
  const int g = codes.code(g_path);
  if (g < 0) return;
  modal.path_control = g == 640 ? PathControl::blend : g == 610 ? PathControl::exact_path : PathControl::exact_stop;
  if (g == 640) {
    modal.blend_tolerance_mm = w->has('P') ? w->get('P') * scale() : 0.0;
    modal.naive_cam_tolerance_mm = w->has('Q') ? w->get('Q') * scale() : modal.blend_tolerance_mm;
    if (modal.blend_tolerance_mm < 0.0 || modal.naive_cam_tolerance_mm < 0.0)
      fail(codes.column(g_path), "tolerance-range", "G64 P Q: tolerances must be >= 0");
  }
}

void Executor::set_distance_modes(const BlockCodes& codes) {
  if (codes.code(g_distance) >= 0)
    modal.distance = codes.code(g_distance) == 900 ? DistanceMode::absolute : DistanceMode::incremental;
  if (codes.code(g_arc_distance) >= 0)
    modal.arc_distance = codes.code(g_arc_distance) == 901 ? DistanceMode::absolute : DistanceMode::incremental;
}

void Executor::set_retract_mode(const BlockCodes& codes) {
  if (codes.code(g_retract) >= 0)
    modal.retract = codes.code(g_retract) == 980 ? RetractMode::initial_z : RetractMode::r_plane;
}

void Executor::set_spindle_mode(const BlockCodes& codes) {
  if (codes.code(g_spindle_mode) == 960)
    warn(codes.column(g_spindle_mode), "G96: constant surface speed is recorded, not simulated (the path feed is unchanged)");
}

void Executor::reject_spline_end(const BlockCodes& codes) {
  if (codes.code(g_spline_end) >= 0)
    fail(codes.column(g_spline_end), "g53-without-g52", "G5.3: no NURBS block is open (G5.2 missing)");
}

// ---------------------------------------------------------------- motion (group 1) and program end (M group 4)

void Executor::run_motion(const BlockCodes& codes, bool machine_coordinates) {
  const int nonmodal = codes.code(g_nonmodal);
  const int motion_word = codes.code(g_motion);
  const bool nonmodal_uses_axes = nonmodal == 100 || nonmodal == 280 || nonmodal == 300 || nonmodal == 920 ||
                                  codes.code(g_tool_length) == 431;
  if (codes.code(g_tool_length) == 431 && motion_word >= 0 && motion_word != motion_none)
    fail(codes.column(g_tool_length), "axis-words",
         fmt::format("G43.1 and {} in one block: both use the axis words", g_name(motion_word)));
  int motion = modal.motion_g10;
  if (motion_word >= 0) motion = motion_word;
  if (motion == 0 || motion == 10 || motion == 20 || motion == 30) group01_motion = motion;
  // Fanuc's G80 cancels the cycle only: the G0 / G1 / G2 / G3 before it is the motion mode again.
  if (motion_word == motion_none && rules_.g80_restores_motion && group01_motion >= 0) motion = group01_motion;
  if (w->keyword == Keyword::cip) motion = motion_cip;
  if (w->keyword == Keyword::conic) motion = motion_conic;
  if (w->keyword == Keyword::ct) motion = motion_ct;
  const bool starts_motion = motion_word >= 0 || w->keyword != Keyword::none;
  const int motion_col =
      motion_word >= 0 ? codes.column(g_motion) : w->keyword != Keyword::none ? w->keyword_column : block_column();
  const bool axes_for_motion = has_axes() && !nonmodal_uses_axes;
  const bool is_cycle = is_canned_cycle(motion);
  if (is_cycle && !is_canned_cycle(modal.motion_g10)) {
    cycle_old_z = pos.z();
    cycle_r_set = cycle_z_set = cycle_q_set = false;
  }
  if (motion_word >= 0 || w->keyword != Keyword::none) modal.motion_g10 = motion;

  if (axes_for_motion || starts_motion || (is_cycle && (w->has('R') || has_axes()))) {
    if (motion == motion_none) {
      if (axes_for_motion)
        fail(block_column(), "axis-words", "axis words without a motion command (G80 cancelled the motion mode)");
    } else if (axes_for_motion || motion == 52 || (motion == 62 && w->has('K')) || is_cycle ||
               w->keyword != Keyword::none) {
      move(motion, motion_col, machine_coordinates, motion_word);
    }
  }

  warn_unused_words(motion, nonmodal, codes.code(g_path), codes.code(g_tool_length), axes_for_motion || starts_motion,
                    codes.code(g_cutter));
}

void Executor::end_if_program_end(const BlockCodes& codes) {
  const int m = codes.m_code(m_stop);
  if (m == 2 || m == 30) {
    program_end_seen_ = true;
    end_program();
  }
}

void Executor::warn_unused_words(int motion, int nonmodal, int path, int tool_length, bool moved, int cutter) {
  std::string used = "FSTN";  // always meaningful
  auto add = [&](const char* letters) { used += letters; };
  const bool cycle = is_canned_cycle(motion);
  if (moved || nonmodal == 100 || nonmodal == 280 || nonmodal == 300 || nonmodal == 920) add("XYZABCUVW");
  if (moved) {
    if (motion == 20 || motion == 30) add("IJKRP");
    if (motion == 50 || motion == 51) add("IJPQ");
    if (motion == 52) add("PL");
    if (motion == 62) add("KRPQ");
    if (cycle) add("RZPQL");
  }
  if (cycle) add(rules_.fanuc_cycles ? "RPQLK" : "RPQL");  // sticky cycle words on a block without a hole
  if (nonmodal == 40) add("P");
  if (nonmodal == 100) add("LPR");
  if (path == 640) add("PQ");
  if (tool_length == 430 || tool_length == 432) add("H");
  if (tool_length == 431) add("Z");
  if (cutter == 410 || cutter == 420 || cutter == 411 || cutter == 421) add(rules_.fanuc_offset_registers ? "DH" : "D");
  for (int c = 0; c < 26; ++c) {
    const char letter = static_cast<char>('A' + c);
    if (letter == 'G' || letter == 'M' || !w->has(letter) || used.find(letter) != std::string::npos) continue;
    warn(w->col(letter), fmt::format("{}{}: not used by any code of this block (ignored)", letter, num(w->get(letter))));
  }
}

void Executor::move(int motion, int col, bool machine_coordinates, int motion_word) {
  const Vec3 to = target(machine_coordinates);
  // the extra axes move linearly along lines, arcs and helices; curves whose points come from
  // several words or blocks have no place for them
  if (motion == 50 || motion == 51 || motion == 52 || motion == 62)
    refuse_extra_words(g_name(motion), "in a spline: its control points are X Y Z (move the extra axes in a block of "
                                       "their own)");
  if (motion == 24 || motion == 34 || motion == motion_cip || motion == motion_conic) {
    const std::string word = motion == motion_cip     ? std::string("CIP")
                             : motion == motion_conic ? std::string("CONIC")
                                                      : g_name(motion, true);
    refuse_extra_words(word, "in a circle or conic through intermediate points (move them in a block of their own)");
  }
  if (is_canned_cycle(motion))
    refuse_extra_words(g_name(motion), "in a canned cycle (LinuxCNC moves them before the first hole; move them in "
                                       "a block of their own)");
  if (arc_not_allowed_ && (motion == 20 || motion == 30))
    fail(col, "arc-after-compensation",
         fmt::format("{}: the move just after G40 (leaving cutter radius compensation) must be straight, not an arc "
                     "(LinuxCNC's rule)",
                     g_name(motion)));
  arc_not_allowed_ = false;
  xto = extra_target(machine_coordinates);
  if (motion != 50 && motion != 51) prev_g5 = false;
  switch (motion) {
    case 0: line_move(BlockType::rapid, to, col, Feed{}); prev_g5 = false; return;
    case 10: line_move(BlockType::line, to, col, feed_move("G1")); prev_g5 = false; return;
    case 20: case 30:
      if (w->has_arc_angle) arc_by_angle(motion == 20, to, col);
      else arc(motion == 20, to, col);
      prev_g5 = false;
      return;
    case 50: case 51: bezier(motion == 50, to, col); return;
    case 52: start_g52(col); return;
    case 62: start_g62(col, motion_word); return;
    case 24: case 34: circle_block(motion, col); return;
    case motion_cip: cip(to, col); return;
    case motion_ct: tangent_arc(to, col); return;
    case motion_conic: conic(to, col); return;
    case 730: case 810: case 820: case 830: case 840: case 850: case 860: case 890: cycle(motion, col); return;
    default: break;
  }
  fail(col, "internal", fmt::format("motion mode {} not handled", g_name(motion)));
}

}  // namespace kontur::gcode::detail
