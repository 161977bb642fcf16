#pragma once
// Internal: the dialect-neutral executor. It runs the words of one block (detail::Words, from a
// dialect front end) in LinuxCNC's order (executor.cpp: values checked, codes sorted into modal
// groups, then feed mode, units, F, S / T / M, dwell, plane, tool length, work system, path
// control, distance modes, non-modal codes, motion, program end), keeps the modal state and the
// coordinate frames, and turns motion into gcode::Blocks with their geometry. It knows nothing of
// how a dialect spells things. The handlers are spread by kind: non-modal codes
// (nonmodal_codes.cpp: G4, G10, G28/G30, G92), arcs, CIP, G02.4 and CONIC (arc_blocks.cpp),
// splines (spline_blocks.cpp), drilling cycles (canned_cycles.cpp).
#include "block_words.hpp"
#include "coordinate_frames.hpp"
#include "diagnostics.hpp"
#include "dialect_front_end.hpp"
#include "message_format.hpp"
#include "modal_groups.hpp"

#include <kontur/error.hpp>
#include <kontur/gcode/block.hpp>
#include <kontur/gcode/expression.hpp>
#include <kontur/gcode/tool_table.hpp>
#include <kontur/tolerances.hpp>

#include <array>
#include <cmath>
#include <map>
#include <numbers>
#include <set>
#include <string>
#include <vector>

namespace kontur::gcode::detail {

inline constexpr double pi = std::numbers::pi;

/// Axes of a plane: first, second, normal (indices into x y z).
struct PlaneAxes {
  int a1, a2, n;
};
inline PlaneAxes plane_axes(Plane p) {
  switch (p) {
    case Plane::xy: return {0, 1, 2};
    case Plane::zx: return {2, 0, 1};
    case Plane::yz: return {1, 2, 0};
  }
  return {0, 1, 2};
}
inline Vec3 unit(int axis) { return Vec3::Unit(axis); }

class Executor final : public ControlFlowBarrier, public ExecutorState {
public:
  /// Reports through `diagnostics`; G28.1 / G30.1 store and G28 / G30 read the home positions in
  /// `parameters` #5161-#5163 and #5181-#5183.
  Executor(Diagnostics& diagnostics, ParameterTable& parameters) : diag(diagnostics), params(parameters) {}
  Executor(const Executor&) = delete;
  Executor& operator=(const Executor&) = delete;

  /// The rules of the program's dialect (before the first block; LinuxCNC's by default).
  void set_rules(const DialectRules& rules) noexcept { rules_ = rules; }
  /// The absolute tolerances of a centre-format arc's radii in mm programs [mm] and inch programs
  /// [in] (ReaderOptions::arc_radius_tolerance_*).
  void set_arc_radius_tolerances(double mm, double inch) noexcept {
    arc_tolerance_mm_ = mm;
    arc_tolerance_inch_ = inch;
  }
  /// The tool table of the run (ReaderOptions::tool_table; nullptr: none given). Copied: G10 L1 /
  /// L10 / L11 change the run's copy.
  void set_tool_table(const ToolTable* table) {
    if (table == nullptr) return;
    tools_ = *table;
    has_table_ = true;
  }
  /// Runs one block; its blocks are appended to blocks(). Throws InputError at the first error.
  /// `words` must stay valid until the next call (a spline or circle may refer to it).
  void execute(const Words& words);
  /// The program ends here (M2 / M30 ran, or the dialect's end mark, or the input's end): a
  /// spline being collected is finished, a missing end point or G5.3 is an error.
  void end_program();
  void before_control_flow(int column) override;

