// The G-code interpreter: words of a block -> modal state, coordinates, and blocks with Kontur
// curves. Order of execution within a block follows LinuxCNC (feed mode, units, F, S/T/M,
// dwell, plane, offsets, distance modes, non-modal codes, motion, program end).
#include <kontur/error.hpp>
#include <kontur/gcode/reader.hpp>
#include <kontur/tolerances.hpp>

#include "circle_through_three_points.hpp"
#include "conic_points.hpp"
#include "line_parser.hpp"

#include <Eigen/Geometry>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <map>
#include <numbers>

namespace kontur::gcode {
namespace {

using detail::Keyword;
using detail::Words;

constexpr double pi = std::numbers::pi;
constexpr std::size_t read_chunk = 1 << 20;  // bytes read from the file at a time

// Motion modes beyond G codes.
constexpr int motion_cip = 10000;
constexpr int motion_conic = 10001;
constexpr int motion_none = 800;  // G80

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

std::string g_name(int g10, bool leading_zero = false) {
  const int whole = g10 / 10, tenth = g10 % 10;
  const char* zero = leading_zero && whole < 10 ? "0" : "";
  if (tenth == 0) return fmt::format("G{}{}", zero, whole);
  return fmt::format("G{}{}.{}", zero, whole, tenth);
}

std::string num(double v) {
  if (v == 0.0) v = 0.0;
  return fmt::format("{:.6g}", v);
}
std::string point_text(const Vec3& p) { return fmt::format("({}, {}, {})", num(p.x()), num(p.y()), num(p.z())); }

// Axes of a plane: first, second, normal (indices into x y z).
struct PlaneAxes {
  int a1, a2, n;
};
PlaneAxes plane_axes(Plane p) {
  switch (p) {
    case Plane::xy: return {0, 1, 2};
    case Plane::zx: return {2, 0, 1};
    case Plane::yz: return {1, 2, 0};
  }
  return {0, 1, 2};
}
Vec3 unit(int axis) { return Vec3::Unit(axis); }

}  // namespace

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
  void open(const std::string& path) {
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
  void open_memory(std::string text) {
    memory = std::move(text);
    end = memory.size();
    input_eof = true;
    check_text(0);
  }
  const char* data() const noexcept { return file ? buf.data() : memory.data(); }
  // Reads more of the file into the buffer (keeping [begin, end)).
  void fill() {
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
  // A NUL byte anywhere means a binary file: say so instead of reporting a syntax error.
  void check_text(std::size_t from) const {
    const char* d = data();
    const void* z = std::memchr(d + from, 0, end - from);
    if (z) {
      const auto offset = buffer_offset + static_cast<std::size_t>(static_cast<const char*>(z) - d);
      throw InputError("not-text", fmt::format("{}: not a text file (NUL byte at offset {})", *name, offset));
    }
  }
  // Offset in the input of the next line to read, and of the line last read.
  std::size_t tell() const noexcept { return buffer_offset + begin; }
  std::size_t line_start = 0;
  // Continues reading at `offset` (a line start seen before), as line `line` - 1 was just read.
  void seek(std::size_t offset, long line) {
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
  bool read_line(std::string_view& out) {
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
  void process_line(std::string_view raw) {
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

  OWord parse_oword(const detail::NormalizedLine& line) const {
    const std::string& t = line.text;
    OWord o;
    std::size_t p = 1;
    if (p < t.size() && t[p] == '<') {
      const std::size_t close = t.find('>', p);
      if (close == std::string::npos) detail::fail_at(line, 0, ctx, "o-word", "O<: '>' missing in the O-word label");
      o.label = t.substr(0, close + 1);
      p = close + 1;
    } else {
      while (p < t.size() && t[p] >= '0' && t[p] <= '9') ++p;
      if (p == 1) detail::fail_at(line, 0, ctx, "o-word", fmt::format("'{}': O needs a number or <name>", t.substr(0, 20)));
      o.label = t.substr(0, p);
    }
    static const std::pair<const char*, OKind> keywords[] = {
        {"ENDSUB", OKind::endsub}, {"SUB", OKind::sub},          {"CALL", OKind::call},
        {"RETURN", OKind::ret},    {"ENDWHILE", OKind::endwhile}, {"WHILE", OKind::while_},
        {"DO", OKind::do_},        {"ENDREPEAT", OKind::endrepeat}, {"REPEAT", OKind::repeat},
        {"ELSEIF", OKind::elseif}, {"ELSE", OKind::else_},        {"ENDIF", OKind::endif},
        {"IF", OKind::if_},        {"BREAK", OKind::break_},      {"CONTINUE", OKind::continue_}};
    for (const auto& [kw, kind] : keywords) {
      const std::size_t n = std::strlen(kw);
      if (t.compare(p, n, kw) == 0) {
        o.kind = kind;
        o.rest = p + n;
        return o;
      }
    }
    detail::fail_at(line, p, ctx, "o-word",
                    fmt::format("'{}': unknown O-word keyword (sub endsub call return while endwhile do repeat endrepeat "
                                "if elseif else endif break continue)",
                                t.substr(0, 24)));
  }
  double o_value(const OWord& o, std::size_t& at, const char* what) const {
    if (at >= nl.text.size())
      detail::fail_at(nl, at, ctx, "o-word", fmt::format("{} {}: [value] missing", o.label, what));
    return detail::parse_real_value(nl, at, ctx, params);
  }
  void o_end_of_line(std::size_t at) const {
    if (at < nl.text.size())
      detail::fail_at(nl, at, ctx, "syntax", fmt::format("'{}': unexpected text after the O-word", nl.text.substr(at, 20)));
  }

  // Reads lines without running them until the O-word `label` with one of `kinds`; leaves nl at it.
  OWord skip_to(const std::string& label, std::initializer_list<OKind> kinds, const char* what) {
    const long from = line_no;
    std::string_view raw;
    while (read_line(raw)) {
      detail::normalize_line(raw, ctx, nl);
      if (nl.text.empty() || nl.text[0] != 'O') continue;
      const OWord o = parse_oword(nl);
      if (o.label != label) continue;
      for (const OKind k : kinds)
        if (o.kind == k) return o;
    }
    fail_column(from, 1, "o-word", fmt::format("{}: {} not found before the end of the file", label, what));
  }
  [[noreturn]] void fail_column(long line, int column, const char* rule, const std::string& message) const {
    throw InputError(rule, fmt::format("{}:{}:{}: {}", *name, line, column, message));
  }
  Frame* find_frame(const std::string& label) {
    for (auto it = frames.rbegin(); it != frames.rend(); ++it)
      if (it->label == label) return &*it;
    return nullptr;
  }
  long loop_iterations = 0;  // O-word loop iterations and calls so far
  void loop_guard(const std::string& label) {
    if (++loop_iterations > opt.max_loop_iterations)
      fail_column(line_no, 1, "o-word-loop",
                  fmt::format("{}: more than {} loop iterations and calls in the program (endless loop?)", label,
                              opt.max_loop_iterations));
  }

  void control_flow() {
    if (spline == Spline::g52)
      fail(nl.first_column, "g52-open", "O-word inside an open G5.2 NURBS block (close it with G5.3 first)");
    if (spline == Spline::g62) finish_g62();
    const OWord o = parse_oword(nl);
    std::size_t at = o.rest;
    const int col = nl.first_column;
    switch (o.kind) {
      case OKind::sub: {
        o_end_of_line(at);
        subs[o.label] = SubStart{tell(), line_no + 1};
        skip_to(o.label, {OKind::endsub}, "endsub");
        return;
      }
      case OKind::call: {
        const auto it = subs.find(o.label);
        if (it == subs.end())
          fail(col, "o-word-call", fmt::format("{} call: subroutine not defined (define it with {} sub before the call)",
                                               o.label, o.label));
        loop_guard(o.label);
        if (frames.size() >= 64) fail(col, "o-word-call", fmt::format("{} call: calls nested more than 64 deep", o.label));
        Frame f{OKind::call, o.label, tell(), line_no + 1};
        f.call_column = col;
        for (int i = 0; i < 30; ++i) f.saved[static_cast<std::size_t>(i)] = params.numbered(i + 1);
        std::array<double, 30> args{};
        int n = 0;
        while (at < nl.text.size()) {
          if (n == 30) fail(col, "o-word-call", fmt::format("{} call: more than 30 arguments", o.label));
          args[static_cast<std::size_t>(n++)] = o_value(o, at, "call");
        }
        for (int i = 0; i < 30; ++i) params.set_numbered(i + 1, args[static_cast<std::size_t>(i)]);
        frames.push_back(f);
        seek(it->second.offset, it->second.line);
        return;
      }
      case OKind::endsub:
      case OKind::ret: {
        if (at < nl.text.size()) params.set_named("_VALUE", o_value(o, at, "return"));
        o_end_of_line(at);
        // leave the loops and conditionals of the subroutine
        while (!frames.empty() && frames.back().kind != OKind::call) frames.pop_back();
        if (frames.empty() || frames.back().label != o.label)
          fail(col, "o-word", fmt::format("{} {}: not inside a call of {}", o.label,
                                          o.kind == OKind::ret ? "return" : "endsub", o.label));
        const Frame f = frames.back();
        frames.pop_back();
        for (int i = 0; i < 30; ++i) params.set_numbered(i + 1, f.saved[static_cast<std::size_t>(i)]);
        seek(f.offset, f.line);
        return;
      }
      case OKind::while_: {
        Frame* open = find_frame(o.label);
        if (open && open->kind == OKind::do_) {  // the end of a do ... while loop
          const double c = o_value(o, at, "while");
          o_end_of_line(at);
          if (c != 0.0) {
            loop_guard(o.label);
            seek(open->offset, open->line);
          } else {
            while (frames.back().label != o.label) frames.pop_back();
            frames.pop_back();
          }
          return;
        }
        const double c = o_value(o, at, "while");
        o_end_of_line(at);
        if (c != 0.0) {
          if (open && open->kind == OKind::while_ && open->offset == line_start) {
            loop_guard(o.label);  // back at the head of a running loop
          } else {
            frames.push_back(Frame{OKind::while_, o.label, line_start, line_no});
          }
        } else {
          if (open && open->kind == OKind::while_ && open->offset == line_start) {
            while (frames.back().label != o.label) frames.pop_back();
            frames.pop_back();
          }
          skip_to(o.label, {OKind::endwhile}, "endwhile");
        }
        return;
      }
      case OKind::endwhile: {
        o_end_of_line(at);
        Frame* f = find_frame(o.label);
        if (!f || f->kind != OKind::while_) fail(col, "o-word", fmt::format("{} endwhile: no open {} while", o.label, o.label));
        seek(f->offset, f->line);
        return;
      }
      case OKind::do_:
        o_end_of_line(at);
        frames.push_back(Frame{OKind::do_, o.label, tell(), line_no + 1});
        return;
      case OKind::repeat: {
        const double c = o_value(o, at, "repeat");
        o_end_of_line(at);
        const double n = std::floor(c);
        if (n > static_cast<double>(opt.max_loop_iterations))
          fail(col, "o-word-loop", fmt::format("{} repeat [{}]: more than {} iterations", o.label, num(c), opt.max_loop_iterations));
        if (n < 1.0) {
          skip_to(o.label, {OKind::endrepeat}, "endrepeat");
          return;
        }
        Frame f{OKind::repeat, o.label, tell(), line_no + 1};
        f.count = static_cast<long>(n);
        frames.push_back(f);
        return;
      }
      case OKind::endrepeat: {
        o_end_of_line(at);
        Frame* f = find_frame(o.label);
        if (!f || f->kind != OKind::repeat) fail(col, "o-word", fmt::format("{} endrepeat: no open {} repeat", o.label, o.label));
        if (--f->count > 0) {
          loop_guard(o.label);
          seek(f->offset, f->line);
        } else {
          while (frames.back().label != o.label) frames.pop_back();
          frames.pop_back();
        }
        return;
      }
      case OKind::if_: {
        double c = o_value(o, at, "if");
        o_end_of_line(at);
        frames.push_back(Frame{OKind::if_, o.label, 0, line_no});
        while (c == 0.0) {  // find the branch to run
          const OWord next = skip_to(o.label, {OKind::elseif, OKind::else_, OKind::endif}, "endif");
          if (next.kind == OKind::endif) {
            frames.pop_back();
            return;
          }
          if (next.kind == OKind::else_) return;
          std::size_t p2 = next.rest;
          c = o_value(next, p2, "elseif");
          o_end_of_line(p2);
        }
        return;
      }
      case OKind::elseif:
      case OKind::else_: {  // the branch that ran ends here
        Frame* f = find_frame(o.label);
        if (!f || f->kind != OKind::if_) fail(col, "o-word", fmt::format("{}: no open {} if", o.label, o.label));
        skip_to(o.label, {OKind::endif}, "endif");
        while (frames.back().label != o.label) frames.pop_back();
        frames.pop_back();
        return;
      }
      case OKind::endif: {
        o_end_of_line(at);
        Frame* f = find_frame(o.label);
        if (!f || f->kind != OKind::if_) fail(col, "o-word", fmt::format("{} endif: no open {} if", o.label, o.label));
        while (frames.back().label != o.label) frames.pop_back();
        frames.pop_back();
        return;
      }
      case OKind::break_:
      case OKind::continue_: {
        o_end_of_line(at);
        Frame* f = find_frame(o.label);
        if (!f || (f->kind != OKind::while_ && f->kind != OKind::do_ && f->kind != OKind::repeat))
          fail(col, "o-word", fmt::format("{} {}: not inside a loop {}", o.label,
                                          o.kind == OKind::break_ ? "break" : "continue", o.label));
        const OKind loop = f->kind;
        if (o.kind == OKind::continue_) {
          while (frames.back().label != o.label) frames.pop_back();
          Frame& top = frames.back();
          loop_guard(o.label);
          if (loop == OKind::while_) {
            seek(top.offset, top.line);
          } else if (loop == OKind::repeat) {
            if (--top.count > 0) seek(top.offset, top.line);
            else {
              frames.pop_back();
              skip_to(o.label, {OKind::endrepeat}, "endrepeat");
            }
          } else {  // do: continue at the condition
            skip_to(o.label, {OKind::while_}, "while");
            control_flow();
          }
          return;
        }
        while (frames.back().label != o.label) frames.pop_back();
        frames.pop_back();
        skip_to(o.label, {loop == OKind::while_ ? OKind::endwhile : loop == OKind::repeat ? OKind::endrepeat : OKind::while_},
                "the loop's end");
        return;
      }
    }
  }

  void end_program() {
    finish_spline_at_end();
    ended = true;
  }

  void finish_spline_at_end() {
    if (circle_pending)
      detail::fail_column(ctx, circle_loc.column, "circle-end-missing",
                          fmt::format("{}: end point block missing at the end of the program: a 3-D circle takes two "
                                      "blocks (intermediate point, then end point)",
                                      g_name(circle_g, true)));
    if (spline == Spline::g62) finish_g62();
    if (spline == Spline::g52)
      fail_spline("g52-not-closed", "G5.2: NURBS block not closed by G5.3 at the end of the program");
  }

  [[noreturn]] void fail_spline(const char* rule, const std::string& message) const {
    throw InputError(rule, fmt::format("{}:{}:{}: {}", *name, spline_loc.line, spline_loc.column, message));
  }

  // ================================================================ block execution
  void check_values() const {
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

  void execute() {
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

  // A word that no code of the block uses is ignored with a warning (a control would raise an
  // alarm for some; the specification asks for a warning).
  void warn_unused_words(int motion, int nonmodal, int path, int tool_length, bool moved) {
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

  // ================================================================ motion
  void move(int motion, int col, bool machine_coordinates, int motion_word) {
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

  // G2 / G3 in the selected plane, with I J K (centre) or R (radius), P turns, helices.
  void arc(bool clockwise, const Vec3& to, int col) {
    const std::string word = clockwise ? "G2" : "G3";
    const Feed feed = feed_move(word);
    const PlaneAxes pa = plane_axes(modal.plane);
    const char offset_letter[3] = {'I', 'J', 'K'};
    const char plane_name[3][3] = {"XY", "ZX", "YZ"};
    const int pidx = static_cast<int>(modal.plane);
    // the offset word of the normal axis is not allowed
    if (w.has(offset_letter[pa.n]))
      fail(w.col(offset_letter[pa.n]), "arc-offset",
           fmt::format("{}: {} not allowed for an arc in the {} plane (G{}), which uses {} and {}", word,
                       offset_letter[pa.n], plane_name[pidx], pidx == 0 ? 17 : pidx == 1 ? 18 : 19,
                       offset_letter[pa.a1], offset_letter[pa.a2]));
    const bool has_ijk = w.has(offset_letter[pa.a1]) || w.has(offset_letter[pa.a2]);
    const bool has_r = w.has('R');
    if (!has_ijk && !has_r)
      fail(col, "arc-centre-missing",
           fmt::format("{}: {} {} (centre) or R (radius) missing", word, offset_letter[pa.a1], offset_letter[pa.a2]));
    int turns = 1;
    if (w.has('P')) {
      const double p = w.get('P');
      if (p != std::floor(p) || p < 1.0 || p > tolerances::gcode_max_arc_turns)
        fail(w.col('P'), "arc-turns", fmt::format("{} P{}: turns must be an integer 1..{}", word, num(p), tolerances::gcode_max_arc_turns));
      turns = static_cast<int>(p);
    }
    const Vec3 n = unit(pa.n), e_a1 = unit(pa.a1), e_a2 = unit(pa.a2);
    auto in_plane = [&](const Vec3& v) { return Vec3(v - v.dot(n) * n); };
    const Vec3 s_p = in_plane(pos), e_p = in_plane(to);
    Vec3 centre;
    const double tol_abs = tolerances::gcode_arc_radius_absolute_mm;
    if (has_ijk) {
      const double i1 = w.has(offset_letter[pa.a1]) ? w.get(offset_letter[pa.a1]) * scale() : 0.0;
      const double i2 = w.has(offset_letter[pa.a2]) ? w.get(offset_letter[pa.a2]) * scale() : 0.0;
      if (modal.arc_distance == DistanceMode::incremental) centre = s_p + i1 * e_a1 + i2 * e_a2;
      else centre = i1 * e_a1 + i2 * e_a2;
      if (has_r) {
        const double r_ijk = (s_p - centre).norm();
        const double r = std::abs(w.get('R') * scale());
        if (std::abs(r_ijk - r) > std::max(tol_abs, tolerances::gcode_arc_radius_relative * r))
          fail(w.col('R'), "arc-r-inconsistent",
               fmt::format("{}: R{} and the radius {} mm of {} {} disagree: I/J/K inconsistent with R", word,
                           num(w.get('R')), num(r_ijk), offset_letter[pa.a1], offset_letter[pa.a2]));
      }
    } else {
      const double r_signed = w.get('R') * scale();
      const double r = std::abs(r_signed);
      const Vec3 chord = e_p - s_p;
      const double c = chord.norm();
      if (c <= tolerances::gcode_same_point_mm)
        fail(col, "arc-r-full-circle",
             fmt::format("{} R{}: the end point is the start point; a full circle needs {} {} (the centre)", word,
                         num(w.get('R')), offset_letter[pa.a1], offset_letter[pa.a2]));
      if (!(r > 0.0)) fail(w.col('R'), "arc-radius", fmt::format("{} R{}: radius must not be zero", word, num(w.get('R'))));
      double h2 = r * r - c * c / 4.0;
      if (h2 < 0.0) {
        if (c / 2.0 - r > std::max(tol_abs, tolerances::gcode_arc_radius_relative * r))
          fail(w.col('R'), "arc-radius-too-small",
               fmt::format("{} R{}: radius smaller than half the distance {} mm from start to end", word,
                           num(w.get('R')), num(c)));
        h2 = 0.0;
      }
      const Vec3 u = chord / c;
      const Vec3 left = n.cross(u);
      const double side = (clockwise ? -1.0 : 1.0) * (r_signed < 0.0 ? -1.0 : 1.0);
      centre = 0.5 * (s_p + e_p) + side * std::sqrt(h2) * left;
    }
    const double r_start = (s_p - centre).norm(), r_end = (e_p - centre).norm();
    if (!(r_start > tolerances::gcode_same_point_mm))
      fail(col, "arc-radius", fmt::format("{}: the centre {} is the start point (radius zero)", word, point_text(centre)));
    if (std::abs(r_start - r_end) > std::max(tol_abs, tolerances::gcode_arc_radius_relative * r_start))
      fail(col, "arc-radius-mismatch",
           fmt::format("{}: radius to the start {} mm and to the end {} mm differ by {} mm (more than {} mm)", word,
                       num(r_start), num(r_end), num(std::abs(r_start - r_end)),
                       num(std::max(tol_abs, tolerances::gcode_arc_radius_relative * r_start))));
    CircleFrame f;
    f.normal = clockwise ? Vec3(-n) : n;
    f.e1 = (s_p - centre) / r_start;
    f.e2 = f.normal.cross(f.e1);
    f.centre = centre + pos.dot(n) * n;
    const Vec3 v = e_p - centre;
    double angle = std::atan2(v.dot(f.e2), v.dot(f.e1));
    if (angle < 0.0) angle += 2.0 * pi;
    if ((e_p - s_p).norm() <= tolerances::gcode_same_point_mm || angle <= 0.0) angle = 2.0 * pi;
    const double sweep = angle + 2.0 * pi * (turns - 1);
    const double rise = (to - pos).dot(f.normal);
    // to machine coordinates (rigid: rotation about Z and translation)
    const Eigen::Matrix3d rot = rotation();
    CircleFrame mf;
    mf.centre = to_machine(f.centre);
    mf.e1 = rot * f.e1;
    mf.e2 = rot * f.e2;
    mf.normal = rot * f.normal;
    Block b = make_block(std::abs(rise) > 0.0 ? BlockType::helix : BlockType::arc, col);
    b.start = to_machine(pos);
    b.end = to_machine(to);
    b.feed = feed;
    b.geometry.emplace<HelixArc>(at(col, word, [&] { return HelixArc(mf, r_start, sweep, rise); }));
    emit(std::move(b));
    pos = to;
  }

  // G5 cubic / G5.1 quadratic Bezier (LinuxCNC; XY plane), as a clamped B-spline.
  void bezier(bool cubic, const Vec3& to, int col) {
    const std::string word = cubic ? "G5" : "G5.1";
    if (modal.plane != Plane::xy) fail(col, "bezier-plane", fmt::format("{}: only in the XY plane (G17)", word));
    const Feed feed = feed_move(word);
    const bool has_i = w.has('I'), has_j = w.has('J'), has_p = w.has('P'), has_q = w.has('Q');
    if (w.has('K')) fail(w.col('K'), "bezier-words", fmt::format("{}: K not allowed (XY plane: I J)", word));
    if (has_i != has_j) fail(col, "bezier-words", fmt::format("{}: I and J must be given together", word));
    Vec3 ij = Vec3::Zero();
    if (has_i) ij = Vec3(w.get('I') * scale(), w.get('J') * scale(), 0.0);
    std::vector<Vec3> pts;
    const Vec3 dz(0.0, 0.0, to.z() - pos.z());
    if (cubic) {
      if (!has_p || !has_q)
        fail(col, "bezier-pq-missing", "G5: P and Q missing (second control point, offset from the end point)");
      if (!has_i) {
        if (!prev_g5)
          fail(col, "bezier-ij-missing",
               "G5: I and J missing (first control point, offset from the start; only a G5 directly after a G5 may "
               "omit them)");
        ij = -prev_g5_pq;
      }
      const Vec3 pq(w.get('P') * scale(), w.get('Q') * scale(), 0.0);
      pts = {pos, pos + ij + dz / 3.0, to + pq - dz / 3.0, to};
      prev_g5 = true;
      prev_g5_pq = pq;
    } else {
      if (!has_i) fail(col, "bezier-ij-missing", "G5.1: I and J missing (the control point, offset from the start)");
      if (has_p || has_q) fail(col, "bezier-words", "G5.1: P and Q not allowed (quadratic: one control point I J)");
      pts = {pos, pos + ij + dz / 2.0, to};
      prev_g5 = false;
    }
    NurbsData d;
    d.degree = static_cast<int>(pts.size()) - 1;
    d.knots.assign(pts.size(), 0.0);
    d.knots.resize(2 * pts.size(), 1.0);
    for (auto& p : pts) d.points.push_back(to_machine(p));
    Block b = make_block(BlockType::bezier, col);
    b.start = to_machine(pos);
    b.end = to_machine(to);
    b.feed = feed;
    b.geometry.emplace<NurbsCurve>(at(col, word, [&] { return NurbsCurve(std::move(d)); }));
    emit(std::move(b));
    pos = to;
  }

  // ---- G5.2 / G5.3 (LinuxCNC NURBS block)
  void start_g52(int col) {
    spline = Spline::g52;
    spline_loc = location(col);
    spline_word = "G5.2";
    spline_feed = feed_move("G5.2");
    spline_modal = modal;
    spline_start = pos;
    nurbs = NurbsData{};
    rank = 3;
    if (w.has('L')) {
      const double l = w.get('L');
      if (l != std::floor(l) || l < 2.0 || l > tolerances::max_degree + 1)
        fail(w.col('L'), "nurbs-order", fmt::format("G5.2 L{}: order outside the supported range 2..{}", num(l), tolerances::max_degree + 1));
      rank = static_cast<int>(l);
    }
    const double weight = w.has('P') ? w.get('P') : 1.0;
    if (!(weight > 0.0)) fail(w.col('P'), "nurbs-weight", fmt::format("G5.2 P{}: weight must be > 0", num(weight)));
    last_point = pos;
    if (has_axes()) {
      add_control_point(pos, 1.0);
      add_control_point(target(), weight);
    } else {
      add_control_point(pos, weight);
    }
  }
  void add_control_point(const Vec3& p, double weight) {
    if (static_cast<int>(nurbs.points.size()) >= tolerances::gcode_max_spline_points)
      fail(block_column(), "nurbs-size", fmt::format("{}: more than {} control points", spline_word, tolerances::gcode_max_spline_points));
    nurbs.points.push_back(p);
    nurbs.weights.push_back(weight);
    last_point = p;
  }
  void finish_g52() {
    const int n = static_cast<int>(nurbs.points.size());
    if (n < rank)
      fail_spline("nurbs-points", fmt::format("G5.2: {} control points (with the start point), order L{} needs at least {}",
                                              n, rank, rank));
    nurbs.degree = rank - 1;
    nurbs.knots.clear();
    for (int i = 0; i < rank; ++i) nurbs.knots.push_back(0.0);
    for (int i = 1; i <= n - rank; ++i) nurbs.knots.push_back(i);
    for (int i = 0; i < rank; ++i) nurbs.knots.push_back(n - rank + 1);
    emit_spline(BlockType::nurbs);
  }
  void emit_spline(BlockType type) {
    Block b;
    b.type = type;
    b.modal = spline_modal;
    b.location = spline_loc;
    b.feed = spline_feed;
    b.start = to_machine(spline_start);
    const Vec3 end_program = nurbs.points.back();
    for (auto& p : nurbs.points) p = to_machine(p);
    b.end = nurbs.points.back();
    if (const auto problem = validate(nurbs))
      fail_spline(problem->rule.c_str(), fmt::format("{}: {}", spline_word, problem->message));
    try {
      b.geometry.emplace<NurbsCurve>(std::move(nurbs));
    } catch (const InputError& e) {
      fail_spline(e.rule().c_str(), fmt::format("{}: {}", spline_word, e.what()));
    }
    nurbs = NurbsData{};
    spline = Spline::none;
    emit(std::move(b));
    pos = end_program;
  }

  // ---- G06.2 / G6.2 (Fanuc, Mitsubishi, LinuxCNC NURBS)
  void start_g62(int col, int motion_word) {
    bool leading_zero = false;
    for (int i = 0; i < w.g_count; ++i)
      if (w.g[static_cast<std::size_t>(i)] == 62) leading_zero = w.g_leading_zero[static_cast<std::size_t>(i)] != 0;
    spline_word = motion_word == 62 ? (leading_zero ? "G06.2" : "G6.2") : "G6.2";
    if (!w.has('K')) fail(col, "nurbs-knot-missing", fmt::format("{}: K (knot) missing in the first block of the curve", spline_word));
    spline = Spline::g62;
    spline_loc = location(col);
    spline_feed = feed_move(spline_word);
    spline_modal = modal;
    spline_start = pos;
    nurbs = NurbsData{};
    knot_line.clear();
    end_knots = 0;
    rank = 4;
    if (w.has('P')) {
      const double p = w.get('P');
      if (p != std::floor(p) || p < 2.0 || p > tolerances::max_degree + 1)
        fail(w.col('P'), "nurbs-rank",
             fmt::format("{} P{}: rank outside the supported range 2..{} (rank = degree + 1; Fanuc accepts 2..4)",
                         spline_word, num(p), tolerances::max_degree + 1));
      rank = static_cast<int>(p);
    }
    if (w.has('Q') && !q_warned) {
      q_warned = true;
      warn(w.col('Q'), fmt::format("{} Q{}: LinuxCNC's approximation by biarcs, arcs or lines is replaced by true spline "
                                   "interpolation",
                                   spline_word, num(w.get('Q'))));
    }
    const Vec3 first = target();
    if ((first - pos).norm() > tolerances::gcode_same_point_mm)
      fail(col, "nurbs-first-point",
           fmt::format("{}: the first control point {} is not the current position {} (distance {} mm)", spline_word,
                       point_text(first), point_text(pos), num((first - pos).norm())));
    last_point = pos;
    add_knot(w.get('K'), w.col('K'));
    add_control_point(pos, weight_word());
  }
  double weight_word() const {
    const double r = w.has('R') ? w.get('R') : 1.0;
    if (!(r > 0.0)) fail(w.col('R'), "nurbs-weight", fmt::format("{}: weight R{} must be > 0", spline_word, num(r)));
    return r;
  }
  void add_knot(double k, int col) {
    if (!nurbs.knots.empty() && k < nurbs.knots.back())
      fail(col, "knots-decreasing",
           fmt::format("{}: knot K{} is less than the previous knot K{} (line {}): knots must not decrease", spline_word,
                       num(k), num(nurbs.knots.back()), knot_line.back()));
    if (static_cast<int>(nurbs.knots.size()) > tolerances::gcode_max_spline_points + tolerances::max_degree + 1)
      fail(col, "nurbs-size", fmt::format("{}: too many knots", spline_word));
    nurbs.knots.push_back(k);
    knot_line.push_back(line_no);
  }
  void finish_g62() {
    const int np = static_cast<int>(nurbs.points.size());
    const int nk = static_cast<int>(nurbs.knots.size());
    const auto& k = nurbs.knots;
    if (nk != np + rank)
      fail_spline("knot-count", fmt::format("{}: {} knots given, {} needed ({} control points + rank {})", spline_word, nk,
                                            np + rank, np, rank));
    if (np < rank)
      fail_spline("nurbs-points", fmt::format("{}: {} control points, rank {} needs at least {}", spline_word, np, rank, rank));
    for (int i = 1; i < rank; ++i)
      if (k[static_cast<std::size_t>(i)] != k[0])
        fail_spline("end-knots", fmt::format("{}: the first {} knots must be equal (rank {}): knot {} is K{}, knot 1 is K{}",
                                             spline_word, rank, rank, i + 1, num(k[static_cast<std::size_t>(i)]), num(k[0])));
    for (int i = nk - rank; i < nk - 1; ++i)
      if (k[static_cast<std::size_t>(i)] != k.back())
        fail_spline("end-knots", fmt::format("{}: the last {} knots must be equal (rank {}): knot {} is K{}, knot {} is K{}",
                                             spline_word, rank, rank, i + 1, num(k[static_cast<std::size_t>(i)]), nk,
                                             num(k.back())));
    if (!(k.back() > k.front()))
      fail_spline("knot-range", fmt::format("{}: all knots are equal (K{}): the parameter range is empty", spline_word, num(k[0])));
    for (int i = rank; i < nk - rank;) {
      int j = i;
      while (j + 1 < nk - rank && k[static_cast<std::size_t>(j + 1)] == k[static_cast<std::size_t>(i)]) ++j;
      const int mult = j - i + 1;
      if (mult >= rank)
        fail_spline("inner-knot-multiplicity",
                    fmt::format("{}: inner knot K{} repeated {} times (line {}); at most rank - 1 = {}", spline_word,
                                num(k[static_cast<std::size_t>(i)]), mult, knot_line[static_cast<std::size_t>(i)], rank - 1));
      i = j + 1;
    }
    nurbs.degree = rank - 1;
    emit_spline(BlockType::nurbs);
  }

  // Returns true if the block belongs to the spline being collected (and consumed it).
  bool continue_spline() {
    if (spline == Spline::g52) {
      bool closes = false;
      for (int i = 0; i < w.g_count; ++i) {
        if (w.g[static_cast<std::size_t>(i)] == 53) closes = true;
        else
          fail(w.g_column[static_cast<std::size_t>(i)], "g52-open",
               fmt::format("{}: not allowed inside an open G5.2 NURBS block (close it with G5.3 first)",
                           g_name(w.g[static_cast<std::size_t>(i)])));
      }
      if (w.m_count > 0)
        fail(w.m_column[0], "g52-open", fmt::format("M{}: not allowed inside an open G5.2 NURBS block (close it with G5.3 first)", w.m[0]));
      check_spline_words("XYZPF", closes ? "G5.3" : "G5.2");
      if (w.has('F')) update_feed();
      if (has_axes()) {
        if (closes) fail(block_column(), "g53-axes", "G5.3: axis words not allowed (G5.3 only closes the NURBS block)");
        const double weight = w.has('P') ? w.get('P') : 1.0;
        if (!(weight > 0.0)) fail(w.col('P'), "nurbs-weight", fmt::format("G5.2: weight P{} must be > 0", num(weight)));
        add_control_point(target(), weight);
      } else if (w.has('P')) {
        fail(w.col('P'), "g52-words", "G5.2: P (weight) without a control point X Y Z");
      }
      if (closes) {
        finish_g52();
        modal.motion_g10 = motion_none;
      }
      return true;
    }
    // G6.2: K with or without axes; a G6.2 word only on K-alone blocks (LinuxCNC's closing blocks)
    if (!w.has('K') || w.m_count > 0 || w.keyword != Keyword::none) return false;
    for (int i = 0; i < w.g_count; ++i)
      if (w.g[static_cast<std::size_t>(i)] != 62) return false;
    if (w.g_count > 0 && has_axes()) return false;  // G6.2 with a point: a new curve
    check_spline_words("KXYZRF", spline_word.c_str());
    if (w.has('F')) update_feed();
    if (has_axes()) {
      if (end_knots > 0)
        fail(block_column(), "nurbs-point-after-end-knots",
             fmt::format("{}: control point after the end knots (K-alone blocks close the curve)", spline_word));
      add_knot(w.get('K'), w.col('K'));
      const double weight = weight_word();
      Vec3 p = last_point;
      const char letters[3] = {'X', 'Y', 'Z'};
      for (int a = 0; a < 3; ++a)
        if (w.has(letters[a])) {
          const double v = w.get(letters[a]) * scale();
          p[a] = modal.distance == DistanceMode::absolute ? v : last_point[a] + v;
        }
      add_control_point(p, weight);
    } else {
      if (w.has('R')) fail(w.col('R'), "nurbs-words", fmt::format("{}: R (weight) without a control point", spline_word));
      add_knot(w.get('K'), w.col('K'));
      ++end_knots;
    }
    return true;
  }
  void check_spline_words(const char* allowed, const char* word) const {
    for (int c = 0; c < 26; ++c) {
      const char letter = static_cast<char>('A' + c);
      if (w.has(letter) && !std::strchr(allowed, letter))
        fail(w.col(letter), "nurbs-words", fmt::format("{}: {} not allowed in a control point block", word, letter));
    }
  }
  void update_feed() {
    const double f = w.get('F');
    if (f < 0.0) fail(w.col('F'), "feed-range", fmt::format("F{}: feed must be >= 0", num(f)));
    if (modal.feed_mode == FeedMode::units_per_minute) feed_mm_per_min = f * scale();
  }

  // ---- circles through an intermediate point
  void emit_circle(const Vec3& mid, const Vec3& to, int col, const std::string& word) {
    const Feed feed = feed_move(word);
    Block b = make_block(BlockType::circle_3d, col);
    b.start = to_machine(pos);
    b.end = to_machine(to);
    b.via[0] = to_machine(mid);
    b.via_count = 1;
    b.feed = feed;
    b.geometry.emplace<HelixArc>(at(col, word, [&] { return make_circle_3d(b.start, b.via[0], b.end); }));
    emit(std::move(b));
    pos = to;
  }
  // The one place that builds the 3-D circle (to switch to the arcs-and-conics issue's API).
  static HelixArc make_circle_3d(const Vec3& r1, const Vec3& r2, const Vec3& r3) {
    return detail::circle_through_three_points(r1, r2, r3);
  }
  void circle_block(int motion, int col) {
    if (!has_axes()) return;
    if (!circle_pending) {
      circle_pending = true;
      circle_mid = target();
      circle_loc = location(col);
      circle_g = motion;
      feed_move(g_name(motion, true));  // report a missing feed at the first block
      return;
    }
    // end point block: in G91 relative to the intermediate point (Fanuc)
    Vec3 end_point = circle_mid;
    const char letters[3] = {'X', 'Y', 'Z'};
    for (int a = 0; a < 3; ++a)
      if (w.has(letters[a])) {
        const double v = w.get(letters[a]) * scale();
        end_point[a] = modal.distance == DistanceMode::absolute ? v : circle_mid[a] + v;
      } else {
        end_point[a] = modal.distance == DistanceMode::absolute ? pos[a] : circle_mid[a];
      }
    circle_pending = false;
    // the circle is the block of its first line: report its errors there
    const long this_line = line_no;
    line_no = ctx.line = circle_loc.line;
    emit_circle(circle_mid, end_point, circle_loc.column, g_name(circle_g, true));
    line_no = ctx.line = this_line;
    queue.back().location = circle_loc;
  }
  Vec3 indexed_point(int point) const {
    Vec3 p = pos;
    for (int a = 0; a < 3; ++a)
      if (w.has_indexed(point, a)) {
        const double v = w.indexed[static_cast<std::size_t>(point)][static_cast<std::size_t>(a)] * scale();
        p[a] = modal.distance == DistanceMode::absolute ? v : pos[a] + v;
      }
    return p;
  }
  void cip(const Vec3& to, int col) {
    for (int p = 1; p < 3; ++p)
      for (int a = 0; a < 3; ++a)
        if (w.has_indexed(p, a))
          fail(w.indexed_column[static_cast<std::size_t>(p)][static_cast<std::size_t>(a)], "cip-words",
               fmt::format("CIP: {}{}= not allowed (CIP has one intermediate point I1= J1= K1=)", static_cast<char>('I' + a), p + 1));
    if (!(w.indexed_present & 7u))
      fail(col, "cip-intermediate-missing", "CIP: intermediate point missing (I1= J1= K1=)");
    if (!has_axes()) fail(col, "cip-end-missing", "CIP: end point missing (X Y Z)");
    emit_circle(indexed_point(0), to, col, "CIP");
  }
  void conic(const Vec3& to, int col) {
    static constexpr const char* names[3] = {"I", "J", "K"};
    for (int p = 0; p < 3; ++p)
      for (int a = 0; a < 3; ++a)
        if (!w.has_indexed(p, a))
          fail(col, "conic-words",
               fmt::format("CONIC: {}{}= missing: a conic needs three intermediate points I1= J1= K1= I2= J2= K2= I3= "
                           "J3= K3= and the end point X Y Z",
                           names[a], p + 1));
    if (!has_axes()) fail(col, "conic-words", "CONIC: end point missing (X Y Z)");
    const Feed feed = feed_move("CONIC");
    const std::array<Vec3, 5> pts{pos, indexed_point(0), indexed_point(1), indexed_point(2), to};
    at(col, "CONIC", [&] {
      detail::check_conic_points(pts);
      return 0;
    });
    Block b = make_block(BlockType::conic, col);
    b.start = to_machine(pos);
    b.end = to_machine(to);
    for (int i = 0; i < 3; ++i) b.via[static_cast<std::size_t>(i)] = to_machine(pts[static_cast<std::size_t>(i + 1)]);
    b.via_count = 3;
    b.feed = feed;
    emit(std::move(b));
    pos = to;
  }

  // ---- canned cycles G73, G81, G82, G83 (XY plane), expanded into moves
  void cycle(int motion, int col) {
    const std::string word = g_name(motion);
    const int cycle_number = motion / 10;
    if (modal.plane != Plane::xy) fail(col, "cycle-plane", fmt::format("{}: canned cycles only in the XY plane (G17)", word));
    if (modal.feed_mode == FeedMode::inverse_time)
      fail(col, "cycle-feed-mode", fmt::format("{}: canned cycles not allowed with G93 (inverse time)", word));
    const Feed feed = feed_move(word);
    const double s = scale();
    if (w.has('R')) {
      cycle_r = w.get('R') * s;
      cycle_r_set = true;
    }
    if (w.has('Z')) {
      cycle_z = w.get('Z') * s;
      cycle_z_set = true;
    }
    if (w.has('Q')) {
      cycle_q = w.get('Q') * s;
      cycle_q_set = true;
    }
    if (w.has('P')) cycle_p = w.get('P');
    if (!cycle_z_set) fail(col, "cycle-words", fmt::format("{}: Z (hole bottom) missing", word));
    if (!cycle_r_set) fail(col, "cycle-words", fmt::format("{}: R (retract plane) missing", word));
    if ((motion == 730 || motion == 830) && !(cycle_q_set && cycle_q > 0.0))
      fail(w.has('Q') ? w.col('Q') : col, "cycle-peck", fmt::format("{}: Q (peck depth) missing or not > 0", word));
    if (cycle_p < 0.0) fail(w.col('P'), "cycle-words", fmt::format("{} P{}: dwell must be >= 0", word, num(cycle_p)));
    int repeats = 1;
    if (w.has('L')) {
      const double l = w.get('L');
      if (l != std::floor(l) || l < 0.0 || l > tolerances::gcode_max_cycle_repeats)
        fail(w.col('L'), "cycle-repeat", fmt::format("{} L{}: repeats must be an integer 0..{}", word, num(l), tolerances::gcode_max_cycle_repeats));
      repeats = static_cast<int>(l);
    }
    const bool incremental = modal.distance == DistanceMode::incremental;
    const double r_plane = incremental ? pos.z() + cycle_r : cycle_r;
    const double bottom = incremental ? r_plane + cycle_z : cycle_z;
    if (bottom > r_plane)
      fail(col, "cycle-depth", fmt::format("{}: the hole bottom Z {} mm is above the retract plane R {} mm", word, num(bottom), num(r_plane)));
    if (motion == 730 || motion == 830) {
      const double pecks = (r_plane - bottom) / cycle_q;
      if (pecks > tolerances::gcode_max_pecks)
        fail(w.has('Q') ? w.col('Q') : col, "cycle-peck", fmt::format("{}: Q {} mm gives more than {} pecks", word, num(cycle_q), tolerances::gcode_max_pecks));
    }
    {
      const double pecks = (motion == 730 || motion == 830) ? std::ceil((r_plane - bottom) / cycle_q) : 1.0;
      if (repeats * (pecks * 3.0 + 4.0) > tolerances::gcode_max_cycle_moves)
        fail(col, "cycle-repeat", fmt::format("{}: L{} holes of {} pecks expand into more than {} moves", word, repeats,
                                              num(pecks), tolerances::gcode_max_cycle_moves));
    }
    const double clear_z = modal.retract == RetractMode::initial_z ? std::max(cycle_old_z, r_plane) : r_plane;
    auto rapid_to = [&](const Vec3& p) {
      if ((p - pos).norm() > 0.0) line_move(BlockType::rapid, p, col, Feed{}, cycle_number);
    };
    auto feed_to = [&](const Vec3& p) { line_move(BlockType::line, p, col, feed, cycle_number); };
    if (pos.z() < r_plane) rapid_to(Vec3(pos.x(), pos.y(), r_plane));
    const double delta = tolerances::gcode_peck_clearance_mm;
    for (int rep = 0; rep < repeats; ++rep) {
      Vec3 hole = pos;
      const char letters[2] = {'X', 'Y'};
      for (int a = 0; a < 2; ++a)
        if (w.has(letters[a])) {
          const double v = w.get(letters[a]) * s;
          hole[a] = incremental ? pos[a] + v : v;
        }
      rapid_to(Vec3(hole.x(), hole.y(), pos.z()));
      rapid_to(Vec3(hole.x(), hole.y(), r_plane));
      if (motion == 810 || motion == 820) {
        feed_to(Vec3(hole.x(), hole.y(), bottom));
        if (motion == 820) {
          Block b = make_block(BlockType::dwell, col);
          b.start = b.end = to_machine(pos);
          b.dwell_s = cycle_p;
          b.canned_cycle = cycle_number;
          emit(std::move(b));
        }
      } else {
        double depth = r_plane;
        while (depth > bottom) {
          depth = std::max(depth - cycle_q, bottom);
          feed_to(Vec3(hole.x(), hole.y(), depth));
          if (depth <= bottom) break;
          if (motion == 830) {
            rapid_to(Vec3(hole.x(), hole.y(), r_plane));
            rapid_to(Vec3(hole.x(), hole.y(), depth + delta));
          } else {
            rapid_to(Vec3(hole.x(), hole.y(), std::min(depth + delta, r_plane)));
          }
        }
      }
      rapid_to(Vec3(hole.x(), hole.y(), clear_z));
    }
  }

  // ---- G10 L2 / L20 (work offsets), L1 / L10 / L11 (tool table, recorded only)
  void g10(int col) {
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

  // ---- G28 / G30: rapid through the given point to the stored home position
  void home(int g, int col) {
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
};

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
