#pragma once
// Internal: the G-code interpreter behind Reader, its state and the handlers of each kind of
// block. reader.cpp reads the lines and runs the codes of a block in LinuxCNC's order;
// arc_blocks.cpp (G2/G3, CIP, G02.4, CONIC), spline_blocks.cpp (G5, G5.1, G5.2/G5.3,
// G06.2/G6.2), canned_cycles.cpp (G73, G81-G83) and o_words.cpp (LinuxCNC control flow) do the rest.
#include <kontur/error.hpp>
#include <kontur/gcode/reader.hpp>
#include <kontur/tolerances.hpp>

#include "line_parser.hpp"

#include <Eigen/Geometry>
#include <fmt/format.h>

#include <array>
#include <cstdio>
#include <initializer_list>
#include <map>
#include <numbers>
#include <string>
#include <vector>

namespace kontur::gcode {
namespace detail {


inline constexpr double pi = std::numbers::pi;
inline constexpr std::size_t read_chunk = 1 << 20;  // bytes read from the file at a time

// Motion modes beyond G codes.
inline constexpr int motion_cip = 10000;
inline constexpr int motion_conic = 10001;
inline constexpr int motion_none = 800;  // G80

inline std::string g_name(int g10, bool leading_zero = false) {
  const int whole = g10 / 10, tenth = g10 % 10;
  const char* zero = leading_zero && whole < 10 ? "0" : "";
  if (tenth == 0) return fmt::format("G{}{}", zero, whole);
  return fmt::format("G{}{}.{}", zero, whole, tenth);
}

inline std::string num(double v) {
  if (v == 0.0) v = 0.0;
  return fmt::format("{:.6g}", v);
}
inline std::string point_text(const Vec3& p) { return fmt::format("({}, {}, {})", num(p.x()), num(p.y()), num(p.z())); }

// Axes of a plane: first, second, normal (indices into x y z).
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

}  // namespace detail

using detail::g_name;
using detail::Keyword;
using detail::motion_cip;
using detail::motion_conic;
using detail::motion_none;
using detail::num;
using detail::pi;
using detail::plane_axes;
using detail::PlaneAxes;
using detail::point_text;
using detail::read_chunk;
using detail::unit;
using detail::Words;

struct Reader::Impl {
  // ---------------------------------------------------------------- input
  std::shared_ptr<const std::string> name;
  ReaderOptions opt;
  std::FILE* file = nullptr;
  std::string memory;
  std::vector<char> buf;
  std::size_t begin = 0, end = 0;
  std::size_t buffer_offset = 0;  // bytes of the file before buf[0]
  bool input_eof = false;
  long line_no = 0;

  // ---------------------------------------------------------------- parsing buffers
  detail::NormalizedLine nl;
  Words w;
  std::vector<detail::Assignment> assignments;
  std::size_t assignment_count = 0;
  ParameterTable params;
  detail::LineContext ctx;

  // ---------------------------------------------------------------- interpreter state
  ModalState modal;
  Vec3 pos = Vec3::Zero();  // program coordinates [mm]
  std::array<Vec3, 10> work_offset{};  // [1..9] G54..G59.3 [mm]
  std::array<double, 10> work_rotation_deg{};
  Vec3 g92 = Vec3::Zero();
  Vec3 g92_saved = Vec3::Zero();
  double feed_mm_per_min = 0.0;
  bool tape = false;       // the program started with '%'
  bool seen_block = false;
  bool ended = false;
  bool program_end_seen = false;
  bool q_warned = false;

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
  std::size_t head = 0;
  std::vector<std::string> warnings;
  std::size_t warning_count = 0;

  Impl(std::string_view n, ReaderOptions o) : name(std::make_shared<const std::string>(n)), opt(o) {
    for (auto& v : work_offset) v.setZero();
    ctx.file = *name;
  }
  ~Impl() {
    if (file) std::fclose(file);
  }
  Impl(const Impl&) = delete;
  Impl& operator=(const Impl&) = delete;

  // ================================================================ input
  void open(const std::string& path);
  void open_memory(std::string text);
  const char* data() const noexcept { return file ? buf.data() : memory.data(); }
  // Reads more of the file into the buffer (keeping [begin, end)).
  void fill();
  // A NUL byte anywhere means a binary file: say so instead of reporting a syntax error.
  void check_text(std::size_t from) const;
  // Offset in the input of the next line to read, and of the line last read.
  std::size_t tell() const noexcept { return buffer_offset + begin; }
  std::size_t line_start = 0;
  // Continues reading at `offset` (a line start seen before), as line `line` - 1 was just read.
  void seek(std::size_t offset, long line);
  bool read_line(std::string_view& out);

