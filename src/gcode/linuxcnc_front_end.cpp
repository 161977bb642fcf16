// The LinuxCNC dialect: a line is a tape mark, a deleted block, an O-word (control flow) or words
// and assignments.
#include "linuxcnc_front_end.hpp"

namespace kontur::gcode::detail {

LineOutcome LinuxcncFrontEnd::read_line(std::string_view raw, Words& words) {
  normalize_line(raw, diag.context(), nl);
  if (nl.percent) {
    if (!seen_block && !tape) {
      tape = true;
      return LineOutcome::nothing;
    }
    return LineOutcome::program_end;
  }
  if (nl.text.empty()) return LineOutcome::nothing;
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
