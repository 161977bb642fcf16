// Dialect names and the detection of a program's dialect from its first lines (dialect.hpp).
// Each line is looked at once, upper-cased, for the marks of each dialect; the strongest kind of
// mark found decides (a Sinumerik or LinuxCNC construct over a grbl `$` line over Fanuc's syntax
// over a control named in a comment over what only a Fanuc accepts over the file's extension),
// the first of its kind names the line in the reason.
#include <kontur/error.hpp>
#include <kontur/gcode/dialect.hpp>
#include <kontur/tolerances.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <fstream>
#include <initializer_list>
#include <regex>
#include <string>
#include <string_view>

namespace kontur::gcode {

const char* to_string(Dialect dialect) noexcept {
  switch (dialect) {
    case Dialect::linuxcnc: return "linuxcnc";
    case Dialect::fanuc: return "fanuc";
    case Dialect::haas: return "haas";
    case Dialect::mitsubishi: return "mitsubishi";
    case Dialect::sinumerik: return "sinumerik";
    case Dialect::grbl: return "grbl";
    case Dialect::mach3: return "mach3";
  }
  return "?";
}

std::optional<Dialect> parse_dialect(std::string_view name) noexcept {
  for (Dialect d : all_dialects) {
    const std::string_view n = to_string(d);
    if (n.size() == name.size() &&
        std::equal(n.begin(), n.end(), name.begin(), [](char a, char b) {
          return a == std::tolower(static_cast<unsigned char>(b));
        }))
      return d;
  }
  return std::nullopt;
}

std::string dialect_names() {
  std::string s;
  for (Dialect d : all_dialects) {
    if (!s.empty()) s += '|';
    s += to_string(d);
  }
  return s;
}

namespace {

// Kinds of marks, strongest first.
enum Strength {
  syntax_sinumerik_or_linuxcnc = 0,
  grbl_command = 1,
  fanuc_syntax = 2,
  named = 3,
  fanuc_usage = 4,  // what only a Fanuc-family control accepts (axis words after G80, Mach3's G50 / G71)
  extension = 5
};

struct Mark {
  Dialect dialect = Dialect::linuxcnc;
  std::string reason;
  bool found = false;
};

// The line's text without comments "( )" and after ';', and the comments' text, both upper case.
void split_line(std::string_view raw, std::string& code, std::string& comments) {
  code.clear();
  comments.clear();
  int depth = 0;
  for (std::size_t i = 0; i < raw.size(); ++i) {
    const char c = static_cast<char>(std::toupper(static_cast<unsigned char>(raw[i])));
    if (depth == 0 && c == ';') {
      for (std::size_t k = i + 1; k < raw.size(); ++k)
        comments += static_cast<char>(std::toupper(static_cast<unsigned char>(raw[k])));
      break;
    }
    if (c == '(') ++depth;
    if (depth > 0) comments += c;
    else code += c;
    if (c == ')' && depth > 0) --depth;
  }
}

// The control a comment names, if any.
std::optional<Dialect> named_control(const std::string& comments, std::string& word) {
  struct Name {
    const char* text;
    Dialect dialect;
  };
  static constexpr Name names[] = {
      {"SINUMERIK", Dialect::sinumerik}, {"SIEMENS", Dialect::sinumerik}, {"HAAS", Dialect::haas},
      {"MITSUBISHI", Dialect::mitsubishi}, {"MELDAS", Dialect::mitsubishi}, {"MACH3", Dialect::mach3},
      {"MACH 3", Dialect::mach3}, {"MACH4", Dialect::mach3}, {"GRBL", Dialect::grbl}, {"FANUC", Dialect::fanuc},
      {"LINUXCNC", Dialect::linuxcnc}, {"EMC2", Dialect::linuxcnc}};
  for (const Name& n : names)
    if (comments.find(n.text) != std::string::npos) {
      word = n.text;
      return n.dialect;
    }
  return std::nullopt;
}

// Whether `s` holds one of `pieces`. std::regex costs microseconds a line with these patterns (a
// tenth of a whole run of dense G01): each pattern is tried only on a line holding a literal piece
// that every match of it contains, which leaves the result as it was.
bool holds_any(const std::string& s, std::initializer_list<std::string_view> pieces) {
  for (std::string_view p : pieces)
    if (s.find(p) != std::string::npos) return true;
  return false;
}

// Whether `s` holds a G followed by leading zeros and one of `numbers` (what "G0*(80)" needs).
bool holds_g(const std::string& s, std::initializer_list<std::string_view> numbers) {
  for (std::size_t g = s.find('G'); g != std::string::npos; g = s.find('G', g + 1)) {
    std::size_t d = g + 1;
    while (d < s.size() && s[d] == '0') ++d;
    for (std::string_view n : numbers)
      if (s.compare(d, n.size(), n) == 0) return true;
  }
  return false;
}

std::string first_token(const std::string& code) {
  const auto b = code.find_first_not_of(" \t");
  if (b == std::string::npos) return {};
  auto e = code.find_first_of(" \t", b);
  return code.substr(b, e == std::string::npos ? std::string::npos : e - b);
}

}  // namespace

DialectChoice detect_dialect(std::string_view name, std::string_view text) {
  // Each pattern is compiled when first used (most programs never need most of them: compiling
  // all of them took 1.3 % of a `kontur run` of circle_small_segments).
  // Sinumerik: headers, DEF, R parameters, labels' jumps, structured control flow without O-words,
  // cycles, frames, CR= / AP= / TURN=, G642.
  const auto sinumerik_re = []() -> const std::regex& {
    static const std::regex r(R"(^\s*%_N_\w+|^\s*%(MPF|SPF)\b|(^|[^A-Z#<_])(DEF\s+(REAL|INT|BOOL|AXIS|FRAME|STRING|CHAR)\b|R\d+\s*=|GOTO[FBC]\b|CYCLE\d+\s*\(|MCALL\b|ENDIF\b|ENDWHILE\b|ENDFOR\b|ENDLOOP\b|MSG\s*\(|A?TRANS\b|A?ROT\b|A?SCALE\b|A?MIRROR\b|CR\s*=|AP\s*=|RP\s*=|TURN\s*=|G64[1-5]\b|SUPA\b)|^\s*(N\d+\s+)?(IF|WHILE|FOR|LOOP|REPEAT|UNTIL|ELSE|RET)\b(?!\s*\[))");
    return r;
  };
  // LinuxCNC: O-word keywords, named parameters, its print comments.
  const auto linuxcnc_re = []() -> const std::regex& {
    static const std::regex r(R"(^\s*(N\d+\s*)?O\s*(<[^>]*>|\d+)\s*(SUB|ENDSUB|CALL|RETURN|IF|ELSEIF|ELSE|ENDIF|WHILE|ENDWHILE|DO|REPEAT|ENDREPEAT|BREAK|CONTINUE)\b|#<)");
    return r;
  };
  // (MSG, is Mach3's too: not a mark.
  const auto linuxcnc_comment_re = []() -> const std::regex& {
    static const std::regex r(R"(^\((DEBUG|PRINT|LOGOPEN|PROBEOPEN),)");
    return r;
  };
  // After G80, axis words without a motion code: a Fanuc keeps G0 / G1 (LinuxCNC refuses them).
  const auto g80_re = []() -> const std::regex& {
    static const std::regex r(R"((^|[^0-9.])G0*80(?![0-9.]))");
    return r;
  };
  // (any motion code: the lines, arcs, splines, threads, probes and cycles; the point lines of a
  // G5.2 block and the knot lines of a G6.2 curve follow their motion code)
  const auto group01_re = []() -> const std::regex& {
    static const std::regex r(R"((^|[^0-9.])G0*([0-3]|5(\.[1-3])?|6\.2|33(\.1)?|38\.[2-5]|7[346]|8[1-9])(?![0-9.]))");
    return r;
  };
  const auto axis_words_re = []() -> const std::regex& {
    static const std::regex r(R"(^\s*(N\d+\s*)?[XYZ]\s*[-+.0-9])");
    return r;
  };
  // Mach3's G50 (scaling off) and G70 / G71 (inch / mm) in a block of modal codes only (LinuxCNC
  // has no G50, and its G70 / G71 are lathe cycles with P Q D words; a Fanuc lathe's G50 takes S X Z).
  const auto mach3_code_re = []() -> const std::regex& {
    static const std::regex r(R"((^|[^0-9.])G0*(50|70|71)(?![0-9.]))");
    return r;
  };
  const auto cycle_or_lathe_words_re = []() -> const std::regex& {
    static const std::regex r(R"([PQDUWSXZRIJK]\s*[-+.0-9#\[])");
    return r;
  };
  const auto grbl_re = []() -> const std::regex& {
    static const std::regex r(R"(^\s*\$(\d+\s*=|[HXJCGNI#$]))");
    return r;
  };
  // Fanuc's family: program numbers, Macro B control flow, subprogram and macro calls.
  const auto program_number_re = []() -> const std::regex& {
    static const std::regex r(R"(^\s*%?\s*([O:]\d+))");
    return r;
  };
  const auto macro_re = []() -> const std::regex& {
    static const std::regex r(R"(^\s*(N\d+\s*)?(IF\s*\[.*\]\s*(GOTO|THEN)|WHILE\s*\[.*\]\s*DO\s*\d|END\s*\d\b|GOTO\s*\d)|(^|[^0-9.])(M98\s*P|G65\s*P|M97\s*P))");
    return r;
  };

  Mark marks[6];
  auto note = [&](Strength s, Dialect d, std::string reason) {
    Mark& m = marks[s];
    if (m.found) return;
    m = Mark{d, std::move(reason), true};
  };
  std::optional<Dialect> fanuc_family_name;  // a comment naming Haas / Mitsubishi / Mach3 / Fanuc
  std::string fanuc_family_reason;  // "a comment naming HAAS on line 3", "Haas's M97 on line 5"

  std::string code, comments;
  long line = 0;
  bool after_g80 = false;  // a G80 and no motion code since
  std::size_t at = 0;
  while (at < text.size() && line < tolerances::gcode_dialect_detection_lines) {
    std::size_t end = text.find('\n', at);
    if (end == std::string_view::npos) end = text.size();
    std::string_view raw = text.substr(at, end - at);
    at = end + 1;
    ++line;
    if (!raw.empty() && raw.back() == '\r') raw.remove_suffix(1);
    if (raw.size() > static_cast<std::size_t>(tolerances::gcode_max_line_length)) continue;
    split_line(raw, code, comments);
    std::smatch m;
    // (the literal pieces each pattern's matches hold, in the order of its alternatives)
    const bool may_linuxcnc = holds_any(code, {"O", "#<"});
    if (!marks[syntax_sinumerik_or_linuxcnc].found) {
      if ((may_linuxcnc && std::regex_search(code, m, linuxcnc_re())) ||
          (!comments.empty() && std::regex_search(comments, m, linuxcnc_comment_re())))
        note(syntax_sinumerik_or_linuxcnc, Dialect::linuxcnc,
             fmt::format("LinuxCNC's '{}' on line {}", std::string(m[0]).substr(0, 24), line));
      else if (holds_any(code, {"%", "D", "=", "O", "C", "E", "(", "R", "G64", "U", "IF", "L"}) &&
               std::regex_search(code, m, sinumerik_re())) {
        std::string what = m[0];
        what.erase(0, what.find_first_not_of(" \t"));
        if (!what.empty() && !std::isalnum(static_cast<unsigned char>(what[0])) && what[0] != '%' && what[0] != '_')
          what.erase(0, 1);
        note(syntax_sinumerik_or_linuxcnc, Dialect::sinumerik, fmt::format("Sinumerik's '{}' on line {}", what, line));
      }
    }
    if (!marks[grbl_command].found && holds_any(code, {"$"}) && std::regex_search(code, m, grbl_re()))
      note(grbl_command, Dialect::grbl, fmt::format("grbl command '{}' on line {}", first_token(code), line));
    if (!marks[fanuc_syntax].found) {
      if (holds_any(code, {"O", ":"}) && std::regex_search(code, m, program_number_re()) &&
          !(may_linuxcnc && std::regex_search(code, linuxcnc_re()))) {
        const std::string number = m[1];
        // "O1234" alone or with a comment: a program number; "O1234 G0" is not.
        const std::string rest = code.substr(static_cast<std::size_t>(m.position(0) + m.length(0)));
        if (rest.find_first_not_of(" \t") == std::string::npos)
          note(fanuc_syntax, Dialect::fanuc, fmt::format("program number {} on line {}", number, line));
      } else if (holds_any(code, {"IF", "WHILE", "END", "GOTO", "M98", "G65", "M97"}) &&
                 std::regex_search(code, m, macro_re())) {
        std::string what = m[0];
        what.erase(0, what.find_first_not_of(" \t0123456789N"));
        note(fanuc_syntax, Dialect::fanuc, fmt::format("'{}' on line {}", what.substr(0, 24), line));
      }
    }
    // (a motion code only matters after a G80: it ends the stretch looked at)
    if (holds_g(code, {"80"}) && std::regex_search(code, g80_re())) after_g80 = true;
    else if (after_g80) {
      if (std::regex_search(code, group01_re())) after_g80 = false;
      else if (std::regex_search(code, axis_words_re())) {
        note(fanuc_usage, Dialect::fanuc,
             fmt::format("axis words without a motion code after G80 on line {} (a Fanuc keeps G0 / G1)", line));
        after_g80 = false;
      }
    }
    if (!marks[fanuc_usage].found && holds_g(code, {"50", "70", "71"}) && std::regex_search(code, m, mach3_code_re()) &&
        !std::regex_search(code, cycle_or_lathe_words_re()))
      note(fanuc_usage, Dialect::mach3,
           fmt::format("Mach3's {} on line {}", first_token(std::string(m[0]).substr(m[1].length())), line));
    std::string word;
    if (auto d = named_control(comments, word)) {
      const std::string reason = fmt::format("a comment naming {} on line {}", word, line);
      note(named, *d, reason);
      if (!fanuc_family_name && (*d == Dialect::haas || *d == Dialect::mitsubishi || *d == Dialect::mach3 ||
                                 *d == Dialect::fanuc)) {
        fanuc_family_name = *d;
        fanuc_family_reason = fmt::format("a comment naming {} on line {}", word, line);
      }
    }
    const auto haas_code_re = []() -> const std::regex& {
      static const std::regex r(R"((^|[^0-9.])(G187|M97\s*P))");
      return r;
    };  // accuracy control, local call
    if (!fanuc_family_name && holds_any(code, {"G187", "M97"}) && std::regex_search(code, m, haas_code_re())) {
      fanuc_family_name = Dialect::haas;
      fanuc_family_reason = fmt::format("Haas's {} on line {}", first_token(m[2]), line);
    }
  }
  std::string ext;
  if (const auto dot = name.rfind('.'); dot != std::string_view::npos)
    for (char c : name.substr(dot + 1)) ext += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (ext == "mpf" || ext == "spf") note(extension, Dialect::sinumerik, fmt::format("file extension .{}", ext));
  if (ext == "ngc") note(extension, Dialect::linuxcnc, "file extension .ngc");

  for (Mark& m : marks) {
    if (!m.found) continue;
    if ((&m == &marks[fanuc_syntax] || &m == &marks[fanuc_usage]) && fanuc_family_name) {
      return {*fanuc_family_name, fmt::format("{}, and {}", m.reason, fanuc_family_reason)};
    }
    return {m.dialect, m.reason};
  }
  return {Dialect::linuxcnc, fmt::format("no mark of another dialect in the first {} lines: LinuxCNC's reading",
                                         std::min<long>(line, tolerances::gcode_dialect_detection_lines))};
}

DialectChoice detect_dialect_of_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError("file", fmt::format("{}: cannot open the program", path));
  std::string head(256 * 1024, '\0');
  in.read(head.data(), static_cast<std::streamsize>(head.size()));
  head.resize(static_cast<std::size_t>(in.gcount()));
  return detect_dialect(path, head);
}

DialectChoice choose_dialect(const std::string& path, std::optional<Dialect> given, std::optional<Dialect> from_machine,
                             const std::string& machine_source) {
  if (given) return {*given, "given with --dialect"};
  if (from_machine)
    return {*from_machine, fmt::format("the machine file{}{}'s dialect", machine_source.empty() ? "" : " ",
                                       machine_source)};
  return detect_dialect_of_file(path);
}

}  // namespace kontur::gcode