  /// True once the program has ended (end_program() or M2 / M30).
  [[nodiscard]] bool ended() const noexcept { return ended_; }
  /// True once M2 or M30 ran.
  [[nodiscard]] bool program_end_seen() const noexcept { return program_end_seen_; }
  /// The blocks made so far and not yet taken (the caller clears it).
  [[nodiscard]] std::vector<Block>& blocks() noexcept { return queue; }
  /// The modal state now.
  [[nodiscard]] const ModalState& modal_state() const noexcept override { return modal; }
  /// The current position in program coordinates [mm].
  [[nodiscard]] const Vec3& position() const noexcept override { return pos; }
  /// The current position in machine coordinates [mm].
  [[nodiscard]] Vec3 machine_position() const override { return to_machine(pos); }
  [[nodiscard]] int group01_code() const noexcept override { return group01_motion > 0 ? group01_motion / 10 : 0; }
  [[nodiscard]] double feed_rate() const noexcept override { return feed_mm_per_min; }
  [[nodiscard]] Vec3 work_offset(int system) const override {
    // to_machine(p) = R (p + g92) + offset and offset_placing(0, p) = -R (p + g92)
    return frames.to_machine(Vec3::Zero(), system) + frames.offset_placing(Vec3::Zero(), Vec3::Zero(), system);
  }
  // work system 0 has no offset and no rotation: what remains is the G92 offset
  [[nodiscard]] Vec3 g92_offset() const override { return frames.to_machine(Vec3::Zero(), 0); }
  void set_work_offset(int system, int axis, double mm) override {
    const Vec3 m = to_machine(pos);
    frames.set_offset(system, axis, mm);
    if (system == modal.work_offset) pos = to_program(m);
  }

private:
  // ================================================================ state
  Diagnostics& diag;
  ParameterTable& params;
  const Words* w = &no_words;  // the block being run
  static const Words no_words;

  ModalState modal;
  DialectRules rules_;
  double arc_tolerance_mm_ = tolerances::gcode_arc_radius_absolute_mm;      // [mm]
  double arc_tolerance_inch_ = tolerances::gcode_arc_radius_absolute_inch;  // [in]
  int group01_motion = -1;  // the last G0 / G1 / G2 / G3 motion mode (times 10), -1 before one
  Vec3 pos = Vec3::Zero();  // program coordinates [mm]
  // The extra axes A B C [deg] U V W [mm] in program coordinates: where they are (xpos) and where
  // the next block made goes (xto; xpos again when it is made). A block's words set xto (move,
  // G28 / G30); every other block keeps the extra axes still.
  ExtraAxes xpos{};
  ExtraAxes xto{};
  CoordinateFrames frames;
  // tools: the run's table (G10 L1 writes it), whether one was given, the Fanuc family's wear
  // registers (G10 L11 / L13) and the tool length offset applied along Z [mm]
  ToolTable tools_;
  bool has_table_ = false;
  std::map<int, double> h_wear_, d_wear_;
  double tool_length_ = 0.0;
  int selected_tool_ = 0;  // the last T (M6 loads it)
  bool arc_not_allowed_ = false;  // G40 ended compensation: the next move must be straight (LinuxCNC)
  double feed_mm_per_min = 0.0;
  bool ended_ = false;
  bool program_end_seen_ = false;
  bool q_warned = false;
  bool tapping_warned = false;  // G84 read as feed in and out (warned once)
  std::set<int> warned_m_codes;  // M codes ignored so far (each warned once)

  // splines
  enum class Spline { none, g62, g52 } spline = Spline::none;
  NurbsData nurbs;
  int rank = 4;
  int end_knots = 0;
  SourceLocation spline_loc;
  std::string spline_word;
  Feed spline_feed;
  ModalState spline_modal;
  Vec3 spline_start = Vec3::Zero();
  Vec3 last_point = Vec3::Zero();  // program coordinates of the last control point
  std::vector<long> knot_line;     // line of every knot, for messages

  // G5 tangent continuation: second control point of the previous G5, relative to its end [mm]
  bool prev_g5 = false;
  Vec3 prev_g5_pq = Vec3::Zero();

  // G02.4 / G03.4 pending intermediate point (program coordinates)
  bool circle_pending = false;
  Vec3 circle_mid = Vec3::Zero();
  SourceLocation circle_loc;
  int circle_g = 24;

  // canned cycles
  double cycle_old_z = 0.0;
  double cycle_r = 0.0, cycle_z = 0.0, cycle_q = 0.0, cycle_p = 0.0;
  bool cycle_r_set = false, cycle_z_set = false, cycle_q_set = false;

  // output
  std::vector<Block> queue;

