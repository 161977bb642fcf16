// The Fanuc family's lines: tape marks, program numbers, block delete, N numbers, Macro B
// statements and variables, and the words of a block with the codes a Fanuc runs apart from the
// executor (calls, no-ops, units of P).
#include "fanuc_front_end.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>

#include "message_format.hpp"
#include "modal_groups.hpp"

namespace kontur::gcode::detail {

FanucFrontEnd::FanucFrontEnd(const DialectServices& services)
    : dialect_(services.dialect),
      input(services.input),
      diag(services.diagnostics),
      opt(services.options),
      executor(services.executor),
      state(services.state) {
  rules.semicolon_comment = dialect_ == Dialect::mach3;  // Mach3 takes ';' comments; a Fanuc ends the block
  rules.comma = true;
  rules.polar = false;
  rules.dialect = to_string(dialect_);
  locals.emplace_back();
  if (dialect_ == Dialect::mach3) mach3_parameters.resize(mach3_parameter_end);
  reader = [this](double index, std::size_t at) { return read_var(index, at); };
}

void FanucFrontEnd::refuse(int column, const std::string& what, const std::string& why) const {
  diag.fail(column, "unsupported", fmt::format("{}: {} (dialect {})", what, why, to_string(dialect_)));
}

double FanucFrontEnd::units() const { return state && state->modal_state().units == Units::inch ? 25.4 : 1.0; }

MacroValue FanucFrontEnd::value_at(std::size_t& pos, bool word_value) {
  return parse_macro_value(nl, pos, diag.context(), reader, word_value);
}

std::string FanucFrontEnd::comment_after(int column) const {
  const auto from = static_cast<std::size_t>(std::max(column - 1, 0));
  const std::size_t open = raw_line.find('(', from);
  if (open == std::string::npos) return {};
  const std::size_t close = raw_line.find(')', open);
  return raw_line.substr(open + 1, close == std::string::npos ? std::string::npos : close - open - 1);
}

// ---------------------------------------------------------------- a line

int FanucFrontEnd::port_output(std::string_view raw) {
  std::size_t i = raw.find_first_not_of(" \t");
  if (i != std::string_view::npos && (raw[i] == 'N' || raw[i] == 'n')) {
    ++i;
    while (i < raw.size() && (is_digit(raw[i]) || raw[i] == ' ' || raw[i] == '\t')) ++i;
  }
  if (i == std::string_view::npos || i + 5 > raw.size()) return 0;
  std::string word(raw.substr(i, 5));
  for (char& ch : word) ch = static_cast<char>(std::toupper(static_cast<unsigned char>(ch)));
  const bool port = word == "DPRNT" || word == "BPRNT" || word == "POPEN" || word == "PCLOS";
  return port ? static_cast<int>(i) + 1 : 0;
}

LineOutcome FanucFrontEnd::read_line(std::string_view raw, Words& words) {
  if (resume_line >= 0) {  // the line after a jump: its own number
    diag.set_line(resume_line);
    resume_line = -1;
  }
  line_offset = input.line_start();
  next_offset = input.tell();
  line_no = diag.line();
  raw_line.assign(raw);
  // DPRNT[..] / BPRNT / POPEN / PCLOS: free text, no motion; not a block either (lines a tool put
  // before the O line leave it the main program's number)
  if (const int at = port_output(raw)) {
    diag.warn(at, fmt::format("{}: output to a port, ignored (it does not move the axes)",
                              raw_line.substr(static_cast<std::size_t>(at - 1), 5)));
    return LineOutcome::nothing;
  }
  normalize_line(raw, diag.context(), nl, rules);
  words.clear();
  if (nl.percent) {
    if (!nl.text.empty() && nl.text[0] != 'O')
      fail_column(diag.context(), nl.percent_column, "percent",
                  "'%' must stand alone on its line (tape start/end), or be followed by a program number");
    if (!seen_block && !tape) {
      tape = true;
      if (nl.text.empty()) return LineOutcome::nothing;
    } else {
      if (!calls.empty()) {
        const Call& c = calls.back();
        diag.fail_at_line(
            c.line, c.column, "subprogram",
            fmt::format("{}: the subprogram runs into the tape end '%' on line {} without M99 (dialect {})", c.what,
                        line_no, to_string(dialect_)));
      }
      return LineOutcome::program_end;
    }
  }
  if (nl.text.empty()) return LineOutcome::nothing;
  if (nl.text[0] == 'O') {  // a program number or name: the main program's header, or the next program
    if (!main_header_seen && !seen_block) {
      main_header_seen = true;
      main_name = nl.text.substr(0, 16);
      seen_block = true;
      return LineOutcome::nothing;
    }
    return next_program_reached(nl.first_column);
  }
  if (nl.block_delete && opt.block_delete) return LineOutcome::nothing;
  seen_block = true;
  return statements(0, words) ? LineOutcome::words : LineOutcome::nothing;
}

bool FanucFrontEnd::statements(std::size_t pos, Words& words) {
  const std::string& t = nl.text;
  auto col = [&](std::size_t p) { return p < nl.column.size() ? nl.column[p] : nl.column.back(); };
  auto starts = [&](std::size_t p, const char* s) { return t.compare(p, std::strlen(s), s) == 0; };
  if (pos < t.size() && t[pos] == 'N') {  // N number
    std::size_t p = pos + 1;
    long n = 0;
    std::size_t digits = 0;
    while (p < t.size() && is_digit(t[p])) {
      if (digits < 12) n = n * 10 + (t[p] - '0');
      ++digits;
      ++p;
    }
    if (digits == 0 || digits > 12)
      fail_at(nl, pos, diag.context(), "n-word", fmt::format("'{}': N needs 1 to 12 digits", excerpt(nl, pos)));
    words.n_number = n;
    pos = p;
  }
  if (pos >= t.size()) return false;
  const int c = col(pos);
  if (starts(pos, "GOTO")) {
    std::size_t p = pos + 4;
    const MacroValue n = value_at(p, false);
    if (p < t.size())
      fail_at(nl, p, diag.context(), "syntax", fmt::format("'{}': unexpected after GOTO", excerpt(nl, p)));
    executor.before_control_flow(c);
    goto_label(n.v, c, fmt::format("GOTO {}", num(n.v)), next_offset, line_offset);
    return false;
  }
  if (starts(pos, "IF")) {
    std::size_t p = pos + 2;
    if (p >= t.size() || t[p] != '[')
      fail_at(nl, p, diag.context(), "syntax", "IF: a [condition] is expected after IF");
    const MacroValue cond = value_at(p, false);
    if (starts(p, "GOTO")) {
      p += 4;
      const MacroValue n = value_at(p, false);
      if (p < t.size())
        fail_at(nl, p, diag.context(), "syntax", fmt::format("'{}': unexpected after GOTO", excerpt(nl, p)));
      if (cond.v != 0.0) {
        executor.before_control_flow(c);
        goto_label(n.v, c, fmt::format("IF .. GOTO {}", num(n.v)), next_offset, line_offset);
      }
      return false;
    }
    if (starts(p, "THEN")) {
      p += 4;
      if (p >= t.size() || t[p] != '#') refuse(col(p), "IF .. THEN", "only an assignment #i = .. may follow THEN");
      if (cond.v != 0.0) {
        assignment(p);
        if (p < t.size())
          fail_at(nl, p, diag.context(), "syntax",
                  fmt::format("'{}': unexpected after IF .. THEN #i = ..", excerpt(nl, p)));
      }
      return false;
    }
    fail_at(nl, p, diag.context(), "syntax", fmt::format("'{}': GOTO or THEN expected after IF [..]", excerpt(nl, p)));
  }
  if (starts(pos, "WHILE") || (starts(pos, "DO") && pos + 2 < t.size() && is_digit(t[pos + 2]))) {
    executor.before_control_flow(c);
    while_do(pos, c);
    return false;
  }
  if (starts(pos, "END") && pos + 3 < t.size() && is_digit(t[pos + 3])) {
    std::size_t p = pos + 3;
    const double id = parse_number(nl, p, diag.context());
    if (p < t.size())
      fail_at(nl, p, diag.context(), "syntax", fmt::format("'{}': unexpected after END", excerpt(nl, p)));
    executor.before_control_flow(c);
    end_loop(static_cast<int>(id), c);
    return false;
  }
  if (t[pos] == '#') assignment(pos);
  if (pos >= t.size()) return false;
  parse_words(pos, words);
  dialect_codes(words);
  return !words.empty();
}

void FanucFrontEnd::assignment(std::size_t& pos) {
  const std::string& t = nl.text;
  while (pos < t.size() && t[pos] == '#') {
    const std::size_t start = pos;
    ++pos;
    const double index = parse_macro_index(nl, pos, diag.context(), reader);
    if (pos >= t.size() || t[pos] != '=')
      fail_at(nl, start, diag.context(), "syntax",
              fmt::format("'{}': '=' expected after a variable at the start of a statement", excerpt(nl, start)));
    ++pos;
    const MacroValue v = value_at(pos, false);
    write_var(index, v, start);
  }
}

// ---------------------------------------------------------------- variables

int FanucFrontEnd::var_index(double index, std::size_t at) const {
  const double r = std::round(index);
  if (std::abs(index - r) > integer_tolerance || r < 0.0 || r > 99999.0)
    fail_at(nl, at, diag.context(), "parameter-range", fmt::format("#{}: not a variable number", num(index)));
  return static_cast<int>(r);
}

MacroValue FanucFrontEnd::read_var(double index, std::size_t at) {
  const int i = var_index(index, at);
  // Mach3 reads an unset parameter as 0, as LinuxCNC does; the Fanuc family as vacant
  const bool mach3 = dialect_ == Dialect::mach3;
  auto value = [mach3](const Var& v) { return MacroValue{v.v, !v.set && !mach3}; };
  if (i == 0) return MacroValue{0.0, true};
  if (i <= 33) return value(locals.back()[static_cast<std::size_t>(i)]);
  if (i >= 100 && i <= 199) return value(common100[static_cast<std::size_t>(i - 100)]);
  if (i >= 500 && i <= 999) return value(common500[static_cast<std::size_t>(i - 500)]);
  if (mach3 && i < mach3_parameter_end) return value(mach3_parameters[static_cast<std::size_t>(i)]);
  const int col = at < nl.column.size() ? nl.column[at] : 1;
  const bool haas_tool_data = dialect_ == Dialect::haas && ((i >= 1601 && i <= 2000) || (i >= 5401 && i <= 5999));
  if ((i >= 2001 && i <= 2999) || (i >= 10001 && i <= 19999) || haas_tool_data) {
    if (!tool_offset_warned) {
      tool_offset_warned = true;
      diag.warn(col, fmt::format("#{}: tool offsets and tool data are not modelled: read as 0 (warned once)", i));
    }
    return MacroValue{0.0, false};
  }
  if (i == 3001 || i == 3002 || i == 3011 || i == 3012 || i == 3901 || i == 3902) return MacroValue{0.0, false};
  if (state) {
    const double u = units();
    const ModalState& m = state->modal_state();
    auto num_of = [](double v) { return MacroValue{v, false}; };
    if (i >= 5001 && i <= 5003) return num_of(state->position()[i - 5001] / u);
    if (i >= 5041 && i <= 5043) return num_of(state->position()[i - 5041] / u);
    if (i >= 5021 && i <= 5023) return num_of(state->machine_position()[i - 5021] / u);
    if (i >= 5221 && i <= 5221 + 20 * 5 + 2 && (i - 5221) % 20 <= 2)
      return num_of(state->work_offset((i - 5221) / 20 + 1)[(i - 5221) % 20] / u);
    if ((i >= 5201 && i <= 5203) || (i >= 5081 && i <= 5083)) return num_of(0.0);  // external / tool offsets: none
    if (i >= 5211 && i <= 5213 && dialect_ == Dialect::mach3) return num_of(state->g92_offset()[i - 5211] / u);
    if (i == 4109) return num_of(state->feed_rate() / u);
    if (i == 4119) return num_of(m.spindle_rpm);
    if (i == 4120) return num_of(m.tool);
    if (i == 4111) return num_of(m.tool_length_h);
    if (i >= 4001 && i <= 4022) {
      const bool cycle = is_canned_cycle(m.motion_g10);
      switch (i) {
        case 4001:
          return num_of(state->group01_code());
        case 4002:
          return num_of(m.plane == Plane::xy ? 17 : m.plane == Plane::zx ? 18 : 19);
        case 4003:
          return num_of(m.distance == DistanceMode::absolute ? 90 : 91);
        case 4005:
          return num_of(m.feed_mode == FeedMode::inverse_time ? 93 : 94);
        case 4006:
          return num_of(m.units == Units::inch ? 20 : 21);
        case 4007:
          return num_of(40);
        case 4008:
          return num_of(m.tool_length_offset ? 43 : 49);
        case 4009:
          return num_of(cycle ? m.motion_g10 / 10 : 80);
        case 4010:
          return num_of(m.retract == RetractMode::initial_z ? 98 : 99);
        case 4011:
          return num_of(50);
        case 4012:
          return num_of(67);
        case 4013:
          return num_of(97);
        case 4014:
          return num_of(m.work_offset <= 6 ? 53 + m.work_offset : 54.1);
        case 4015:
          return num_of(m.path_control == PathControl::blend ? 64 : 61);
        case 4016:
          return num_of(69);
        case 4017:
          return num_of(15);
        default:
          return num_of(0.0);
      }
    }
  }
  fail_at(nl, at, diag.context(), "unsupported",
          fmt::format("#{}: a system variable Kontur does not read (dialect {})", i, to_string(dialect_)));
}

void FanucFrontEnd::write_var(double index, const MacroValue& value, std::size_t at) {
  const int i = var_index(index, at);
  const int col = at < nl.column.size() ? nl.column[at] : 1;
  const Var v{value.vacant ? 0.0 : value.v, !value.vacant};
  if (i >= 1 && i <= 33) {
    locals.back()[static_cast<std::size_t>(i)] = v;
    return;
  }
  if (i >= 100 && i <= 199) {
    common100[static_cast<std::size_t>(i - 100)] = v;
    return;
  }
  if (i >= 500 && i <= 999) {
    common500[static_cast<std::size_t>(i - 500)] = v;
    return;
  }
  if (dialect_ == Dialect::mach3 && i > 0 && i < mach3_parameter_end) {
    mach3_parameters[static_cast<std::size_t>(i)] = v;
    return;
  }
  const std::string what = fmt::format("#{}={}", i, value.vacant ? "#0" : num(value.v));
  if (i == 3000) {
    const std::string message = comment_after(col);
    diag.fail(col, "macro-alarm",
              fmt::format("{}: the program raises macro alarm {}{} (dialect {})", what,
                          3000 + static_cast<int>(value.v), message.empty() ? "" : " " + message, to_string(dialect_)));
  }
  if (i == 3006) {
    const std::string message = comment_after(col);
    diag.warn(col, fmt::format("{}: the program stops here with the message '{}' (read on)", what, message));
    return;
  }
  if (i == 3001 || i == 3002 || i == 3003 || i == 3004 || i == 3901 || i == 3902) return;  // clocks, counters, modes
  if ((i >= 2001 && i <= 2999) || (i >= 10001 && i <= 19999)) {
    diag.warn(col, fmt::format("{}: tool offsets are not modelled: the assignment is ignored", what));
    return;
  }
  if (i >= 5221 && i <= 5221 + 20 * 5 + 2 && (i - 5221) % 20 <= 2 && state) {
    if (value.vacant) return;
    state->set_work_offset((i - 5221) / 20 + 1, (i - 5221) % 20, value.v * units());
    return;
  }
  if (i == 0 || (i >= 4001 && i <= 4120) || (i >= 5001 && i <= 5043))
    diag.fail(col, "parameter-range", fmt::format("{}: #{} is read-only (dialect {})", what, i, to_string(dialect_)));
  refuse(col, what, "a system variable Kontur does not write");
}

// ---------------------------------------------------------------- words

void FanucFrontEnd::parse_words(std::size_t pos, Words& w) {
  const std::string& t = nl.text;
  integer_literal = 0;
  const auto& ctx = diag.context();
  while (pos < t.size()) {
    const char c = t[pos];
    const std::size_t start = pos;
    const int col = nl.column[pos];
    if (w.first_column == 0) w.first_column = col;
    if (c == ',') {
      if (pos + 1 < t.size() && (t[pos + 1] == 'C' || t[pos + 1] == 'R'))
        refuse(col, std::string(",") + t[pos + 1], "chamfers and corner roundings between blocks are not supported");
      fail_at(nl, start, ctx, "syntax", fmt::format("'{}': unexpected ','", excerpt(nl, start)));
    }
    if (c == '#')
      fail_at(nl, start, ctx, "syntax",
              fmt::format("'{}': an assignment must come before the words of the block", excerpt(nl, start)));
    if (!is_letter(c)) {
      if (is_digit(c) || c == '.' || c == '-' || c == '+')
        fail_at(nl, start, ctx, "syntax", fmt::format("'{}': a number without a word letter", excerpt(nl, start)));
      fail_at(nl, start, ctx, "syntax", fmt::format("'{}': unexpected character '{}'", excerpt(nl, start), c));
    }
    if (c == 'N')
      fail_at(nl, start, ctx, "n-word",
              fmt::format("'{}': N number not at the start of the block", excerpt(nl, start)));
    if (c == 'O')
      fail_at(nl, start, ctx, "o-word",
              fmt::format("'{}': a program number must stand on its own line", excerpt(nl, start)));
    ++pos;
    if (pos < t.size() && is_letter(t[pos]))
      fail_at(nl, start, ctx, "syntax", fmt::format("'{}': {} without a value", excerpt(nl, start), c));
    const bool literal = pos < t.size() && (is_digit(t[pos]) || t[pos] == '.' || t[pos] == '-' || t[pos] == '+');
    const MacroValue v = value_at(pos, true);
    const std::string_view word = std::string_view(t).substr(start, pos - start);
    if (pos < t.size() && (t[pos] == '+' || t[pos] == '-' || t[pos] == '*' || t[pos] == '/'))
      fail_at(nl, pos, ctx, "syntax",
              fmt::format("'{}': arithmetic in a word needs brackets (dialect {} reads {}#i or {}[expression])",
                          excerpt(nl, start), to_string(dialect_), c, c));
    if (v.vacant) continue;  // a vacant variable: the word is omitted (Fanuc)
    const bool integer = literal && word.find('.') == std::string_view::npos &&
                         word.find('#') == std::string_view::npos && word.find('[') == std::string_view::npos;
    if (c == 'G' || c == 'M') {
      const double scaled = c == 'G' ? v.v * 10.0 : v.v;
      const double r = std::round(scaled);
      if (std::abs(scaled - r) > integer_tolerance * 10.0 || r < 0.0 || r > 100000.0)
        fail_at(nl, start, ctx, c == 'G' ? "unknown-g-code" : "unknown-m-code",
                fmt::format("{}: unknown {} code {}{}", word, c, c, num(v.v)));
      const bool leading_zero = word.size() > 2 && word[1] == '0' && is_digit(word[2]);
      if (c == 'G' ? !w.add_g(static_cast<int>(r), col, leading_zero) : !w.add_m(static_cast<int>(r), col))
        fail_at(nl, start, ctx, "too-many-words", fmt::format("{}: too many {} codes in a block", word, c));
      continue;
    }
    if (w.has(c))
      fail_at(nl, start, ctx, "word-twice",
              fmt::format("{}: word given twice in the block (first at column {})", word, w.col(c)));
    w.set(c, v.v, col);
    if (integer) integer_literal |= 1u << static_cast<unsigned>(c - 'A');
  }
}

void FanucFrontEnd::dialect_codes(Words& w) {
  const char* d = to_string(dialect_);
  // Removes the G code at index i (times 10), or the M code.
  auto drop_g = [&](int i) {
    for (int k = i; k + 1 < w.g_count; ++k) {
      const auto a = static_cast<std::size_t>(k), b = static_cast<std::size_t>(k + 1);
      w.g[a] = w.g[b];
      w.g_column[a] = w.g_column[b];
      w.g_leading_zero[a] = w.g_leading_zero[b];
    }
    --w.g_count;
  };
  auto drop_m = [&](int i) {
    for (int k = i; k + 1 < w.m_count; ++k) {
      w.m[static_cast<std::size_t>(k)] = w.m[static_cast<std::size_t>(k + 1)];
      w.m_column[static_cast<std::size_t>(k)] = w.m_column[static_cast<std::size_t>(k + 1)];
    }
    --w.m_count;
  };
  auto drop = [&](const char* letters) {
    for (const char* l = letters; *l; ++l) w.present &= ~(1u << static_cast<unsigned>(*l - 'A'));
  };
  enum class Action { none, m98, m97, m99, g65 } action = Action::none;
  int action_col = 1;
  bool dwell_block = false, cycle_block = false, motion_word = false;
  for (int i = 0; i < w.g_count;) {
    const int g = w.g[static_cast<std::size_t>(i)];
    const int col = w.g_column[static_cast<std::size_t>(i)];
    const std::string name = g_name(g, w.g_leading_zero[static_cast<std::size_t>(i)] != 0);
    if (g == 51 && w.has('Q') && dialect_ != Dialect::mach3) {  // G05.1 Q1: AI contour control
      diag.warn(col, fmt::format("{} Q{}: look-ahead / AI contour control is the planner's business: read as no code",
                                 name, num(w.get('Q'))));
      drop("Q");
      drop_g(i);
      continue;
    }
    if (g == 80 && dialect_ != Dialect::mach3) {  // G08 P1: look-ahead control
      diag.warn(col, fmt::format("{}: look-ahead control is the planner's business: read as no code", name));
      drop("P");
      drop_g(i);
      continue;
    }
    if (g == 1870) {  // Haas G187 P E: accuracy control
      diag.warn(col, fmt::format("{}: accuracy control (smoothness) is the planner's business: read as no code", name));
      drop("PE");
      drop_g(i);
      continue;
    }
    // G10 L10..L13: the offset registers; the executor writes them (DialectRules::fanuc_offset_registers),
    // Mach3 has none
    if (g == 100 && w.has('L') && w.get('L') >= 10.0 && w.get('L') <= 13.0 && dialect_ == Dialect::mach3) {
      diag.warn(col, fmt::format("{} L{}: tool offsets are not modelled: ignored", name, num(w.get('L'))));
      drop("LPRXYZQ");
      drop_g(i);
      continue;
    }
    // cancel codes of features Kontur does not run (scaling, rotation, polar coordinates, mirror)
    if (g == 500 || g == 690 || g == 150 || g == 501) {
      if (g == 500 && (w.has('X') || w.has('Z')))
        refuse(col, name, "the lathe's coordinate system setting (G50 X Z) is not supported");
      if (g == 500 && w.has('S'))
        refuse(col, "G50 S",
               "the lathe's spindle speed limit: lathe programs (X as a diameter, feed per revolution) are not "
               "supported");
      drop_g(i);
      continue;
    }
    if (g == 1030) {  // Haas G103 P: block look-ahead limit
      diag.warn(col, fmt::format("{}: the look-ahead limit is the planner's business: read as no code", name));
      drop("P");
      drop_g(i);
      continue;
    }
    if (g == 680 || g == 510 || g == 511 || g == 160 || g == 310)
      refuse(col, name,
             g == 680   ? "coordinate system rotation is not supported"
             : g == 510 ? "scaling is not supported"
             : g == 511 ? "programmable mirror image is not supported"
             : g == 160 ? "polar coordinate programming is not supported"
                        : "the skip function (probing) is not supported");
    if (g == 100 && w.has('L') && w.get('L') == 20.0 && dialect_ != Dialect::mach3) {  // G54.1 Pn offsets
      diag.warn(col, fmt::format("{} L20: the additional work offsets (G54.1 Pn) are not modelled: ignored", name));
      drop("LPRXYZ");
      drop_g(i);
      continue;
    }
    if (g == 100 && w.has('L') && w.get('L') == 2.0 && w.has('P') && w.get('P') == 0.0 && dialect_ != Dialect::mach3)
      refuse(col, "G10 L2 P0", "the external work offset (EXT, shifting every work system) is not supported");
    if (g == 541 || g == 1540)
      refuse(col, name, "additional work coordinate systems (G54.1 Pn, Haas G154 Pn) are not supported");
    if (g == 650) {
      action = Action::g65;
      action_col = col;
      drop_g(i);
      continue;
    }
    if (g == 660 || g == 661) refuse(col, name, "modal macro calls are not supported");
    if (g == 670) {
      drop_g(i);
      continue;
    }
    if (g == 760 || g == 870 || g == 880 || g == 740)
      refuse(col, name,
             g == 740   ? "the left-hand tapping cycle is not supported"
             : g == 760 ? "the fine boring cycle (oriented spindle stop and shift) is not supported"
                        : "the back boring cycle is not supported");
    if (dialect_ == Dialect::mach3 && (g == 700 || g == 710)) {  // Mach3's older inch / mm codes
      w.g[static_cast<std::size_t>(i)] = g == 700 ? 200 : 210;
      ++i;
      continue;
    }
    if (g == 40) dwell_block = true;
    if (is_canned_cycle(g)) cycle_block = true;
    if (g == 0 || g == 10 || g == 20 || g == 30 || g == 800) motion_word = true;
    ++i;
  }
  for (int i = 0; i < w.m_count;) {
    const int m = w.m[static_cast<std::size_t>(i)];
    const int col = w.m_column[static_cast<std::size_t>(i)];
    if (m == 97 && dialect_ != Dialect::haas && dialect_ != Dialect::mach3)
      refuse(col, "M97", "Haas's local subprogram call is not this control's: read the program with --dialect haas");
    if (m == 98 || m == 99 || m == 97) {
      if (action != Action::none) refuse(col, fmt::format("M{}", m), "a second call or return in one block");
      action = m == 98 ? Action::m98 : m == 97 ? Action::m97 : Action::m99;
      action_col = col;
      drop_m(i);
      continue;
    }
    ++i;
  }
  // (a motion code beside G28 / G30 / G92 / G10 only sets the mode: DialectRules::motion_code_beside_nonmodal)
  // P of a dwell: an integer is milliseconds, with a decimal point seconds (G4 X: seconds)
  const bool p_ms = dialect_ != Dialect::mach3 && w.has('P') && (integer_literal >> ('P' - 'A') & 1u);
  if (dwell_block) {
    if (!w.has('P') && w.has('X') && dialect_ != Dialect::mach3) {
      w.set('P', w.get('X'), w.col('X'));
      drop("X");
    } else if (p_ms) {
      w.value[static_cast<std::size_t>('P' - 'A')] /= 1000.0;
    }
  } else if (action == Action::none && p_ms &&
             (cycle_block || (!motion_word && state && is_canned_cycle(state->modal_state().motion_g10)))) {
    w.value[static_cast<std::size_t>('P' - 'A')] /= 1000.0;
  }
  // the decimal point: whole units, as Haas and Mach3 read them; a Fanuc with DPI=0 would not
  if (!decimal_warned && (dialect_ == Dialect::fanuc || dialect_ == Dialect::mitsubishi) && action != Action::g65) {
    for (const char c : {'X', 'Y', 'Z', 'A', 'B', 'C', 'I', 'J', 'K', 'R', 'Q'}) {
      if (!w.has(c) || !(integer_literal >> (c - 'A') & 1u) || w.get(c) == 0.0) continue;
      if (c == 'K' && (cycle_block || (state && is_canned_cycle(state->modal_state().motion_g10)))) continue;
      decimal_warned = true;
      const double v = w.get(c);
      const bool angle = c == 'A' || c == 'B' || c == 'C';  // rotary axes: degrees, increments of 0.001 deg
      const char* unit = angle ? "deg" : units() == 1.0 ? "mm" : "inch";
      diag.warn(w.col(c),
                fmt::format("{}{}: written without a decimal point, read as {} {}; a {} with parameter 3401#0 "
                            "DPI=0 reads it as {} least increments ({} {}) (warned once)",
                            c, num(v), num(v), unit, d, num(v),
                            num(v * (angle || units() == 1.0 ? 0.001 : 0.0001)), unit));
      break;
    }
  }
  // U V W: on the Fanuc family's lathes the incremental X Y Z (U-4.6 is X 4.6 less); its mills have
  // A B C as their 4th and 5th axes (read), and no U V W axes. (G65's U V W are arguments.)
  if (action != Action::g65)
    for (const char c : {'U', 'V', 'W'})
      if (w.has(c))
        refuse(w.col(c), fmt::format("{}{}", c, num(w.get(c))),
               "a lathe's incremental X Y Z (U V W): lathe programs (X as a diameter, feed per revolution) are not "
               "supported; A B C are the rotary axes of a mill");
  switch (action) {
    case Action::none:
      return;
    case Action::m99: {
      const bool has_p = w.has('P');
      const double p = w.get('P');
      drop("P");
      if (calls.empty()) {
        diag.warn(action_col, fmt::format("M99 in the main program: a {} control starts the program again (endlessly); "
                                          "read as the program's end",
                                          d));
        w.add_m(30, action_col);
        return;
      }
      return_from_sub(action_col, has_p, p);
      return;
    }
    case Action::m98:
    case Action::m97: {
      Words call_words = w;
      drop("PL");
      if (w.has('K') && !cycle_block) drop("K");
      call(action == Action::m98 ? CallKind::m98 : CallKind::m97, call_words, action_col, nullptr);
      return;
    }
    case Action::g65: {
      static constexpr std::array<std::pair<char, int>, 21> arg_of = {
          {{'A', 1},  {'B', 2},  {'C', 3},  {'I', 4},  {'J', 5},  {'K', 6},  {'D', 7},
           {'E', 8},  {'F', 9},  {'H', 11}, {'M', 13}, {'Q', 17}, {'R', 18}, {'S', 19},
           {'T', 20}, {'U', 21}, {'V', 22}, {'W', 23}, {'X', 24}, {'Y', 25}, {'Z', 26}}};
      std::array<MacroValue, 34> args{};
      for (auto& a : args) a.vacant = true;
      for (const auto& [letter, index] : arg_of)
        if (w.has(letter)) args[static_cast<std::size_t>(index)] = MacroValue{w.get(letter), false};
      if (w.m_count > 0) args[13] = MacroValue{static_cast<double>(w.m[0]), false};
      if (w.g_count > 0) refuse(w.g_column[0], g_name(w.g[0]), "G65 takes no other G code in its block");
      const Words call_words = w;
      w.clear();
      call(CallKind::g65, call_words, action_col, &args);
      return;
    }
  }
}

}  // namespace kontur::gcode::detail
