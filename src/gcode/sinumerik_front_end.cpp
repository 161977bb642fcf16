// The Sinumerik 840D dialect: a line is a header, a definition, control flow, or the words of a
// block (addresses, assignments, frame instructions, cycle and subprogram calls).
#include "sinumerik_front_end.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>

#include "message_format.hpp"

namespace kontur::gcode::detail {
namespace {

bool is_ident_start(char c) noexcept { return (c >= 'A' && c <= 'Z') || c == '_'; }
bool is_digit(char c) noexcept { return c >= '0' && c <= '9'; }

bool all_digits(std::string_view s) noexcept {
  return !s.empty() && std::all_of(s.begin(), s.end(), [](char c) { return is_digit(c); });
}

// Keywords that switch something of the control Kontur's path does not depend on: accepted with a
// warning (once each).
constexpr const char* no_op_keywords[] = {
    "SOFT",     "BRISK",    "DRIVE",      "FFWON",     "FFWOF",    "COMPCAD",  "COMPOF",    "COMPON", "COMPCURV",
    "COMPSURF", "FNORM",    "TRAFOOF",    "UPATH",     "SPATH",    "CFC",      "CFTCP",     "CFIN",   "DYNNORM",
    "DYNPOS",   "DYNROUGH", "DYNSEMIFIN", "DYNFINISH", "FIFOCTRL", "STOPFIFO", "STARTFIFO", "ORIWKS", "ORIMKS",
    "ORIAXES",  "ORIVECT",  "CUT2D",      "CUT2DF",    "CUT3DC",   "DIAMOF",   "SPCON",     "SPCOF",  "FGREF",
    "G601",     "G602",     "G603",       "ACN",       "ACP",      "CDON",     "CDOF",      "CDOF2",  "SBLOF",
    "SBLON",    "DISPLOF",  "DISPLON",    "PTP",       "CP",       "FGROUP",   "WAITM",     "WAITE",  "TOFFOF",
};
// Function-like statements without an effect on the path (display, spindle assignment, settings).
constexpr const char* no_op_calls[] = {"WORKPIECE", "SETMS", "CYCLE832",  "FGROUP",   "SPOS",
                                       "SPOSA",     "SUPD",  "G_SETTING", "SETPIECE", "FFWON",
                                       "WAITM",     "WAITE", "WAITS",     "CLEARM",   "SETM"};

// What the control can do and Kontur does not.
struct Refusal {
  const char* name;
  const char* feature;
};
constexpr Refusal refusals[] = {
    {"CYCLE800", "5-axis swivelling (CYCLE800: a swivel head or table)"},
    {"TRAORI", "the 5-axis transformation TRAORI"},
    {"TRANSMIT", "the face-milling transformation TRANSMIT"},
    {"TRACYL", "the cylinder-surface transformation TRACYL"},
    {"TRAANG", "the inclined-axis transformation TRAANG"},
    {"TRACON", "chained transformations TRACON"},
    {"DIAMON", "lathe diameter programming DIAMON"},
    {"DIAM90", "lathe diameter programming DIAM90"},
    {"DIAMCYCOF", "lathe diameter programming"},
    {"ASPLINE", "Akima splines (ASPLINE)"},
    {"CSPLINE", "cubic splines (CSPLINE)"},
    {"BSPLINE", "B splines (BSPLINE)"},
    {"POLY", "polynomial interpolation (POLY)"},
    {"OFFN", "contour offset OFFN (cutter compensation)"},
    {"CASE", "CASE branches"},
    {"SPLINEPATH", "spline groups (SPLINEPATH)"},
    {"ROTS", "solid-angle rotations ROTS / AROTS"},
    {"AROTS", "solid-angle rotations ROTS / AROTS"},
    {"CROTS", "solid-angle rotations CROTS"},
    {"DEFINE", "DEFINE macros"},
    {"EXECSTRING", "EXECSTRING"},
    {"EXECTAB", "EXECTAB"},
    {"CALL", "indirect calls (CALL)"},
    {"PCALL", "calls by path (PCALL)"},
    {"OSC", "tool oscillation (OSC)"},
    {"RND", "corner rounding between blocks (RND=)"},
    {"RNDM", "modal corner rounding (RNDM=)"},
    {"CHF", "chamfers between blocks (CHF=)"},
    {"CHR", "chamfers between blocks (CHR=)"},
    {"ANG", "contour definitions by angles (ANG=)"},
    {"GOTOS", "jumps to the program start (GOTOS)"},
    {"SPATH", "SPATH"},
};
}  // namespace

const char* SinumerikFrontEnd::refusal_of(std::string_view name) noexcept {
  for (const auto& r : refusals)
    if (name == r.name) return r.feature;
  // lathe, pocket, slot and other cycles of the control's cycle package
  if (name.starts_with("CYCLE9")) return "the lathe cycles CYCLE9x (turning, threading, grooving)";
  if (name.starts_with("POCKET") || name.starts_with("SLOT") || name == "LONGHOLE" || name.starts_with("CYCLE6") ||
      name.starts_with("CYCLE7") || name.starts_with("CYCLE8") || name.starts_with("HOLES") ||
      name.starts_with("CYCLE4") || name.starts_with("CYCLE1") || name.starts_with("CYCLE2") ||
      name.starts_with("CYCLE3") || name.starts_with("CYCLE5"))
    return "this machining cycle of the cycle package (only CYCLE81, CYCLE82 and CYCLE83 are expanded)";
  return nullptr;
}

SinumerikFrontEnd::SinumerikFrontEnd(const DialectServices& services)
    : main_input(services.input),
      main_name(services.diagnostics.context().file), main_file(services.diagnostics.name()),
      params(services.parameters),
      diag(services.diagnostics),
      opt(services.options),
      executor(services.executor),
      r_(r_count, 0.0),
      scopes(1) {}

void SinumerikFrontEnd::warn_once(const std::string& key, int column, const std::string& message) {
  if (warned.insert(key).second) diag.warn(column, message + " (warned once)");
}

// ---------------------------------------------------------------- the line

void SinumerikFrontEnd::prepare(std::string_view raw) {
  text.clear();
  bool in_string = false;
  for (std::size_t i = 0; i < raw.size(); ++i) {
    char c = raw[i];
    const auto uc = static_cast<unsigned char>(c);
    const int col = static_cast<int>(i) + 1;
    if (uc == 0 || (uc < 32 && c != '\t' && c != '\r' && c != '\f' && c != '\v') || uc == 127)
      diag.fail(col, "not-text", fmt::format("byte 0x{:02x}: not a text file (control character)", uc));
    if (!in_string && c == ';') break;
    if (c == '"') in_string = !in_string;
    if (!in_string) {
      if (uc >= 128)
        diag.fail(col, "character",
                  fmt::format("byte 0x{:02x}: only ASCII is allowed outside comments and strings", uc));
      if (c == '\t' || c == '\r' || c == '\f' || c == '\v') c = ' ';
      c = static_cast<char>(std::toupper(uc));
    }
    text.push_back(c);
  }
  while (!text.empty() && text.back() == ' ') text.pop_back();
  cur = Cursor{text, 0};
}

SinumerikFrontEnd::Head SinumerikFrontEnd::read_head(Cursor& c, bool record) {
  Head h;
  c.ws();
  if (c.p < c.t.size() && c.t[c.p] == '/') {
    ++c.p;
    if (c.p < c.t.size() && is_digit(c.t[c.p])) ++c.p;  // skip level /0 .. /9
    h.deleted = opt.block_delete;
  }
  for (int k = 0; k < 2; ++k) {
    c.ws();
    if (c.p + 1 < c.t.size() && (c.t[c.p] == 'N' || c.t[c.p] == ':') && is_digit(c.t[c.p + 1])) {
      std::size_t q = c.p + 1;
      long n = 0;
      int digits = 0;
      while (q < c.t.size() && is_digit(c.t[q])) {
        if (digits < 12) n = n * 10 + (c.t[q] - '0');
        ++digits;
        ++q;
      }
      // (a name starts with two letters or '_' on a Sinumerik: N10G0 is N10 and G0)
      if (q < c.t.size() && (c.t[q] == '=' || c.t[q] == '[')) break;
      if (h.n >= 0) diag.fail(c.col(), "n-word", "a second block number in the block");
      h.n = n;
      c.p = q;
      continue;
    }
    const std::size_t save = c.p;
    const std::string_view id = identifier(c);
    if (!id.empty() && c.p < c.t.size() && c.t[c.p] == ':' && !(c.p + 1 < c.t.size() && c.t[c.p + 1] == '=')) {
      h.label = std::string(id);
      ++c.p;
      if (record) labels[h.label] = Position{in().line_start(), diag.line()};
      continue;
    }
    c.p = save;
    break;
  }
  return h;
}

LineOutcome SinumerikFrontEnd::read_line(std::string_view raw, Words& words) {
  if (deferred_return) {  // M17 ended a subprogram file's block: the block has run in its file
    deferred_return = false;
    end_of_sub(1);
    if (!external) diag.set_line(main_line + 1);  // `raw` is the main program's line after the call
  }
  if (!external) {
    const LineOutcome r = read_program_line(raw, words);
    if (external) external_line = diag.line();  // a subprogram file was opened
    return r;
  }
  // A subprogram of its own file runs: the main program's line is read again later, and the line
  // numbers (kept in the diagnostics) are the subprogram's while it runs.
  main_input.seek(main_input.line_start(), main_line + 1);
  diag.set_line(external_line);
  std::string_view line;
  if (!external->read_line(line)) {  // the end of the subprogram's file: its end
    words.clear();
    end_of_sub(1);
    return LineOutcome::nothing;
  }
  const LineOutcome r = read_program_line(line, words);
  if (external) external_line = diag.line();
  return r;
}

LineOutcome SinumerikFrontEnd::read_program_line(std::string_view raw, Words& words) {
  words.clear();
  prepare(raw);
  if (cur.end()) return LineOutcome::nothing;
  if (cur.peek() == '%') {
    // %_N_NAME_MPF, %_N_NAME_SPF, %MPF 90, %SPF 12: the program's header, or the next program of
    // the file (the end of this one)
    if (!seen_block && !seen_header) {
      seen_header = true;
      return LineOutcome::nothing;
    }
    if (in_call()) {
      end_of_sub(1);
      return LineOutcome::nothing;
    }
    return LineOutcome::program_end;
  }
  const Head h = read_head(cur, true);
  if (!frames.empty() && frames.back().kind == FKind::section) {  // a repeated section ends here?
    const Frame& f = frames.back();
    if (in().line_start() == f.stop_offset) {  // back at the REPEAT line: before it
      end_section();
      return LineOutcome::nothing;
    }
    if (f.single || (!f.var.empty() && h.label == f.var) || (f.var.empty() && h.label == "ENDLABEL")) end_section();
  }
  if (h.deleted) return LineOutcome::nothing;
  words.n_number = h.n;
  if (cur.end()) return LineOutcome::nothing;
  const bool first_block = !seen_block;
  seen_block = true;
  {
    Cursor c = cur;
    const int col = c.col();
    const std::string_view kw = identifier(c);
    if (kw == "PROC") {
      cur = c;
      define_proc(cur, col, first_block);
      if (end_requested) {
        end_requested = false;
        return LineOutcome::program_end;
      }
      return LineOutcome::nothing;
    }
    if (statement(words)) {
      if (end_requested) {
        end_requested = false;
        return LineOutcome::program_end;
      }
      if (words.empty() && !pending.empty()) {
        words = pending.front();
        pending.pop_front();
      }
      return words.empty() ? LineOutcome::nothing : LineOutcome::words;
    }
  }
  return block(words);
}

bool SinumerikFrontEnd::pending_words(Words& words) {
  if (pending.empty()) return false;
  words = pending.front();
  pending.pop_front();
  return true;
}

void SinumerikFrontEnd::at_end_of_input() {
  if (external)
    diag.fail(1, "control-flow",
              fmt::format("the program's file {} ends right after the call of {}: Kontur needs a line (M30) after it",
                          main_name, frames.empty() ? std::string("a subprogram") : frames.back().var));
  if (frames.empty()) return;
  const Frame& f = frames.back();
  static constexpr const char* names[] = {"IF", "WHILE", "FOR", "REPEAT", "LOOP", "subprogram call", "REPEAT"};
  static constexpr const char* ends[] = {"ENDIF",   "ENDWHILE",   "ENDFOR",       "UNTIL",
                                         "ENDLOOP", "M17 or RET", "its end label"};
  const auto k = static_cast<std::size_t>(f.kind);
  diag.fail_at_line(f.kind == FKind::call ? diag.line() : f.line, 1, "control-flow",
                    fmt::format("{}: the program ends inside it ({} missing)", names[k], ends[k]));
}

// ---------------------------------------------------------------- statements

bool SinumerikFrontEnd::statement(Words& words) {
  Cursor c = cur;
  const int col = c.col();
  const std::string_view kw = identifier(c);
  static constexpr const char* control_words[] = {
      "IF",    "ELSE",  "ENDIF", "WHILE",   "ENDWHILE", "FOR", "ENDFOR", "REPEAT", "UNTIL", "LOOP",   "ENDLOOP",
      "GOTOF", "GOTOB", "GOTO",  "REPEATB", "GOTOC",    "RET", "DEF",    "EXTERN", "MSG",   "STOPRE", "MCALL"};
  bool is_control = false;
  for (const char* k : control_words)
    if (kw == k) is_control = true;
  if (!is_control) return false;
  cur = c;
  if (kw == "MCALL") {
    cur.ws();
    if (cur.end()) {
      mcall_active = false;
      return true;
    }
    const int ccol = cur.col();
    Cursor save = cur;
    const std::string name(identifier(cur));
    if (name != "CYCLE81" && name != "CYCLE82" && name != "CYCLE83") {
      if (const char* r = refusal_of(name))
        fail(ccol, "unsupported", fmt::format("MCALL {}: {} is not supported by Kontur (dialect sinumerik)", name, r));
      fail(ccol, "unsupported",
           fmt::format("MCALL {}: only the drilling cycles CYCLE81, CYCLE82, CYCLE83 are called "
                       "modally by Kontur (dialect sinumerik)",
                       name));
    }
    // check the arguments now; they are read again at every position
    (void)cycle_arguments(cur, name);
    if (!cur.end())
      fail(cur.col(), "syntax", fmt::format("'{}': unexpected after the cycle call", cur.t.substr(cur.p, 16)));
    mcall_active = true;
    mcall_text = std::string(save.t.substr(save.p));
    mcall_column = ccol;
    (void)words;
    return true;
  }
  control(kw, cur, col);
  return true;
}

LineOutcome SinumerikFrontEnd::block(Words& words) {
  const int block_col = cur.col();
  read_words(words);
  // M17 (and M2 / M30 in a subprogram): the subprogram ends after this block
  bool sub_end = false;
  for (int i = 0; i < words.m_count; ++i) {
    const int m = words.m[static_cast<std::size_t>(i)];
    if (m == 17 || ((m == 2 || m == 30) && in_call())) {
      if (!in_call()) {
        words.m[static_cast<std::size_t>(i)] = 30;  // M17 in the main program ends it
        continue;
      }
      sub_end = true;
      for (int j = i; j + 1 < words.m_count; ++j) {
        words.m[static_cast<std::size_t>(j)] = words.m[static_cast<std::size_t>(j + 1)];
        words.m_column[static_cast<std::size_t>(j)] = words.m_column[static_cast<std::size_t>(j + 1)];
      }
      --words.m_count;
      --i;
    }
  }
  auto remove = [&](char letter) { words.present &= ~(1u << (letter - 'A')); };
  bool dwell = false, g9 = false, path_set = false;
  for (int i = 0; i < words.g_count; ++i) {
    const int g = words.g[static_cast<std::size_t>(i)];
    if (g == 40) dwell = true;
    if (g == 90000) g9 = true;
    if (g == 640 || g == 611) path_set = true;
    if (g >= 0 && g <= 30 && g % 10 == 0) motion_g = g;
    if (g == 170 || g == 180 || g == 190) plane_g = g;
    if (g == 200) inch = true;
    if (g == 210) inch = false;
  }
  // G2 / G3 with a centre and no end point: a full circle (the end is the start)
  bool arc_word = false;
  for (int i = 0; i < words.g_count; ++i)
    if (words.g[static_cast<std::size_t>(i)] == 20 || words.g[static_cast<std::size_t>(i)] == 30) arc_word = true;
  if ((arc_word || ((motion_g == 20 || motion_g == 30) && words.keyword == Keyword::none)) && !words.has('X') &&
      !words.has('Y') && !words.has('Z') && (words.has('I') || words.has('J') || words.has('K'))) {
    words.set('X', 0.0, words.first_column > 0 ? words.first_column : block_col);
    words.incremental_words |= 1u << ('X' - 'A');
  }
  if (g9) {  // G9: exact stop in this block only
    int j = 0;
    for (int i = 0; i < words.g_count; ++i)
      if (words.g[static_cast<std::size_t>(i)] != 90000) {
        words.g[static_cast<std::size_t>(j)] = words.g[static_cast<std::size_t>(i)];
        words.g_column[static_cast<std::size_t>(j++)] = words.g_column[static_cast<std::size_t>(i)];
      }
    words.g_count = j;
  }
  if (dwell) {  // G4 F: seconds, G4 S: spindle revolutions
    if (words.has('F') && words.has('S'))
      fail(words.col('S'), "dwell", "G4: F (seconds) or S (spindle revolutions), not both");
    if (words.has('F')) {
      words.set('P', words.get('F'), words.col('F'));
      remove('F');
    } else if (words.has('S')) {
      if (!(spindle_rpm > 0.0))
        fail(words.col('S'), "dwell",
             fmt::format("G4 S{}: a dwell in spindle revolutions needs a spindle speed S first", num(words.get('S'))));
      words.set('P', words.get('S') * 60.0 / spindle_rpm, words.col('S'));
      remove('S');
    } else {
      fail(block_col, "dwell", "G4: F (dwell time in seconds) or S (spindle revolutions) missing");
    }
  } else if (words.has('S')) {
    spindle_rpm = words.get('S');
  }
  // path control: G64 with the ADIS tolerance, G9 for one block
  if (path_set) {
    for (int i = 0; i < words.g_count; ++i)
      if (words.g[static_cast<std::size_t>(i)] == 640 || words.g[static_cast<std::size_t>(i)] == 611)
        path_g = words.g[static_cast<std::size_t>(i)];
  }
  if (path_g == 640 && (path_set || adis_given) && path_tolerance >= 0.0 && !words.has('P')) {
    if (!path_set) add_g(words, 640, block_col);
    words.set('P', path_tolerance, block_col);
  }
  adis_given = false;
  if (g9) {
    if (path_set) fail(block_col, "modal-group", "G9 with G60 / G64 in one block");
    add_g(words, 611, block_col);
    g9_restore = true;
  } else if (g9_restore) {
    g9_restore = false;
    if (!path_set) {
      add_g(words, path_g, block_col);
      if (path_g == 640 && path_tolerance >= 0.0 && !words.has('P')) words.set('P', path_tolerance, block_col);
    }
  }
  // a modal cycle call after every positioning block
  if (mcall_active && (words.has('X') || words.has('Y') || words.has('Z')) && !dwell &&
      words.frame_op == FrameOp::none) {
    Cursor c{mcall_text, 0};
    const std::string name(identifier(c));
    const auto args = cycle_arguments(c, name);
    expand_cycle(name, args, mcall_column);
  }
  if (sub_end) {
    if (external && frames.back().kind == FKind::call && frames.back().external)
      deferred_return = true;
    else
      end_of_sub(block_col);
  }
  if (words.empty() && !pending.empty()) {
    words = pending.front();
    pending.pop_front();
  }
  return words.empty() ? LineOutcome::nothing : LineOutcome::words;
}

void SinumerikFrontEnd::add_g(Words& words, int g, int col) {
  if (!words.add_g(g, col)) fail(col, "too-many-words", "more than 16 G codes in a block");
}

void SinumerikFrontEnd::read_words(Words& words) {
  bool first = true;
  while (!cur.end()) {
    const int col = cur.col();
    const char ch = cur.peek();
    if (ch == '(')
      fail(col, "comment",
           "'(': unexpected; it is not a comment on a Sinumerik (comments start with ';'; dialect sinumerik)");
    if (!is_ident_start(ch))
      fail(col, "syntax", fmt::format("'{}': unexpected character '{}'", cur.t.substr(cur.p, 16), ch));
    const std::size_t start = cur.p;
    const std::string name(identifier(cur));
    if (words.first_column == 0) words.first_column = col;
    const bool was_first = first;
    first = false;
    // an assignment to a variable or an R parameter
    Cursor look = cur;
    const bool eq = look.eat('=') && !(look.p < look.t.size() && look.t[look.p] == '=');
    const bool r_param = name.size() > 1 && name[0] == 'R' && all_digits(std::string_view(name).substr(1));
    if ((find_var(name) && (eq || cur.peek() == '[')) || (r_param && eq) || (name == "R" && cur.peek() == '[')) {
      assign(cur, name, col);
      continue;
    }
    if (r_param) fail(col, "syntax", fmt::format("{}: an R parameter in a block needs '=' (R1=5)", name));
    if (keyword_word(name, col, words)) continue;
    // An address: a letter and its value. Names start with two letters or '_' on a Sinumerik, so
    // that a letter and a digit are an address also without spaces (G1X10Y5, N10G0).
    const char letter = name[0];
    const bool address_form = name.size() == 1 || is_digit(name[1]);
    if (address_form && letter == 'L' && name.size() > 1) {  // L100: a subprogram call
      std::size_t digits = 1;
      while (digits < name.size() && is_digit(name[digits])) ++digits;
      cur.p = start + digits;
      call(name.substr(0, digits), cur, col);
      continue;
    }
    if (address_form && std::strchr("XYZIJKFSTDHMGPABCUVW", letter)) {
      cur.p = start + 1;
      address(letter, col, words);
      continue;
    }
    if (const char* r = refusal_of(name))
      fail(col, "unsupported", fmt::format("{}: {} is not supported by Kontur (dialect sinumerik)", name, r));
    if (was_first) {  // a subprogram called by its name
      call(name, cur, col);
      continue;
    }
    fail(col, "unknown-word", fmt::format("{}: unknown word or keyword (dialect sinumerik)", name));
  }
}

bool SinumerikFrontEnd::keyword_word(std::string_view name, int col, Words& words) {
  const std::string n(name);
  // addresses of several letters, with '='
  if (cur.peek() == '=' && (name == "CR" || name == "TURN" || name == "AP" || name == "RP" || name == "AR" || name == "ADIS" ||
                            name == "ADISPOS" || name == "RPL" ||
                            (name.size() == 2 && (name[0] == 'I' || name[0] == 'J' || name[0] == 'K') &&
                             name[1] >= '1' && name[1] <= '3'))) {
    ++cur.p;
    const double v = expr(cur);
    if (name == "CR") {
      if (words.has('R')) fail(col, "word-twice", "CR=: given twice in the block");
      words.set('R', v, col);
    } else if (name == "TURN") {
      if (v < 0.0 || v != std::floor(v))
        fail(col, "arc-turns", fmt::format("TURN={}: full turns must be an integer >= 0", num(v)));
      words.set('P', v + 1.0, col);
    } else if (name == "ADIS" || name == "ADISPOS") {
      if (v < 0.0) fail(col, "tolerance-range", fmt::format("{}={}: the rounding distance must be >= 0", name, num(v)));
      if (name == "ADIS") {
        path_tolerance = v;
        adis_given = true;
      }
    } else if (name == "AR") {
      if (words.has_arc_angle) fail(col, "word-twice", "AR=: given twice in the block");
      words.has_arc_angle = true;
      words.arc_angle = v;
    } else if (name == "AP" || name == "RP") {
      const unsigned bit = name == "AP" ? 1u : 2u;
      if (words.polar & bit) fail(col, "word-twice", fmt::format("{}=: given twice in the block", name));
      words.polar = static_cast<std::uint8_t>(words.polar | bit);
      (name == "AP" ? words.polar_angle : words.polar_radius) = v;
      if (words.polar_column == 0) words.polar_column = col;
    } else if (name == "RPL") {
      words.frame_rpl = v;
      words.frame_has_rpl = true;
    } else {
      const int point = name[1] - '1', axis = name[0] - 'I';
      if (words.has_indexed(point, axis)) fail(col, "word-twice", fmt::format("{}=: word given twice", name));
      words.set_indexed(point, axis, v, col);
    }
    return true;
  }
  if (name == "SUPA" || name == "G153") {
    add_g(words, 530, col);
    return true;
  }
  if (name == "CIP" || name == "CT") {
    if (words.keyword != Keyword::none)
      fail(col, "word-twice", fmt::format("{}: a second CIP or CT in the block", name));
    words.keyword = name == "CIP" ? Keyword::cip : Keyword::ct;
    words.keyword_column = col;
    motion_g = name == "CIP" ? 10000 : 10002;  // modal like G2 / G3
    return true;
  }
  static const std::pair<const char*, FrameOp> frame_ops[] = {
      {"TRANS", FrameOp::trans},   {"ATRANS", FrameOp::atrans},  {"ROT", FrameOp::rot},
      {"AROT", FrameOp::arot},     {"SCALE", FrameOp::scale},    {"ASCALE", FrameOp::ascale},
      {"MIRROR", FrameOp::mirror}, {"AMIRROR", FrameOp::amirror}};
  for (const auto& [word, op] : frame_ops)
    if (name == word) {
      if (!words.empty() || words.frame_op != FrameOp::none)
        fail(col, "frame-words", fmt::format("{}: a frame instruction stands in a block of its own", name));
      words.frame_op = op;
      words.frame_column = col;
      return true;
    }
  for (const char* k : no_op_keywords)
    if (name == k) {
      warn_once(n, col, fmt::format("{}: accepted, no effect on Kontur's path (dialect sinumerik)", name));
      return true;
    }
  if (name == "SETAL")
    fail(col, "alarm", "SETAL(..): the program raises an alarm here, and the control stops (dialect sinumerik)");
  if (cur.peek() == '(') {
    for (const char* k : no_op_calls)
      if (name == k) {
        warn_once(n, col, fmt::format("{}(..): accepted, no effect on Kontur's path (dialect sinumerik)", name));
        int depth = 0;
        bool in_string = false;
        while (cur.p < cur.t.size()) {
          const char ch = cur.t[cur.p++];
          if (ch == '"') in_string = !in_string;
          if (in_string) continue;
          if (ch == '(') ++depth;
          if (ch == ')' && --depth == 0) break;
        }
        if (depth != 0) fail(col, "syntax", fmt::format("{}(: ')' missing", name));
        return true;
      }
    if (name == "CYCLE81" || name == "CYCLE82" || name == "CYCLE83") return cycle_call(name, cur, col, words);
  }
  return false;
}

void SinumerikFrontEnd::address(char letter, int col, Words& words) {
  double v = 0.0;
  bool ac = false, ic = false;
  if (cur.eat('=')) {
    Cursor look = cur;
    const std::string_view id = identifier(look);
    if ((id == "AC" || id == "IC") && look.peek() == '(') {
      cur = look;
      ++cur.p;
      v = expr(cur);
      if (!cur.eat(')')) fail(cur.col(), "syntax", fmt::format("{}(: ')' expected", id));
      (id == "AC" ? ac : ic) = true;
      if (!std::strchr("XYZABCUVWIJK", letter))
        fail(col, "syntax",
             fmt::format("{}={}(..): AC / IC only on the axes X Y Z A B C U V W and on I J K", letter, id));
    } else if ((id == "DC" || id == "ACP" || id == "ACN") && look.peek() == '(') {
      fail(col, "unsupported",
           fmt::format("{}={}(..): positioning a rotary axis by the shortest way or in one direction (DC, ACP, ACN: "
                       "modulo axes) is not supported; A B C are read as plain angles (write {}=AC(..) or {}=IC(..))",
                       letter, id, letter, letter));
    } else if (cur.peek() == '"') {
      const std::string s = string_literal(cur);
      if (letter != 'T')
        fail(col, "syntax", fmt::format("{}=\"{}\": a string is a value of T (a tool name) only", letter, s));
      warn_once("T=", col, fmt::format("T=\"{}\": a tool by name is recorded as no tool number", s));
      return;
    } else {
      v = expr(cur);
    }
  } else {
    cur.ws();
    bool negative = false;
    if (cur.p < cur.t.size() && (cur.t[cur.p] == '-' || cur.t[cur.p] == '+')) negative = cur.t[cur.p++] == '-';
    cur.ws();
    if (cur.p >= cur.t.size() || !(is_digit(cur.t[cur.p]) || cur.t[cur.p] == '.'))
      fail(col, "syntax", fmt::format("{}: a number or '=' and an expression expected after the address", letter));
    v = number_literal(cur);
    if (negative) v = -v;
  }
  const std::string word = fmt::format("{}{}", letter, num(v));
  switch (letter) {
    case 'G': {
      const double r = std::round(v);
      if (std::abs(v - r) > 1e-9 || r < 0.0 || r > 9999.0)
        fail(col, "unknown-g-code", fmt::format("{}: unknown G code", word));
      const int g = static_cast<int>(r);
      auto refusal = [&](const char* what) {
        return fmt::format("G{}: {} is not supported by Kontur (dialect sinumerik)", g, what);
      };
      switch (g) {
        case 9:
          add_g(words, 90000, col);
          return;  // G9, taken out again in block()
        case 0:
        case 1:
        case 2:
        case 3:
        case 4:
        case 53:
        case 17:
        case 18:
        case 19:
        case 40:
        case 90:
        case 91:
        case 93:
        case 94:
        case 95:
        case 96:
        case 97:
        case 41:
        case 42:
          add_g(words, g * 10, col);  // the executor's code: G times 10
          return;
        case 110:
        case 111:
        case 112:
          if (words.pole_g != 0) fail(col, "modal-group", fmt::format("G{}: a second pole definition in the block", g));
          words.pole_g = g;
          words.polar_column = col;
          return;
        case 54:
        case 55:
        case 56:
        case 57:
          add_g(words, g * 10, col);
          return;
        case 500:
          warn_once("G500", col, "G500: no settable frame; Kontur's work offsets are all zero, read as G54");
          add_g(words, 540, col);
          return;
        case 60:
          add_g(words, 611, col);
          return;
        case 64:
        case 641:
        case 642:
        case 643:
        case 644:
        case 645:
          add_g(words, 640, col);
          return;
        case 601:
        case 602:
        case 603:
          warn_once("G60x", col, fmt::format("G{}: exact-stop window accepted, no effect on Kontur's path", g));
          return;
        case 70:
        case 700:
          add_g(words, 200, col);
          return;
        case 71:
        case 710:
          add_g(words, 210, col);
          return;
        case 25:
        case 26:
        case 450:
        case 451:
        case 153:
          warn_once(fmt::format("G{}", g), col,
                    fmt::format("G{}: accepted, no effect on Kontur's path (dialect sinumerik)", g));
          return;
        case 33:
        case 34:
        case 35:
        case 331:
        case 332:
        case 63:
          fail(col, "unsupported", refusal("thread cutting and tapping (spindle-synchronised motion)"));
        case 74:
        case 75:
          fail(col, "unsupported",
               refusal("reference point approach (G74 / G75: the machine's reference points are not known)"));
        case 58:
        case 59:
          fail(col, "unsupported", refusal("axial programmable offsets (G58 / G59)"));
        case 140:
        case 141:
        case 142:
        case 143:
        case 147:
        case 148:
        case 247:
        case 248:
        case 347:
        case 348:
        case 340:
        case 341:
          fail(col, "unsupported", refusal("soft approach and retract (G14x / G24x / G34x)"));
        default:
          break;
      }
      if (g >= 505 && g <= 599) {
        warn_once("G505", col, fmt::format("G{}: Kontur's work offsets are all zero, read as G54", g));
        add_g(words, 540, col);
        return;
      }
      fail(col, "unknown-g-code", fmt::format("G{}: unknown or unsupported G code (dialect sinumerik)", g));
    }
    case 'M': {
      const double r = std::round(v);
      if (std::abs(v - r) > 1e-9 || r < 0.0 || r > 99999.0)
        fail(col, "unknown-m-code", fmt::format("{}: unknown M code", word));
      if (!words.add_m(static_cast<int>(r), col)) fail(col, "too-many-words", "more than 8 M codes in a block");
      return;
    }
    case 'D':
      warn_once("D", col,
                fmt::format("{}: the tool edge (D) is recorded nowhere: Kontur follows the programmed path", word));
      return;
    case 'H':
      warn_once("H", col, fmt::format("{}: auxiliary functions (H) are ignored", word));
      return;
    default:
      break;
  }
  if (words.has(letter))
    fail(col, "word-twice",
         fmt::format("{}: word given twice in the block (first at column {})", word, words.col(letter)));
  words.set(letter, v, col);
  const std::uint32_t bit = 1u << (letter - 'A');
  if (ac) words.absolute_words |= bit;
  if (ic) words.incremental_words |= bit;
}

// ---------------------------------------------------------------- variables

SinumerikFrontEnd::Variable* SinumerikFrontEnd::find_var(std::string_view name) {
  auto& top = scopes.back();
  if (const auto it = top.find(name); it != top.end()) return &it->second;
  auto& main = scopes.front();
  if (const auto it = main.find(name); it != main.end()) return &it->second;
  return nullptr;
}

double SinumerikFrontEnd::store(VarType type, double v) {
  switch (type) {
    case VarType::integer:
      return std::round(v);
    case VarType::boolean:
      return v != 0.0 ? 1.0 : 0.0;
    case VarType::character:
      return std::round(v);
    default:
      return v;
  }
}

void SinumerikFrontEnd::define(Cursor& c) {
  const int col = c.col();
  std::string_view type_name = identifier(c);
  if (type_name == "NCK" || type_name == "CHAN" || type_name == "LUD" || type_name == "PUD") type_name = identifier(c);
  const std::optional<VarType> named = var_type_named(type_name);
  if (!named && type_name == "FRAME")
    fail(col, "unsupported",
         "DEF FRAME: frame variables are not supported by Kontur (dialect sinumerik); use TRANS / ROT");
  if (!named) fail(col, "syntax", fmt::format("DEF {}: unknown type (REAL INT BOOL CHAR STRING[n] AXIS)", type_name));
  const VarType type = *named;
  if (type == VarType::string) {  // STRING[n]
    if (!c.eat('[')) fail(c.col(), "syntax", "DEF STRING: its length [n] missing");
    (void)expr(c);
    if (!c.eat(']')) fail(c.col(), "syntax", "DEF STRING[: ']' expected");
  }
  for (;;) {
    const int ncol = c.col();
    const std::string name(identifier(c));
    if (name.empty()) fail(ncol, "syntax", fmt::format("DEF {}: a variable name expected", type_name));
    if (name.size() > 31) fail(ncol, "syntax", fmt::format("{}: a name has at most 31 characters", name));
    Variable v;
    v.type = type;
    if (c.eat('[')) {
      const double n = expr(c);
      if (!c.eat(']')) fail(c.col(), "syntax", fmt::format("{}[: ']' expected", name));
      if (n < 1.0 || n > 100000.0 || n != std::floor(n))
        fail(ncol, "syntax", fmt::format("{}[{}]: an array size is an integer 1 .. 100000", name, num(n)));
      if (type == VarType::string || type == VarType::axis)
        fail(ncol, "unsupported", fmt::format("{}: arrays of STRING or AXIS are not supported", name));
      v.is_array = true;
      v.array.assign(static_cast<std::size_t>(n), 0.0);
    }
    if (c.eat('=')) {
      if (v.is_array) fail(c.col(), "unsupported", fmt::format("{}: initialising an array is not supported", name));
      if (type == VarType::string)
        v.text = string_literal(c);
      else if (type == VarType::axis)
        v.text = std::string(identifier(c));
      else
        v.value = store(type, expr(c));
    }
    scopes.back()[name] = std::move(v);
    if (!c.eat(',')) break;
  }
  if (!c.end()) fail(c.col(), "syntax", fmt::format("'{}': unexpected after DEF", c.t.substr(c.p, 16)));
}

std::optional<SinumerikFrontEnd::VarType> SinumerikFrontEnd::var_type_named(std::string_view name) {
  if (name == "REAL") return VarType::real;
  if (name == "INT") return VarType::integer;
  if (name == "BOOL") return VarType::boolean;
  if (name == "CHAR") return VarType::character;
  if (name == "STRING") return VarType::string;
  if (name == "AXIS") return VarType::axis;
  return std::nullopt;
}

double& SinumerikFrontEnd::array_element(Cursor& c, Variable& v, std::string_view name, int col) {
  if (!c.eat('[')) fail(c.col(), "syntax", fmt::format("{}: an array needs an index [i]", name));
  const double i = expr(c);
  if (!c.eat(']')) fail(c.col(), "syntax", fmt::format("{}[: ']' expected", name));
  const double r = std::round(i);
  if (r < 0 || r >= static_cast<double>(v.array.size()))
    fail(col, "index-range", fmt::format("{}[{}]: index beyond 0 .. {}", name, num(i), v.array.size() - 1));
  return v.array[static_cast<std::size_t>(r)];
}

std::size_t SinumerikFrontEnd::r_index(Cursor& c, int col) {
  ++c.p;  // '['
  const double i = expr(c);
  if (!c.eat(']')) fail(c.col(), "syntax", "R[: ']' expected");
  const double r = std::round(i);
  if (std::abs(r - i) > 1e-9 || r < 0 || r >= r_count)
    fail(col, "parameter-range", fmt::format("R[{}]: R parameters are R0 .. R{}", num(i), r_count - 1));
  return static_cast<std::size_t>(r);
}

double* SinumerikFrontEnd::lvalue(Cursor& c, std::string_view name, int col, VarType* type) {
  *type = VarType::real;
  if (name == "R" && c.peek() == '[') return &r_[r_index(c, col)];
  if (Variable* v = find_var(name)) {
    *type = v->type;
    if (v->is_array) {
      return &array_element(c, *v, name, col);
    }
    return &v->value;
  }
  const long r = std::strtol(std::string(name.substr(1)).c_str(), nullptr, 10);
  if (r >= r_count || name.size() > 5)
    fail(col, "parameter-range", fmt::format("{}: R parameters are R0 .. R{}", name, r_count - 1));
  return &r_[static_cast<std::size_t>(r)];
}

void SinumerikFrontEnd::assign(Cursor& c, std::string_view name, int col) {
  VarType type;
  Variable* var = find_var(name);
  if (var && (var->type == VarType::string || var->type == VarType::axis)) {
    if (!c.eat('=')) fail(c.col(), "syntax", fmt::format("{}: '=' expected", name));
    if (var->type == VarType::string)
      var->text = string_literal(c);
    else
      var->text = std::string(identifier(c));
    return;
  }
  double* target = lvalue(c, name, col, &type);
  if (!c.eat('=')) fail(c.col(), "syntax", fmt::format("{}: '=' expected", name));
  const double v = expr(c);
  *target = store(type, v);
}

}  // namespace kontur::gcode::detail