  // ================================================================ helpers
  [[noreturn]] void fail(int column, const char* rule, const std::string& message) const {
    diag.fail(column, rule, message);
  }
  void warn(int column, const std::string& message) { diag.warn(column, message); }
  // Re-throws a location-free InputError of a geometry helper with the block's location and word.
  template <class F>
  auto at(int column, const std::string& word, F&& f) -> decltype(f()) {
    try {
      return f();
    } catch (const InputError& e) {
      fail(column, e.rule().c_str(), fmt::format("{}: {}", word, e.what()));
    }
  }
  double scale() const noexcept { return modal.units == Units::inch ? 25.4 : 1.0; }
  SourceLocation location(int column) const {
    return SourceLocation{diag.name(), diag.line(), column > 0 ? column : 1, w->n_number};
  }
  Eigen::Matrix3d rotation() const { return frames.linear(modal.work_offset); }
  // machine = the work coordinates' point + the tool length along Z (LinuxCNC's G43); the offset is
  // only added when it is not 0, so that programs without one keep their exact numbers
  Vec3 to_machine(const Vec3& p) const {
    Vec3 m = frames.to_machine(p, modal.work_offset);
    if (tool_length_ != 0.0) m.z() += tool_length_;
    return m;
  }
  Vec3 to_program(const Vec3& m) const {
    if (tool_length_ == 0.0) return frames.to_program(m, modal.work_offset);
    return frames.to_program(Vec3(m.x(), m.y(), m.z() - tool_length_), modal.work_offset);
  }
  ExtraAxes extra_to_machine(const ExtraAxes& p) const { return frames.extra_to_machine(p, modal.work_offset); }
  ExtraAxes extra_to_program(const ExtraAxes& m) const { return frames.extra_to_program(m, modal.work_offset); }
  // The unit factor of extra axis i: U V W are lengths (G20: inch), A B C angles [deg] (never scaled).
  double extra_scale(int i) const noexcept { return i >= 3 ? scale() : 1.0; }
  Block make_block(BlockType type, int column) const {
    Block b;
    b.type = type;
    b.modal = modal;
    b.location = location(column);
    b.frame_linear = rotation();
    b.frame_origin = to_machine(Vec3::Zero());
    return b;
  }
  // Appends a block; its extra axes go from xpos to xto (machine coordinates), and are at xto after it.
  void emit(Block&& b) {
    b.extra_start = extra_to_machine(xpos);
    b.extra_end = extra_to_machine(xto);
    check_extra(b.extra_start, b.location.column);
    check_extra(b.extra_end, b.location.column);
    check_point(b.start, b.location.column);
    check_point(b.end, b.location.column);
    for (int i = 0; i < b.via_count; ++i) check_point(b.via[static_cast<std::size_t>(i)], b.location.column);
    if (const Curve* c = b.curve()) {  // the direction at the end, for an arc tangent to it (CT)
      const Vec3 d = c->derivatives_left(c->u_max(), 1)[1];
      if (d.norm() > 0.0) end_tangent = d.normalized();
    }
    queue.push_back(std::move(b));
    xpos = xto;
  }
  void check_point(const Vec3& p, int column) const {
    const double m = tolerances::gcode_max_coordinate_mm;
    if (!(p.allFinite() && p.cwiseAbs().maxCoeff() <= m))
      fail(column, "coordinate-range",
           fmt::format("the point {} mm is beyond the supported range of +-{} mm", point_text(p), num(m)));
  }
  void check_extra(const ExtraAxes& e, int column) const {
    for (int i = 0; i < extra_axis_count; ++i) {
      const double v = e[static_cast<std::size_t>(i)];
      const double m = i >= 3 ? tolerances::gcode_max_coordinate_mm : tolerances::gcode_max_value;
      if (!(std::abs(v) <= m))
        fail(column, "coordinate-range",
             fmt::format("{} {} {}: beyond the supported range of +-{} {}", extra_axis_letters[i], num(v),
                         i >= 3 ? "mm" : "deg", num(m), i >= 3 ? "mm" : "deg"));
    }
  }
  int block_column() const { return w->first_column > 0 ? w->first_column : 1; }

  // The block's first extra axis word (A B C U V W), or 0.
  char extra_word() const noexcept {
    for (int i = 0; i < extra_axis_count; ++i)
      if (w->has(extra_axis_letters[i])) return extra_axis_letters[i];
    return 0;
  }
  // Refuses the block's extra axis words where they cannot move: "`what` A10: extra axes ... `why`".
  void refuse_extra_words(const std::string& what, const char* why) const {
    if (const char c = extra_word())
      fail(w->col(c), "unsupported",
           fmt::format("{}{}{}: extra axes (A B C U V W) are not supported {}", what, what.empty() ? "" : " ",
                       word_text(c), why));
  }
  std::string word_text(char c) const { return fmt::format("{}{}", c, num(w->get(c))); }
  // The extra axis words of the block as a target in program coordinates (G53: the words are
  // machine coordinates).
  ExtraAxes extra_target(bool machine_coordinates = false) const {
    ExtraAxes t = xpos;
    if (machine_coordinates) {
      ExtraAxes m = extra_to_machine(xpos);
      for (int i = 0; i < extra_axis_count; ++i)
        if (w->has(extra_axis_letters[i]))
          m[static_cast<std::size_t>(i)] = w->get(extra_axis_letters[i]) * extra_scale(i);
      return extra_to_program(m);
    }
    for (int i = 0; i < extra_axis_count; ++i) {
      const char letter = extra_axis_letters[i];
      if (!w->has(letter)) continue;
      const auto k = static_cast<std::size_t>(i);
      const double v = w->get(letter) * extra_scale(i);
      t[k] = w->absolute(letter, modal.distance == DistanceMode::absolute) ? v : xpos[k] + v;
    }
    return t;
  }

