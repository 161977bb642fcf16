// Sinumerik control flow by seeking in the streamed program: labels and GOTOF / GOTOB / GOTO /
// GOTOC (to a label or a block number), IF / ELSE / ENDIF, WHILE / ENDWHILE, FOR / ENDFOR,
// REPEAT / UNTIL, LOOP / ENDLOOP, and subprograms of the same file (PROC NAME or a
// %_N_NAME_SPF section) called by name, with M17 / RET. Loops, jumps back and calls count
// against ReaderOptions::max_loop_iterations (an endless loop is an error, not a hang).
#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>

#include "message_format.hpp"
#include "sinumerik_front_end.hpp"

namespace kontur::gcode::detail {
namespace {

bool is_open(std::string_view kw, bool single_if) {
  return (kw == "IF" && !single_if) || kw == "WHILE" || kw == "FOR" || kw == "REPEAT" || kw == "LOOP";
}
bool is_close(std::string_view kw) {
  return kw == "ENDIF" || kw == "ENDWHILE" || kw == "ENDFOR" || kw == "UNTIL" || kw == "ENDLOOP";
}
const char* kind_name(int k) {
  static constexpr const char* names[] = {
      "IF", "WHILE", "FOR", "REPEAT", "LOOP", "a subprogram call", "a repeated section"};
  return names[k];
}

}  // namespace

bool SinumerikFrontEnd::in_call() const noexcept {
  return std::any_of(frames.begin(), frames.end(), [](const Frame& f) { return f.kind == FKind::call; });
}

void SinumerikFrontEnd::loop_guard(const char* what) {
  if (++loop_iterations > opt.max_loop_iterations)
    diag.fail(1, "loop-limit",
              fmt::format("{}: more than {} loop iterations, jumps back and calls in the program (endless loop?)", what,
                          opt.max_loop_iterations));
}

std::string SinumerikFrontEnd::scan_keyword(bool& single_if, Head& head) {
  single_if = false;
  Cursor c = cur;
  head = read_head(c, true);
  if (head.deleted) return {};
  std::string kw(identifier(c));
  if (kw == "REPEAT" && !c.end()) return "REPEAT_SECTION";  // REPEAT label: no loop to close
  if (kw == "IF") {
    while (!c.end()) {
      const std::string_view id = identifier(c);
      if (id == "GOTOF" || id == "GOTOB" || id == "GOTO" || id == "GOTOC") {
        single_if = true;
        break;
      }
      if (id.empty()) {
        if (c.peek() == '"') {
          ++c.p;
          while (c.p < c.t.size() && c.t[c.p] != '"') ++c.p;
        }
        ++c.p;
      }
    }
  }
  return kw;
}

bool SinumerikFrontEnd::next_scanned_line(std::string& kw, bool& single_if, Head& head) {
  std::string_view raw;
  while (in().read_line(raw)) {
    prepare(raw);
    if (cur.end()) continue;
    if (cur.peek() == '%') return false;
    kw = scan_keyword(single_if, head);
    return true;
  }
  return false;
}

std::string SinumerikFrontEnd::skip_to(const char* open, const char* middle, const char* close) {
  const long from = diag.line();
  int depth = 0;
  std::string kw;
  bool single_if = false;
  Head head;
  while (next_scanned_line(kw, single_if, head)) {
    if (kw == "PROC") break;
    if (kw == open && (kw != "IF" || !single_if)) {
      ++depth;
      continue;
    }
    if (depth == 0 && (kw == close || (middle && kw == middle))) return kw;
    if (kw == close) --depth;
  }
  diag.fail_at_line(from, 1, "control-flow",
                    fmt::format("{}: {} not found before the end of the program", open, close));
}

// ---------------------------------------------------------------- jumps

bool SinumerikFrontEnd::scan_forward(const std::string& label, long number) {
  const std::size_t resume = in().tell();
  const long resume_line = diag.line() + 1;
  const std::vector<Frame> saved = frames;
  int depth = 0;
  std::string kw;
  bool single_if = false;
  Head head;
  while (next_scanned_line(kw, single_if, head)) {
    if ((!label.empty() && head.label == label) || (number >= 0 && head.n == number)) {
      in().seek(in().line_start(), diag.line());
      return true;
    }
    if (kw == "PROC") break;
    if (is_open(kw, single_if))
      ++depth;
    else if (is_close(kw)) {
      if (depth > 0)
        --depth;
      else if (!frames.empty() && frames.back().kind != FKind::call)
        frames.pop_back();  // the jump leaves it
    }
  }
  frames = saved;
  in().seek(resume, resume_line);
  return false;
}

bool SinumerikFrontEnd::scan_backward(const std::string& label, long number) {
  const std::size_t here = in().line_start();
  const std::size_t resume = in().tell();
  const long resume_line = diag.line() + 1;
  Position target{0, 0};
  bool found = false;
  if (!label.empty()) {
    const auto it = labels.find(label);
    if (it != labels.end() && it->second.offset <= here) {
      target = it->second;
      found = true;
    }
  } else {  // a block number: the last one before this line, from the start of the file
    in().seek(0, 1);
    std::string_view raw;
    while (in().read_line(raw) && in().line_start() < here) {
      prepare(raw);
      Cursor c = cur;
      const Head head = read_head(c, true);
      if (head.n == number) {
        target = Position{in().line_start(), diag.line()};
        found = true;
      }
    }
    in().seek(resume, resume_line);
  }
  if (!found) return false;
  // loops and conditionals that start after the target are left
  while (!frames.empty() && frames.back().kind != FKind::call && frames.back().offset > target.offset)
    frames.pop_back();
  loop_guard(label.empty() ? "GOTOB" : label.c_str());
  in().seek(target.offset, target.line);
  return true;
}

void SinumerikFrontEnd::jump(std::string_view how_text, Cursor& c, int col) {
  const std::string how(how_text);  // the line's text is overwritten by the search
  c.ws();
  std::string label;
  long number = -1;
  const int tcol = c.col();
  if (c.p < c.t.size() && c.t[c.p] >= '0' && c.t[c.p] <= '9') {
    number = static_cast<long>(number_literal(c));
  } else {
    const std::string id(identifier(c));
    if (id.empty()) fail(tcol, "syntax", fmt::format("{}: a label or block number expected", how));
    if (id.size() > 1 && id[0] == 'N' &&
        std::all_of(id.begin() + 1, id.end(), [](char d) { return d >= '0' && d <= '9'; }))
      number = std::strtol(id.c_str() + 1, nullptr, 10);
    else
      label = id;
  }
  if (!c.end()) fail(c.col(), "syntax", fmt::format("'{}': unexpected after the jump target", c.t.substr(c.p, 16)));
  const std::string target = label.empty() ? fmt::format("N{}", number) : label;
  bool found = false;
  if (how == "GOTOF")
    found = scan_forward(label, number);
  else if (how == "GOTOB")
    found = scan_backward(label, number);
  else
    found = scan_forward(label, number) || scan_backward(label, number);
  if (found || how == "GOTOC") return;
  fail(col, "jump-target",
       fmt::format("{} {}: jump target not found {}", how, target,
                   how == "GOTOF"   ? "after this line"
                   : how == "GOTOB" ? "before this line"
                                    : "in the program"));
}

// ---------------------------------------------------------------- IF, loops, RET

void SinumerikFrontEnd::control(std::string_view kw_text, Cursor& c, int col) {
  const std::string kw(kw_text);  // the line's text is overwritten when lines are skipped
  auto end_of_line = [&](std::string_view what) {
    if (!c.end()) fail(c.col(), "syntax", fmt::format("'{}': unexpected after {}", c.t.substr(c.p, 16), what));
  };
  auto top = [&](FKind kind, std::string_view what, const char* opener) -> Frame& {
    if (frames.empty() || frames.back().kind != kind)
      fail(col, "control-flow",
           fmt::format("{}: no open {}{}", what, opener,
                       frames.empty() ? ""
                                      : fmt::format(" (the innermost open construct is {})",
                                                    kind_name(static_cast<int>(frames.back().kind)))));
    return frames.back();
  };
  if (kw == "DEF") {
    define(c);
    return;
  }
  if (kw == "EXTERN") return;  // the declaration of a subprogram's parameters
  if (kw == "MSG") {
    warn_once("MSG", col, "MSG(..): messages are not shown by Kontur");
    return;
  }
  if (kw == "STOPRE") {
    end_of_line(kw);
    return;
  }
  executor.before_control_flow(col);
  const std::size_t here = in().line_start();
  const long line = diag.line();
  if (kw == "IF") {
    const double cond = expr(c);
    Cursor look = c;
    const std::string id(identifier(look));
    if (id == "GOTOF" || id == "GOTOB" || id == "GOTO" || id == "GOTOC") {
      c = look;
      if (cond != 0.0) jump(id, c, col);
      return;
    }
    end_of_line("the IF condition");
    if (cond != 0.0) {
      frames.push_back(Frame{FKind::if_, here, line});
      return;
    }
    if (skip_to("IF", "ELSE", "ENDIF") == "ELSE") frames.push_back(Frame{FKind::if_, here, line});
    return;
  }
  if (kw == "ELSE") {
    end_of_line(kw);
    top(FKind::if_, kw, "IF");
    skip_to("IF", nullptr, "ENDIF");
    frames.pop_back();
    return;
  }
  if (kw == "ENDIF") {
    end_of_line(kw);
    top(FKind::if_, kw, "IF");
    frames.pop_back();
    return;
  }
  if (kw == "WHILE") {
    const double cond = expr(c);
    end_of_line("the WHILE condition");
    const bool running = !frames.empty() && frames.back().kind == FKind::while_ && frames.back().offset == here;
    if (cond != 0.0) {
      if (running)
        loop_guard("WHILE");
      else
        frames.push_back(Frame{FKind::while_, here, line});
    } else {
      if (running) frames.pop_back();
      skip_to("WHILE", nullptr, "ENDWHILE");
    }
    return;
  }
  if (kw == "ENDWHILE") {
    end_of_line(kw);
    const Frame& f = top(FKind::while_, kw, "WHILE");
    in().seek(f.offset, f.line);
    return;
  }
  if (kw == "FOR") {
    const int vcol = c.col();
    const std::string name(identifier(c));
    if (name.empty()) fail(vcol, "syntax", "FOR: a counter variable expected (FOR I=1 TO 10)");
    const Variable* v = find_var(name);
    const bool r_param = name.size() > 1 && name[0] == 'R' &&
                         std::all_of(name.begin() + 1, name.end(), [](char d) { return d >= '0' && d <= '9'; });
    if (!v && !r_param)
      fail(vcol, "undefined-variable", fmt::format("FOR {}: variable not defined (DEF INT {})", name, name));
    if (v && (v->type != VarType::integer && v->type != VarType::real))
      fail(vcol, "syntax", fmt::format("FOR {}: the counter is an INT or REAL variable or an R parameter", name));
    if (!c.eat('=')) fail(c.col(), "syntax", fmt::format("FOR {}: '=' expected", name));
    const double first = expr(c);
    if (!eat_keyword(c, "TO")) fail(c.col(), "syntax", fmt::format("FOR {}: TO expected", name));
    const double last = expr(c);
    end_of_line("FOR");
    VarType type;
    Cursor dummy{name, name.size()};
    *lvalue(dummy, name, vcol, &type) = store(type, first);
    if (first > last) {
      skip_to("FOR", nullptr, "ENDFOR");
      return;
    }
    Frame f{FKind::for_, in().tell(), line + 1};
    f.var = name;
    f.end = last;
    frames.push_back(f);
    return;
  }
  if (kw == "ENDFOR") {
    end_of_line(kw);
    Frame& f = top(FKind::for_, kw, "FOR");
    VarType type;
    Cursor dummy{f.var, f.var.size()};
    double* counter = lvalue(dummy, f.var, col, &type);
    *counter = store(type, *counter + 1.0);
    if (*counter <= f.end) {
      loop_guard("FOR");
      in().seek(f.offset, f.line);
    } else {
      frames.pop_back();
    }
    return;
  }
  if (kw == "REPEAT" || kw == "REPEATB") {
    if (!c.end() || kw == "REPEATB") {
      repeat_section(c, col, kw == "REPEATB");
      return;
    }
    frames.push_back(Frame{FKind::repeat, in().tell(), line + 1});
    return;
  }
  if (kw == "UNTIL") {
    const double cond = expr(c);
    end_of_line("the UNTIL condition");
    const Frame& f = top(FKind::repeat, kw, "REPEAT");
    if (cond == 0.0) {
      loop_guard("REPEAT");
      in().seek(f.offset, f.line);
    } else {
      frames.pop_back();
    }
    return;
  }
  if (kw == "LOOP") {
    end_of_line(kw);
    frames.push_back(Frame{FKind::loop, in().tell(), line + 1});
    return;
  }
  if (kw == "ENDLOOP") {
    end_of_line(kw);
    const Frame& f = top(FKind::loop, kw, "LOOP");
    loop_guard("LOOP");
    in().seek(f.offset, f.line);
    return;
  }
  if (kw == "GOTOF" || kw == "GOTOB" || kw == "GOTO" || kw == "GOTOC") {
    jump(kw, c, col);
    return;
  }
  if (kw == "RET") {
    end_of_line(kw);
    end_of_sub(col);
    return;
  }
  fail(col, "internal", fmt::format("{}: statement not handled", kw));
}

// ---------------------------------------------------------------- program sections

void SinumerikFrontEnd::repeat_section(Cursor& c, int col, bool single) {
  const char* kw = single ? "REPEATB" : "REPEAT";
  const std::string start(identifier(c));
  if (start.empty()) fail(c.col(), "syntax", fmt::format("{}: a label expected", kw));
  std::string end_label;
  {
    Cursor look = c;
    const std::string id(identifier(look));
    if (!id.empty() && !(id == "P" && look.peek() == '=')) {
      if (single) fail(c.col(), "syntax", "REPEATB: one label (the block repeated)");
      end_label = id;
      c = look;
    }
  }
  long times = 1;
  if (identifier(c) == "P") {
    if (!c.eat('=')) fail(c.col(), "syntax", fmt::format("{} {} P: '=' expected", kw, start));
    const double p = expr(c);
    if (p < 1.0 || p != std::floor(p) || p > static_cast<double>(opt.max_loop_iterations))
      fail(col, "syntax", fmt::format("{} {} P={}: the repetitions are an integer >= 1", kw, start, num(p)));
    times = static_cast<long>(p);
  }
  if (!c.end()) fail(c.col(), "syntax", fmt::format("'{}': unexpected after {}", c.t.substr(c.p, 16), kw));
  const std::size_t here = in().line_start();
  const auto it = labels.find(start);
  if (it == labels.end() || it->second.offset >= here)
    fail(col, "jump-target", fmt::format("{} {}: label not found before this line", kw, start));
  if (!end_label.empty()) {
    const auto e = labels.find(end_label);
    if (e == labels.end() || e->second.offset >= here || e->second.offset < it->second.offset)
      fail(col, "jump-target",
           fmt::format("{} {} {}: the end label is not between the start label and this line", kw, start, end_label));
  }
  Frame f{FKind::section, it->second.offset, it->second.line};
  f.var = end_label;
  f.single = single;
  f.repeats = times;
  f.stop_offset = here;
  f.ret_offset = in().tell();
  f.ret_line = diag.line() + 1;
  loop_guard(kw);
  frames.push_back(std::move(f));
  in().seek(frames.back().offset, frames.back().line);
}

void SinumerikFrontEnd::end_section() {
  Frame& f = frames.back();
  if (--f.repeats > 0) {
    loop_guard("REPEAT");
    in().seek(f.offset, f.line);
    return;
  }
  const std::size_t offset = f.ret_offset;
  const long line = f.ret_line;
  frames.pop_back();
  in().seek(offset, line);
}

// ---------------------------------------------------------------- subprograms

void SinumerikFrontEnd::call(const std::string& name, Cursor& c, int col) {
  std::vector<double> args;
  if (c.eat('(')) {
    if (!c.eat(')')) {
      for (;;) {
        if (c.peek() == ',' || c.peek() == ')')
          args.push_back(0.0);  // an argument left out
        else
          args.push_back(expr(c));
        if (c.eat(')')) break;
        if (!c.eat(',')) fail(c.col(), "syntax", fmt::format("{}(: ',' or ')' expected", name));
      }
    }
  }
  long repeats = 1;
  if (c.peek() == 'P') {
    ++c.p;
    c.eat('=');
    const double p = expr(c);
    if (p < 1.0 || p != std::floor(p) || p > static_cast<double>(opt.max_loop_iterations))
      fail(col, "syntax", fmt::format("{} P{}: the repetitions are an integer >= 1", name, num(p)));
    repeats = static_cast<long>(p);
  }
  if (!c.end())
    fail(c.col(), "syntax", fmt::format("'{}': unexpected after the call of {}", c.t.substr(c.p, 16), name));
  const std::size_t return_offset = in().tell();
  const long return_line = diag.line() + 1;
  const auto known = procs.find(name);
  const bool external_file = (known != procs.end() && known->second.external) ||
                             (known == procs.end() && !find_proc(name) && open_external(name, col));
  if (!external_file && !procs.count(name)) {
    if (const char* r = refusal_of(name))
      fail(col, "unsupported", fmt::format("{}: {} is not supported by Kontur (dialect sinumerik)", name, r));
    fail(col, "unknown-word",
         fmt::format("{}: unknown word, or a subprogram found neither in this file nor as {}.SPF beside it "
                     "(dialect sinumerik)",
                     name, name));
  }
  if (external_file && !external) (void)open_external(name, col);  // called again
  const Proc& p = procs.at(name);
  if (args.size() > p.params.size())
    fail(col, "syntax",
         fmt::format("{}: {} arguments given, the subprogram has {} parameters", name, args.size(), p.params.size()));
  loop_guard(name.c_str());
  if (frames.size() >= 64) fail(col, "control-flow", fmt::format("{}: calls nested more than 64 deep", name));
  Frame f{FKind::call, return_offset, return_line};
  f.external = external_file;
  f.var = name;
  f.repeats = repeats;
  f.args = std::move(args);
  frames.push_back(std::move(f));
  enter_proc(frames.back(), true);
  c = Cursor{text, text.size()};
}

void SinumerikFrontEnd::enter_proc(const Frame& f, bool fresh) {
  const Proc& p = procs.at(f.var);
  Scope scope;
  for (std::size_t i = 0; i < p.params.size(); ++i) {
    Variable v;
    v.type = p.params[i].first;
    v.value = store(v.type, i < f.args.size() ? f.args[i] : 0.0);
    scope[p.params[i].second] = std::move(v);
  }
  if (fresh)
    scopes.push_back(std::move(scope));
  else
    scopes.back() = std::move(scope);
  in().seek(p.start.offset, p.start.line);
}

void SinumerikFrontEnd::end_of_sub(int col) {
  while (!frames.empty() && frames.back().kind != FKind::call) frames.pop_back();
  if (frames.empty()) {  // RET of a subprogram run as a program of its own
    end_requested = true;
    (void)col;
    return;
  }
  Frame& f = frames.back();
  if (--f.repeats > 0) {
    loop_guard(f.var.c_str());
    enter_proc(f, false);
    return;
  }
  const Position back{f.offset, f.line};
  const bool was_external = f.external;
  frames.pop_back();
  scopes.pop_back();
  if (was_external) {  // the main program goes on at the line after the call (read again)
    close_external();
    return;
  }
  in().seek(back.offset, back.line);
}

bool SinumerikFrontEnd::open_external(const std::string& name, int col) {
  namespace fs = std::filesystem;
  if (external)
    fail(col, "unsupported",
         fmt::format(
             "{}: a subprogram file calling another subprogram file is not supported by Kontur (dialect sinumerik)",
             name));
  const fs::path dir = fs::path(main_name).parent_path();
  std::string lower = name;
  for (char& ch : lower) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
  fs::path found;
  for (const std::string& file : {name + ".SPF", name + ".spf", lower + ".spf", lower + ".SPF"}) {
    std::error_code ec;
    const fs::path p = dir / file;
    if (fs::is_regular_file(p, ec)) {
      found = p;
      break;
    }
  }
  if (found.empty()) return false;
  auto file = std::make_unique<ProgramInput>(diag);
  file->open(found.string());
  external = std::move(file);
  main_line = diag.line();
  diag.set_file(std::make_shared<const std::string>(found.string()));
  diag.set_line(0);  // the subprogram file's own line numbers
  labels.swap(saved_labels);
  labels.clear();
  Proc proc{Position{0, 1}, {}, true};
  std::string_view raw;
  while (external->read_line(raw)) {  // its header and PROC line
    prepare(raw);
    if (cur.end()) continue;
    if (cur.peek() == '%') {
      proc.start = Position{external->tell(), diag.line() + 1};
      continue;
    }
    Cursor c = cur;
    (void)read_head(c, false);
    if (identifier(c) == "PROC") {
      const int pcol = c.col();
      const std::string pname(identifier(c));
      if (pname != name)
        fail(pcol, "syntax",
             fmt::format("PROC {}: the file {} is called as the subprogram {}", pname, found.string(), name));
      proc.params = proc_params(c);
      proc.start = Position{external->tell(), diag.line() + 1};
    }
    break;
  }
  procs[name] = std::move(proc);
  return true;
}

void SinumerikFrontEnd::close_external() {
  external.reset();
  diag.set_file(main_file);
  diag.set_line(main_line);
  labels.swap(saved_labels);
  saved_labels.clear();
}

std::vector<std::pair<SinumerikFrontEnd::VarType, std::string>> SinumerikFrontEnd::proc_params(Cursor& c) {
  std::vector<std::pair<VarType, std::string>> out;
  if (!c.eat('(')) return out;
  if (c.eat(')')) return out;
  for (;;) {
    const int col = c.col();
    std::string_view type_name = identifier(c);
    if (type_name == "VAR") type_name = identifier(c);
    const std::optional<VarType> named = var_type_named(type_name);
    if (!named || *named == VarType::string || *named == VarType::axis)
      fail(col, "unsupported",
           fmt::format("PROC: parameters of type {} are not supported (REAL INT BOOL CHAR)", type_name));
    const VarType type = *named;
    const std::string name(identifier(c));
    if (name.empty()) fail(c.col(), "syntax", "PROC: a parameter name expected");
    out.emplace_back(type, name);
    if (c.eat(')')) break;
    if (!c.eat(',')) fail(c.col(), "syntax", "PROC(: ',' or ')' expected");
  }
  return out;
}

bool SinumerikFrontEnd::find_proc(const std::string& name) {
  if (procs.count(name)) return true;
  const std::size_t resume = in().tell();
  const long resume_line = diag.line() + 1;
  bool found = false;
  bool after_header = false;  // %_N_NAME_SPF was read: a PROC line may follow
  std::string_view raw;
  while (in().read_line(raw)) {
    prepare(raw);
    if (cur.end()) continue;
    if (cur.peek() == '%') {
      if (found) break;
      if (text == "%_N_" + name + "_SPF" || text == "%SPF" + name.substr(name.starts_with("L") ? 1 : 0)) {
        procs[name] = Proc{Position{in().tell(), diag.line() + 1}, {}};
        found = after_header = true;
      }
      continue;
    }
    Cursor c = cur;
    (void)read_head(c, false);
    const std::string_view kw = identifier(c);
    if (kw == "PROC" && identifier(c) == name) {
      procs[name] = Proc{Position{in().tell(), diag.line() + 1}, proc_params(c)};
      found = true;
      break;
    }
    if (after_header) break;  // the section's first line is not its PROC line
  }
  in().seek(resume, resume_line);
  return found;
}

void SinumerikFrontEnd::define_proc(Cursor& c, int col, bool as_main) {
  const std::string name(identifier(c));
  if (name.empty()) fail(c.col(), "syntax", "PROC: a name expected");
  auto params_of = proc_params(c);
  if (as_main) {  // a subprogram file read on its own: its parameters are 0
    if (!params_of.empty())
      diag.warn(col,
                fmt::format("PROC {}: read as a program of its own; its {} parameters are 0", name, params_of.size()));
    for (const auto& [type, pname] : params_of) {
      Variable v;
      v.type = type;
      scopes.back()[pname] = std::move(v);
    }
    return;
  }
  if (!procs.count(name)) procs[name] = Proc{Position{in().tell(), diag.line() + 1}, std::move(params_of)};
  if (in_call()) {  // the next subprogram of the file: this one ends here
    end_of_sub(col);
    return;
  }
  end_requested = true;  // the main program ends where a subprogram starts
}

}  // namespace kontur::gcode::detail
