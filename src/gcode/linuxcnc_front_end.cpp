// The LinuxCNC dialect: a line is a tape mark, a deleted block, an O-word (control flow) or words
// and assignments.
#include "linuxcnc_front_end.hpp"

#include <algorithm>
#include <cctype>

namespace kontur::gcode::detail {

void LinuxcncFrontEnd::grbl_command(std::string_view line, int column) {
  const auto upper = [](char c) { return static_cast<char>(std::toupper(static_cast<unsigned char>(c))); };
  const char what = line.size() > 1 ? upper(line[1]) : ' ';
  // Homing before the program's first axis words only says where the run starts: at home, where a run
  // starts anyway. Later it would move to switches a machine file does not give.
  if (what == 'H' && !axis_words_seen) {
    diag.warn(column, fmt::format("{}: grbl's homing cycle before the program: the run starts at the home position",
                                  line));
    return;
  }
  if (what == 'H')
    fail(column, "grbl-homing",
         fmt::format("{}: grbl's homing cycle in the middle of a program moves to the machine's home switches, which "
                     "a machine file does not give (dialect grbl); home the machine before the program",
                     line));
  if (what == 'J')
    fail(column, "grbl-jog",
         fmt::format("{}: a grbl jog is a manual motion, not part of a program (dialect grbl); write it as G1", line));
  diag.warn(column, fmt::format("{}: a grbl setting or command, ignored: it does not move the axes", line));
}

LineOutcome LinuxcncFrontEnd::read_line(std::string_view raw, Words& words) {
  if (dialect_ == Dialect::grbl) {
    const auto first = raw.find_first_not_of(" \t");
    if (first != std::string_view::npos && raw[first] == '$') {
      auto line = raw.substr(first);
      while (!line.empty() && (line.back() == ' ' || line.back() == '\t' || line.back() == '\r')) line.remove_suffix(1);
      grbl_command(line, static_cast<int>(first) + 1);
      return LineOutcome::nothing;
    }
  }
  normalize_line(raw, diag.context(), nl);
  // A Fanuc / Haas program number ("O1234 (NAME)", ":0097", "%O1200"): the program's header, never
  // a LinuxCNC O-word (those have a keyword).
  const bool program_number = nl.text.size() >= 2 && nl.text[0] == 'O' &&
                              std::all_of(nl.text.begin() + 1, nl.text.end(), [](char c) { return c >= '0' && c <= '9'; });
  if (nl.percent && !nl.text.empty() && !program_number)
    fail_column(diag.context(), nl.percent_column, "percent",
                "'%' must stand alone on its line (tape start/end), or be followed by a program number");
  if (program_number && !program_number_warned) {
    program_number_warned = true;
    diag.warn(nl.first_column, fmt::format("{}: a program number (Fanuc, Haas), read as the program's name", nl.text));
  }
  if (nl.percent) {
    if (!seen_block && !tape) {
      tape = true;
      return LineOutcome::nothing;
    }
    return LineOutcome::program_end;
  }
  if (nl.text.empty() || program_number) return LineOutcome::nothing;
  if (nl.block_delete && opt.block_delete) return LineOutcome::nothing;
  seen_block = true;
  if (nl.text[0] == 'O') {
    control_flow();
    return LineOutcome::nothing;
  }
  parse_words(nl, diag.context(), params, words, assignments, assignment_count);
  for (std::size_t i = 0; i < assignment_count; ++i) {
    const auto& a = assignments[i];
    if (a.index > 0) params.set_numbered(a.index, a.value);
    else params.set_named(a.name, a.value);
  }
  for (const char c : {'X', 'Y', 'Z', 'A', 'B', 'C', 'U', 'V', 'W'})
    if (words.has(c)) axis_words_seen = true;
  return words.empty() ? LineOutcome::nothing : LineOutcome::words;
}

void LinuxcncFrontEnd::at_end_of_input() {
  if (frames.empty()) return;
  const auto& f = frames.back();
  static constexpr const char* names[] = {"sub", "endsub", "call", "return", "while", "endwhile", "do",
                                          "repeat", "endrepeat", "if"};
  const auto k = static_cast<std::size_t>(f.kind);
  diag.fail_at_line(f.line, 1, "o-word",
                    fmt::format("{} {}: the program ends inside it ({} missing)", f.label, k < 10 ? names[k] : "?",
                                f.kind == OKind::if_ ? "endif" : f.kind == OKind::call ? "endsub" :
                                f.kind == OKind::while_ ? "endwhile" : f.kind == OKind::do_ ? "while" : "endrepeat"));
}

}  // namespace kontur::gcode::detail