  // The axis words X Y Z of the block as a target in program coordinates [mm].
  Vec3 target(bool machine_coordinates = false) const {
    Vec3 t = pos;
    const char letters[3] = {'X', 'Y', 'Z'};
    if (machine_coordinates) {  // G53: absolute machine coordinates for this block
      Vec3 m = to_machine(pos);
      for (int a = 0; a < 3; ++a)
        if (w->has(letters[a])) m[a] = w->get(letters[a]) * scale();
      return to_program(m);
    }
    for (int a = 0; a < 3; ++a)
      if (w->has(letters[a])) {
        const double v = w->get(letters[a]) * scale();
        t[a] = w->absolute(letters[a], modal.distance == DistanceMode::absolute) ? v : pos[a] + v;
      }
    if (w->polar != 0) t = polar_target(t);
    return t;
  }
  // X Y Z, polar words or an extra axis word (A B C U V W)
  bool has_axes() const noexcept {
    return w->has('X') || w->has('Y') || w->has('Z') || w->polar != 0 || extra_word() != 0;
  }

  // Feed of a feed move (not rapid); errors if none is in effect.
  Feed feed_move(const std::string& what) const {
    if (modal.feed_mode == FeedMode::inverse_time) {
      if (!w->has('F'))
        fail(block_column(), "feed-missing",
             fmt::format("{}: F missing: with G93 (inverse time) every feed move needs its own F", what));
      return Feed{FeedMode::inverse_time, w->get('F')};
    }
    if (!(feed_mm_per_min > 0.0))
      fail(block_column(), "feed-missing", fmt::format("{}: feed rate is zero (no F given before the first feed move)", what));
    return Feed{FeedMode::units_per_minute, feed_mm_per_min};
  }

  void line_move(BlockType type, const Vec3& to, int column, const Feed& feed, int cycle = 0) {
    Block b = make_block(type, column);
    b.start = to_machine(pos);
    b.end = to_machine(to);
    b.geometry.emplace<LineSegment>(b.start, b.end);
    b.feed = type == BlockType::rapid ? Feed{} : feed;
    b.canned_cycle = cycle;
    emit(std::move(b));
    pos = to;
  }

  // ================================================================ the block, step by step (executor.cpp)
  void check_values() const;
  void check_circle_end_block() const;
  void check_words_allowed(const BlockCodes& codes) const;
  // one small function per modal group, in the order they run
  void set_feed_mode(const BlockCodes& codes);
  void set_units(const BlockCodes& codes);
  void set_feed_rate();
  void set_spindle_speed();
  void set_tool(const BlockCodes& codes);
  void set_spindle(const BlockCodes& codes);
  void set_coolant(const BlockCodes& codes);
  void warn_io_codes(const BlockCodes& codes);
  // M codes the tables do not know (machine-specific, user M100-M199): a warning once per code.
  void warn_ignored_m_codes(const BlockCodes& codes);
  void set_plane(const BlockCodes& codes);
  void set_cutter_comp(const BlockCodes& codes);
  // The Fanuc family's G41 / G42 H n without D (Fanuc 0M): H names the radius register.
  bool cutter_register_h(const BlockCodes& codes) const;
  void set_tool_length(const BlockCodes& codes);
  // The tool length offset becomes `mm`; the machine stays where it is (the program position changes).
  void apply_tool_length(double mm);
  // The length [mm] of tool / H register `n` (`word` names it in messages): 0 for n = 0, and when no
  // table is given; not in a given table: an error.
  double tool_length_of(int n, int column, const std::string& word) const;
  // The radius [mm] of tool / D register `n` for G41 / G42; not in the table (or no table): an error.
  double tool_radius_of(int n, int column, const std::string& word) const;
  // The integer >= 0 of word `letter` (H, D, P of G10), or an error.
  int register_word(char letter, const char* what) const;
  void set_work_system(const BlockCodes& codes);
  void set_path_control(const BlockCodes& codes);
  void set_distance_modes(const BlockCodes& codes);
  void set_retract_mode(const BlockCodes& codes);
  void set_spindle_mode(const BlockCodes& codes);
  void reject_spline_end(const BlockCodes& codes);
  void run_motion(const BlockCodes& codes, bool machine_coordinates);
  void end_if_program_end(const BlockCodes& codes);

