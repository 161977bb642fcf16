// The Fanuc family's control flow: GOTO / IF .. GOTO to N numbers, WHILE .. DO m / END m loops,
// M98 / M97 subprograms and G65 macro calls with M99 returns, by seeking in the streamed program.
#include <algorithm>
#include <cctype>
#include <cmath>

#include "fanuc_front_end.hpp"
#include "message_format.hpp"

namespace kontur::gcode::detail {
namespace {

// An integer word value (a program or N number, a count), or -1.
long whole(double v) {
  const double r = std::round(v);
  if (std::abs(v - r) > integer_tolerance || r < 0.0 || r > 1e12) return -1;
  return static_cast<long>(r);
}

}  // namespace

void FanucFrontEnd::index_file(bool want_labels) {
  if (want_labels ? labels_indexed : programs_indexed) return;
  programs_indexed = true;
  labels_indexed = want_labels;
  programs.clear();
  end_offset = static_cast<std::size_t>(-1);
  const std::size_t back = input.tell();
  const long here = diag.line();
  input.seek(0, 1);
  std::string_view raw;
  bool content = false;
  while (input.read_line(raw)) {
    const std::size_t at = input.line_start();
    const long ln = diag.line();
    std::size_t i = 0;
    auto skip_blank = [&] {
      while (i < raw.size() && (raw[i] == ' ' || raw[i] == '\t')) ++i;
    };
    skip_blank();
    if (i < raw.size() && raw[i] == '%') {
      ++i;
      skip_blank();
      if (i >= raw.size() || raw[i] == '\r') {
        if (content && end_offset == static_cast<std::size_t>(-1)) end_offset = at;
        continue;
      }
    }
    if (i < raw.size() && raw[i] == '/') {
      ++i;
      skip_blank();
    }
    if (i >= raw.size() || raw[i] == '\r') continue;
    content = true;
    const char c = static_cast<char>(raw[i] & ~0x20);
    if ((c == 'O' || raw[i] == ':') && i + 1 < raw.size() && std::isalnum(static_cast<unsigned char>(raw[i + 1]))) {
      std::size_t j = i + 1;
      long number = 0;
      bool digits = true;
      while (j < raw.size() && std::isalnum(static_cast<unsigned char>(raw[j]))) {
        if (!std::isdigit(static_cast<unsigned char>(raw[j])))
          digits = false;
        else if (number < 100000000)
          number = number * 10 + (raw[j] - '0');
        ++j;
      }
      std::string name(1, 'O');
      name.append(raw.substr(i + 1, j - i - 1));
      for (char& ch : name) ch = static_cast<char>(std::toupper(static_cast<unsigned char>(ch)));
      programs.push_back(Program{digits ? number : -1, std::move(name), Pos{at, ln}, Pos{input.tell(), ln + 1}});
      continue;
    }
    if (want_labels && c == 'N' && i + 1 < raw.size() && std::isdigit(static_cast<unsigned char>(raw[i + 1]))) {
      long n = 0;
      for (std::size_t j = i + 1;
           j < raw.size() && std::isdigit(static_cast<unsigned char>(raw[j])) && n < 100000000000L; ++j)
        n = n * 10 + (raw[j] - '0');
      labels[n].push_back(Pos{at, ln});
    }
  }
  input.seek(back, here + 1);
}

std::pair<std::size_t, std::size_t> FanucFrontEnd::program_extent(std::size_t offset) const {
  std::size_t begin = 0, end = end_offset;
  for (const Program& p : programs) {
    if (p.header.offset <= offset)
      begin = p.body.offset;
    else {
      end = std::min(end, p.header.offset);
      break;
    }
  }
  return {begin, end};
}

const FanucFrontEnd::Program* FanucFrontEnd::find_program(long number) const {
  for (const Program& p : programs)
    if (p.number == number) return &p;
  return nullptr;
}

void FanucFrontEnd::jump(const Pos& to) {
  input.seek(to.offset, to.line);
  diag.set_line(line_no);  // the words of this line still report here
  resume_line = to.line;
}

void FanucFrontEnd::loop_guard(int column, const std::string& what) {
  if (++loop_iterations > opt.max_loop_iterations)
    diag.fail(column, "loop",
              fmt::format(
                  "{}: more than {} loop iterations, jumps back and calls in the program (endless loop?) (dialect {})",
                  what, opt.max_loop_iterations, to_string(dialect_)));
}

void FanucFrontEnd::goto_label(double n, int column, const std::string& what, std::size_t from, std::size_t scope_at) {
  const long label = whole(n);
  if (label < 0)
    diag.fail(column, "goto",
              fmt::format("{}: the block number must be a whole number >= 0 (dialect {})", what, to_string(dialect_)));
  index_file(true);
  const auto [begin, end] = program_extent(scope_at);
  const Pos* target = nullptr;
  if (const auto it = labels.find(label); it != labels.end()) {
    for (const Pos& p : it->second)
      if (p.offset >= from && p.offset < end) {
        target = &p;
        break;
      }
    if (!target)
      for (const Pos& p : it->second)
        if (p.offset >= begin && p.offset < end) {
          target = &p;
          break;
        }
  }
  if (!target)
    diag.fail(column, "goto",
              fmt::format("{}: no block N{} in this program (dialect {})", what, label, to_string(dialect_)));
  if (target->offset < from) loop_guard(column, what);
  jump(*target);
}

void FanucFrontEnd::while_do(std::size_t pos, int column) {
  const std::string& t = nl.text;
  std::size_t p = pos;
  MacroValue cond{1.0, false};
  const bool is_while = t.compare(p, 5, "WHILE") == 0;
  if (is_while) {
    p += 5;
    if (p >= t.size() || t[p] != '[') fail_at(nl, p, diag.context(), "syntax", "WHILE: a [condition] is expected");
    cond = value_at(p, false);
    if (t.compare(p, 2, "DO") != 0)
      fail_at(nl, p, diag.context(), "syntax", fmt::format("'{}': DO m expected after WHILE [..]", excerpt(nl, p)));
  }
  p += 2;
  if (p >= t.size() || !is_digit(t[p])) fail_at(nl, p, diag.context(), "syntax", "DO: a loop number 1..3 is expected");
  const double idv = parse_number(nl, p, diag.context());
  if (p < t.size()) fail_at(nl, p, diag.context(), "syntax", fmt::format("'{}': unexpected after DO", excerpt(nl, p)));
  if (idv != 1.0 && idv != 2.0 && idv != 3.0)
    diag.fail(column, "loop",
              fmt::format("DO{}: the loop number must be 1, 2 or 3 (dialect {})", num(idv), to_string(dialect_)));
  const int id = static_cast<int>(idv);
  const std::size_t level = calls.size();
  auto same = std::find_if(loops.begin(), loops.end(), [&](const Loop& l) { return l.id == id && l.level == level; });
  const bool running = same != loops.end() && same->head.offset == line_offset;
  const std::string what = fmt::format("{}DO{}", is_while ? "WHILE [..] " : "", id);
  if (cond.v != 0.0) {
    if (running) {
      loop_guard(column, what);
      return;
    }
    if (same != loops.end()) loops.erase(same, loops.end());  // left by a GOTO
    loops.push_back(Loop{id, Pos{line_offset, line_no}, level});
    return;
  }
  if (same != loops.end()) loops.erase(same, loops.end());
  skip_to_end(id, column, what);
}

void FanucFrontEnd::skip_to_end(int id, int column, const std::string& what) {
  std::string_view raw;
  while (input.read_line(raw)) {
    if (port_output(raw)) continue;
    normalize_line(raw, diag.context(), nl, rules);
    if (nl.percent && nl.text.empty()) break;
    const std::string& t = nl.text;
    if (!t.empty() && t[0] == 'O') break;
    std::size_t p = 0;
    if (p < t.size() && t[p] == 'N')
      for (++p; p < t.size() && is_digit(t[p]);) ++p;
    if (t.compare(p, 3, "END") == 0 && p + 3 < t.size() && is_digit(t[p + 3])) {
      p += 3;
      if (parse_number(nl, p, diag.context()) == static_cast<double>(id)) return;
    }
  }
  diag.fail_at_line(
      line_no, column, "loop",
      fmt::format("{}: END{} not found before the end of the program (dialect {})", what, id, to_string(dialect_)));
}

void FanucFrontEnd::end_loop(int id, int column) {
  const std::size_t level = calls.size();
  for (auto it = loops.rbegin(); it != loops.rend(); ++it)
    if (it->id == id && it->level == level) {
      const Pos head = it->head;
      jump(head);
      return;
    }
  diag.fail(column, "loop", fmt::format("END{}: no open WHILE [..] DO{} (dialect {})", id, id, to_string(dialect_)));
}

void FanucFrontEnd::call(CallKind kind, const Words& w, int column, const std::array<MacroValue, 34>* args) {
  const char* d = to_string(dialect_);
  const char* code = kind == CallKind::g65 ? "G65" : kind == CallKind::m98 ? "M98" : "M97";
  if (!w.has('P'))
    diag.fail(column, "subprogram",
              fmt::format("{}: P (the {}) missing (dialect {})", code,
                          kind == CallKind::m97 ? "block number" : "program number", d));
  long number = whole(w.get('P'));
  const std::string what = fmt::format("{} P{}", code, num(w.get('P')));
  if (number < 0)
    diag.fail(w.col('P'), "subprogram", fmt::format("{}: P must be a whole number (dialect {})", what, d));
  long repeats = 1;
  if (w.has('L')) {
    repeats = whole(w.get('L'));
    if (repeats < 0 || repeats > opt.max_loop_iterations)
      diag.fail(w.col('L'), "subprogram",
                fmt::format("{} L{}: the repeat count must be a whole number 0..{} (dialect {})", what, num(w.get('L')),
                            opt.max_loop_iterations, d));
  }
  index_file(kind == CallKind::m97);
  Pos start;
  if (kind == CallKind::m97) {
    const Pos* target = nullptr;
    if (const auto it = labels.find(number); it != labels.end()) {
      for (const Pos& p : it->second)
        if (p.offset >= next_offset) {
          target = &p;
          break;
        }
      if (!target) target = &it->second.front();
    }
    if (!target)
      diag.fail(column, "subprogram", fmt::format("{}: no block N{} in this file (dialect {})", what, number, d));
    start = *target;
  } else {
    const Program* prog = find_program(number);
    // Fanuc's older form M98 P0030 1000: the four digits before the last four are the repeat count
    if (!prog && kind == CallKind::m98 && dialect_ != Dialect::haas && number > 9999 && !w.has('L')) {
      if (const Program* split = find_program(number % 10000)) {
        prog = split;
        repeats = number / 10000;
        number %= 10000;
      }
    }
    if (!prog)
      diag.fail(column, "subprogram",
                fmt::format("{}: subprogram O{:04} is not in this file (dialect {}); Kontur reads one file: put the "
                            "subprogram after the main program's end",
                            what, number, d));
    start = prog->body;
  }
  if (repeats == 0) return;
  if (calls.size() >= 16)
    diag.fail(column, "subprogram", fmt::format("{}: calls nested more than 16 deep (dialect {})", what, d));
  loop_guard(column, what);
  calls.push_back(Call{kind, what, start, Pos{next_offset, line_no + 1}, repeats - 1, line_no, column, loops.size()});
  if (kind == CallKind::g65) {
    locals.emplace_back();
    for (std::size_t i = 1; i < 34; ++i)
      if (!(*args)[i].vacant) locals.back()[i] = Var{(*args)[i].v, true};
  }
  jump(start);
}

void FanucFrontEnd::return_from_sub(int column, bool has_p, double p) {
  Call& c = calls.back();
  loops.resize(std::min(loops.size(), c.loops));
  if (c.repeats_left > 0) {
    --c.repeats_left;
    loop_guard(column, c.what);
    jump(c.start);
    return;
  }
  const Call done = c;
  calls.pop_back();
  if (done.kind == CallKind::g65) locals.pop_back();
  if (has_p) {
    goto_label(p, column, fmt::format("M99 P{}", num(p)), done.ret.offset, done.ret.offset);
    return;
  }
  jump(done.ret);
}

LineOutcome FanucFrontEnd::next_program_reached(int column) {
  if (!calls.empty()) {
    const Call& c = calls.back();
    diag.fail_at_line(
        c.line, c.column, "subprogram",
        fmt::format("{}: the subprogram runs into the next program {} on line {} without M99 (dialect {})", c.what,
                    nl.text.substr(0, 16), line_no, to_string(dialect_)));
  }
  diag.warn(column,
            fmt::format("{}: the next program starts here: the main program{} ends without M30 (read as its end)",
                        nl.text.substr(0, 16), main_name.empty() ? "" : " " + main_name));
  return LineOutcome::program_end;
}

void FanucFrontEnd::at_end_of_input() {
  if (calls.empty()) {
    if (loops.empty()) return;
    const Loop& l = loops.back();
    diag.fail_at_line(l.head.line, 1, "loop",
                      fmt::format("DO{}: the program ends inside the loop (END{} missing) (dialect {})", l.id, l.id,
                                  to_string(dialect_)));
  }
  const Call& c = calls.back();
  diag.fail_at_line(c.line, c.column, "subprogram",
                    fmt::format("{}: the subprogram runs to the end of the file without M99 (dialect {})", c.what,
                                to_string(dialect_)));
}

}  // namespace kontur::gcode::detail
