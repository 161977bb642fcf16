// LinuxCNC O-word control flow: subroutines, loops and conditionals, by seeking back in the
// streamed program (docs/gcode.md, "O-words").
#include "linuxcnc_front_end.hpp"
#include "message_format.hpp"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <cmath>
#include <cstring>

namespace kontur::gcode::detail {

LinuxcncFrontEnd::OWord LinuxcncFrontEnd::parse_oword(const NormalizedLine& line) const {
  const std::string& t = line.text;
  OWord o;
  std::size_t p = 1;
  if (p < t.size() && t[p] == '<') {
    const std::size_t close = t.find('>', p);
    if (close == std::string::npos) fail_at(line, 0, diag.context(), "o-word", "O<: '>' missing in the O-word label");
    o.label = t.substr(0, close + 1);
    p = close + 1;
  } else {
    while (p < t.size() && t[p] >= '0' && t[p] <= '9') ++p;
    if (p == 1) fail_at(line, 0, diag.context(), "o-word", fmt::format("'{}': O needs a number or <name>", t.substr(0, 20)));
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
  fail_at(line, p, diag.context(), "o-word",
                  fmt::format("'{}': unknown O-word keyword (sub endsub call return while endwhile do repeat endrepeat "
                              "if elseif else endif break continue)",
                              t.substr(0, 24)));
}

double LinuxcncFrontEnd::o_value(const OWord& o, std::size_t& at, const char* what) const {
  if (at >= nl.text.size())
    fail_at(nl, at, diag.context(), "o-word", fmt::format("{} {}: [value] missing", o.label, what));
  return parse_real_value(nl, at, diag.context(), params);
}

void LinuxcncFrontEnd::o_end_of_line(std::size_t at) const {
  if (at < nl.text.size())
    fail_at(nl, at, diag.context(), "syntax", fmt::format("'{}': unexpected text after the O-word", nl.text.substr(at, 20)));
}

LinuxcncFrontEnd::OWord LinuxcncFrontEnd::skip_to(const std::string& label, std::initializer_list<OKind> kinds, const char* what) {
  const long from = diag.line();
  std::string_view raw;
  while (input.read_line(raw)) {
    normalize_line(raw, diag.context(), nl);
    if (nl.text.empty() || nl.text[0] != 'O') continue;
    const OWord o = parse_oword(nl);
    if (o.label != label) continue;
    for (const OKind k : kinds)
      if (o.kind == k) return o;
  }
  diag.fail_at_line(from, 1, "o-word", fmt::format("{}: {} not found before the end of the file", label, what));
}

std::map<std::string, LinuxcncFrontEnd::SubStart, std::less<>>::iterator
LinuxcncFrontEnd::load_subroutine_file(const std::string& label, int col) {
  // LinuxCNC: o<name> call of a subroutine not in the program runs name.ngc (lower case) of the
  // first folder of SUBROUTINE_PATH that has it; the file holds o<name> sub ... o<name> endsub.
  std::vector<std::string> folders = opt.subroutine_path;
  if (folders.empty()) {
    const std::filesystem::path program(*diag.name());
    folders.push_back(program.has_parent_path() ? program.parent_path().string() : std::string("."));
  }
  std::string file;
  const std::size_t open = label.find('<');  // labels are written "O<name>"
  if (open != std::string::npos && label.size() > open + 2 && label.back() == '>') {
    file = label.substr(open + 1, label.size() - open - 2);
    for (char& c : file) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    file += ".ngc";
  }
  std::string path;
  std::error_code ec;
  for (const std::string& folder : folders)
    if (!file.empty() && std::filesystem::is_regular_file(std::filesystem::path(folder) / file, ec)) {
      path = (std::filesystem::path(folder) / file).string();
      break;
    }
  if (path.empty()) {
    std::string where;
    for (const std::string& folder : folders) {
      if (!where.empty()) where += ':';
      where += folder;
    }
    fail(col, "o-word-call",
         file.empty() ? fmt::format("{} call: subroutine not defined (define it with {} sub before the call)", label,
                                    label)
                      : fmt::format("{} call: subroutine not defined in the program, and no {} in the subroutine path "
                                    "{} (--subroutine-path, [RS274NGC] SUBROUTINE_PATH)",
                                    label, file, where));
  }
  // Read the file up to its "o<name> sub" line, note where the body starts, and come back.
  const std::size_t back = input.tell();
  const long back_line = diag.line() + 1;
  const NormalizedLine caller = nl;
  input.seek(input.add_file(path), 1);
  std::string_view raw;
  bool found = false;
  while (!found && input.read_line(raw)) {
    normalize_line(raw, diag.context(), nl);
    if (nl.text.empty() || nl.text[0] != 'O') continue;
    const OWord o = parse_oword(nl);
    if (o.kind == OKind::sub && o.label == label) {
      subs[label] = SubStart{input.tell(), diag.line() + 1};
      found = true;
    }
  }
  if (!found) fail(1, "o-word-call", fmt::format("{}: no {} sub in this file (called for {} call)", path, label, label));
  input.seek(back, back_line);
  nl = caller;
  return subs.find(label);
}

LinuxcncFrontEnd::Frame* LinuxcncFrontEnd::find_frame(const std::string& label) {
  for (auto it = frames.rbegin(); it != frames.rend(); ++it)
    if (it->label == label) return &*it;
  return nullptr;
}

void LinuxcncFrontEnd::loop_guard(const std::string& label) {
  if (++loop_iterations > opt.max_loop_iterations)
    diag.fail_at_line(diag.line(), 1, "o-word-loop",
                fmt::format("{}: more than {} loop iterations and calls in the program (endless loop?)", label,
                            opt.max_loop_iterations));
}

void LinuxcncFrontEnd::control_flow() {
  executor.before_control_flow(nl.first_column);  // closes a G6.2 curve, rejects an open G5.2
  const OWord o = parse_oword(nl);
  std::size_t at = o.rest;
  const int col = nl.first_column;
  switch (o.kind) {
    case OKind::sub: {
      o_end_of_line(at);
      subs[o.label] = SubStart{input.tell(), diag.line() + 1};
      skip_to(o.label, {OKind::endsub}, "endsub");
      return;
    }
    case OKind::call: {
      auto it = subs.find(o.label);
      if (it == subs.end()) it = load_subroutine_file(o.label, col);
      loop_guard(o.label);
      if (frames.size() >= 64) fail(col, "o-word-call", fmt::format("{} call: calls nested more than 64 deep", o.label));
      Frame f{OKind::call, o.label, input.tell(), diag.line() + 1};
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
      input.seek(it->second.offset, it->second.line);
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
      input.seek(f.offset, f.line);
      return;
    }
    case OKind::while_: {
      Frame* open = find_frame(o.label);
      if (open && open->kind == OKind::do_) {  // the end of a do ... while loop
        const double c = o_value(o, at, "while");
        o_end_of_line(at);
        if (c != 0.0) {
          loop_guard(o.label);
          input.seek(open->offset, open->line);
        } else {
          while (frames.back().label != o.label) frames.pop_back();
          frames.pop_back();
        }
        return;
      }
      const double c = o_value(o, at, "while");
      o_end_of_line(at);
      if (c != 0.0) {
        if (open && open->kind == OKind::while_ && open->offset == input.line_start()) {
          loop_guard(o.label);  // back at the head of a running loop
        } else {
          frames.push_back(Frame{OKind::while_, o.label, input.line_start(), diag.line()});
        }
      } else {
        if (open && open->kind == OKind::while_ && open->offset == input.line_start()) {
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
      input.seek(f->offset, f->line);
      return;
    }
    case OKind::do_:
      o_end_of_line(at);
      frames.push_back(Frame{OKind::do_, o.label, input.tell(), diag.line() + 1});
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
      Frame f{OKind::repeat, o.label, input.tell(), diag.line() + 1};
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
        input.seek(f->offset, f->line);
      } else {
        while (frames.back().label != o.label) frames.pop_back();
        frames.pop_back();
      }
      return;
    }
    case OKind::if_: {
      double c = o_value(o, at, "if");
      o_end_of_line(at);
      frames.push_back(Frame{OKind::if_, o.label, 0, diag.line()});
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
          input.seek(top.offset, top.line);
        } else if (loop == OKind::repeat) {
          if (--top.count > 0) input.seek(top.offset, top.line);
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

}  // namespace kontur::gcode::detail