  // A word that no code of the block uses is ignored with a warning (a control would raise an
  // alarm for some; the specification asks for a warning).
  void warn_unused_words(int motion, int nonmodal, int path, int tool_length, bool moved, int cutter);

  void finish_spline_at_end();
  [[noreturn]] void fail_spline(const char* rule, const std::string& message) const {
    diag.fail_at_line(spline_loc.line, spline_loc.column, rule, message);
  }

  // ================================================================ non-modal codes (nonmodal_codes.cpp)
  // Runs the block's non-modal code; true for G53 (this block's axis words are machine coordinates).
  bool run_nonmodal(const BlockCodes& codes);
  // G4 P: a dwell block
  void dwell(int col);
  // G10 L2 / L20 (work offsets), L1 / L10 / L11 (tool table, recorded only)
  void g10(int col);
  // G10 L1 / L10 / L11 (LinuxCNC), L10..L13 (the Fanuc family's registers)
  void g10_tool(int l, int col);
  // G28 / G30: rapid through the given point to the stored home position
  void home(int g, int col);
  // G28.1 / G30.1: store the current position as home
  void store_home(int g);
  // G92, G92.1, G92.2, G92.3
  void g92(int g, int col);

  // ================================================================ motion
  void move(int motion, int col, bool machine_coordinates, int motion_word);

  // G2 / G3 in the selected plane, with I J K (centre) or R (radius), P turns, helices.
  void arc(bool clockwise, const Vec3& to, int col);

  // G5 cubic / G5.1 quadratic Bezier (LinuxCNC; XY plane), as a clamped B-spline.
  void bezier(bool cubic, const Vec3& to, int col);

  // ---- G5.2 / G5.3 (LinuxCNC NURBS block)
  void start_g52(int col);
  void add_control_point(const Vec3& p, double weight);
  void finish_g52();
  void emit_spline(BlockType type);

  // ---- G06.2 / G6.2 (Fanuc, Mitsubishi, LinuxCNC NURBS)
  void start_g62(int col, int motion_word);
  double weight_word() const;
  void add_knot(double k, int col);
  void finish_g62();

  // Returns true if the block belongs to the spline being collected (and consumed it).
  bool continue_spline();
  void check_spline_words(const char* allowed, const char* word) const;
  void update_feed();

  // ---- circles through an intermediate point
  void emit_circle(const Vec3& mid, const Vec3& to, int col, const std::string& word);
  // The one place that builds the 3-D circle (to switch to the arcs-and-conics issue's API).
  static HelixArc make_circle_3d(const Vec3& r1, const Vec3& r2, const Vec3& r3);
  void circle_block(int motion, int col);
  Vec3 indexed_point(int point) const;
  void cip(const Vec3& to, int col);
  void conic(const Vec3& to, int col);

  // ---- canned cycles G73, G81, G82, G83 (and with DialectRules::fanuc_cycles G84, G85, G86, G89;
  // XY plane), expanded into moves
  void cycle(int motion, int col);

  // ---- the programmable frame (programmable_frame.cpp): a block of a FrameOp alone
  void programmable_frame();
  // ---- polar coordinates and CT (programmable_frame.cpp)
  Vec3 pole = Vec3::Zero();           // program coordinates (in the plane) of the polar pole
  Vec3 end_tangent = Vec3::Zero();    // machine direction at the end of the last move (0: none)
  // G110 / G111 / G112: a block defining the pole alone
  void define_pole();
  // `t` with its plane coordinates from AP= / RP= about the pole (the one not given: the current
  // position's)
  Vec3 polar_target(const Vec3& t) const;
  // CT: an arc from the position to `to`, tangent to the previous move
  void tangent_arc(const Vec3& to, int col);
  // G2 / G3 with AR= (opening angle): with the end point (the radius follows) or with I J K (the
  // end point follows)
  void arc_by_angle(bool clockwise, const Vec3& to, int col);
};

}  // namespace kontur::gcode::detail