  // ================================================================ helpers
  [[noreturn]] void fail(int column, const char* rule, const std::string& message) const {
    detail::fail_column(ctx, column, rule, message);
  }
  void warn(int column, const std::string& message) {
    ++warning_count;
    if (warnings.size() < opt.max_warnings_kept)
      warnings.push_back(fmt::format("{}:{}:{}: warning: {}", *name, line_no, column, message));
  }
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
    return SourceLocation{name, line_no, column > 0 ? column : 1, w.n_number};
  }
  Eigen::Matrix3d rotation() const {
    const double a = work_rotation_deg[static_cast<std::size_t>(modal.work_offset)] * pi / 180.0;
    Eigen::Matrix3d r = Eigen::Matrix3d::Identity();
    if (a != 0.0) r = Eigen::AngleAxisd(a, Vec3::UnitZ()).toRotationMatrix();
    return r;
  }
  Vec3 to_machine(const Vec3& p) const {
    return rotation() * (p + g92) + work_offset[static_cast<std::size_t>(modal.work_offset)];
  }
  Vec3 to_program(const Vec3& m) const {
    return rotation().transpose() * (m - work_offset[static_cast<std::size_t>(modal.work_offset)]) - g92;
  }
  Block make_block(BlockType type, int column) const {
    Block b;
    b.type = type;
    b.modal = modal;
    b.location = location(column);
    return b;
  }
  void emit(Block&& b) {
    check_point(b.start, b.location.column);
    check_point(b.end, b.location.column);
    for (int i = 0; i < b.via_count; ++i) check_point(b.via[static_cast<std::size_t>(i)], b.location.column);
    queue.push_back(std::move(b));
  }
  void check_point(const Vec3& p, int column) const {
    const double m = tolerances::gcode_max_coordinate_mm;
    if (!(p.allFinite() && p.cwiseAbs().maxCoeff() <= m))
      fail(column, "coordinate-range",
           fmt::format("the point {} mm is beyond the supported range of +-{} mm", point_text(p), num(m)));
  }
  int block_column() const { return w.first_column > 0 ? w.first_column : 1; }

  // The axis words X Y Z of the block as a target in program coordinates [mm].
  Vec3 target(bool machine_coordinates = false) const {
    Vec3 t = pos;
    const char letters[3] = {'X', 'Y', 'Z'};
    if (machine_coordinates) {  // G53: absolute machine coordinates for this block
      Vec3 m = to_machine(pos);
      for (int a = 0; a < 3; ++a)
        if (w.has(letters[a])) m[a] = w.get(letters[a]) * scale();
      return to_program(m);
    }
    for (int a = 0; a < 3; ++a)
      if (w.has(letters[a])) {
        const double v = w.get(letters[a]) * scale();
        t[a] = modal.distance == DistanceMode::absolute ? v : pos[a] + v;
      }
    return t;
  }
  bool has_axes() const noexcept { return w.has('X') || w.has('Y') || w.has('Z'); }

  // Feed of a feed move (not rapid); errors if none is in effect.
  Feed feed_move(const std::string& what) const {
    if (modal.feed_mode == FeedMode::inverse_time) {
      if (!w.has('F'))
        fail(block_column(), "feed-missing",
             fmt::format("{}: F missing: with G93 (inverse time) every feed move needs its own F", what));
      return Feed{FeedMode::inverse_time, w.get('F')};
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

  // ================================================================ line processing
  void process_line(std::string_view raw);

  // ================================================================ O-words (LinuxCNC control flow)
  // Subroutines (sub/endsub/call/return), loops (while/endwhile, do/while, repeat/endrepeat,
  // break, continue) and conditionals (if/elseif/else/endif). The reader streams: a loop or a call
  // seeks back to a line start it has seen; only the open frames and the subroutines' start
  // offsets are kept.
  enum class OKind { sub, endsub, call, ret, while_, endwhile, do_, repeat, endrepeat, if_, elseif, else_, endif,
                     break_, continue_ };
  struct OWord {
    std::string label;
    OKind kind = OKind::sub;
    std::size_t rest = 0;  // position in nl.text after the keyword
  };
  struct Frame {
    OKind kind;            // while_, do_, repeat, if_, call
    std::string label;
    std::size_t offset;    // while: the while line; do/repeat: the line after; call: the return line
    long line;
    long count = 0;        // repeat: iterations left; loops: iterations done
    std::array<double, 30> saved{};  // call: #1..#30 of the caller
    int call_column = 1;
  };
  struct SubStart {
    std::size_t offset;
    long line;
  };
  std::vector<Frame> frames;
  std::map<std::string, SubStart, std::less<>> subs;

  OWord parse_oword(const detail::NormalizedLine& line) const;
  double o_value(const OWord& o, std::size_t& at, const char* what) const;
  void o_end_of_line(std::size_t at) const;

  // Reads lines without running them until the O-word `label` with one of `kinds`; leaves nl at it.
  OWord skip_to(const std::string& label, std::initializer_list<OKind> kinds, const char* what);
  [[noreturn]] void fail_column(long line, int column, const char* rule, const std::string& message) const {
    throw InputError(rule, fmt::format("{}:{}:{}: {}", *name, line, column, message));
  }
  Frame* find_frame(const std::string& label);
  long loop_iterations = 0;  // O-word loop iterations and calls so far
  void loop_guard(const std::string& label);

  void control_flow();

  void end_program();

  void finish_spline_at_end();

  [[noreturn]] void fail_spline(const char* rule, const std::string& message) const {
    throw InputError(rule, fmt::format("{}:{}:{}: {}", *name, spline_loc.line, spline_loc.column, message));
  }

  // ================================================================ block execution
  void check_values() const;

  void execute();

  // A word that no code of the block uses is ignored with a warning (a control would raise an
  // alarm for some; the specification asks for a warning).
  void warn_unused_words(int motion, int nonmodal, int path, int tool_length, bool moved);

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

  // ---- canned cycles G73, G81, G82, G83 (XY plane), expanded into moves
  void cycle(int motion, int col);

  // ---- G10 L2 / L20 (work offsets), L1 / L10 / L11 (tool table, recorded only)
  void g10(int col);

  // ---- G28 / G30: rapid through the given point to the stored home position
  void home(int g, int col);
};

}  // namespace kontur::gcode
