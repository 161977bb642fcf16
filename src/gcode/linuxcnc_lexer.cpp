// The LinuxCNC dialect's lexer: a raw line normalised (comments, spaces, case), then its words
// and assignments. Its values come from linuxcnc_expression.cpp.
#include "linuxcnc_lexer.hpp"

#include <kontur/error.hpp>

#include <fmt/format.h>

#include <cmath>

namespace kontur::gcode::detail {

std::string excerpt(const NormalizedLine& line, std::size_t pos, std::size_t max_len) {
  if (pos >= line.text.size()) return "end of line";
  std::string s = line.text.substr(pos, max_len);
  if (pos + max_len < line.text.size()) s += "...";
  return s;
}

void fail_at(const NormalizedLine& line, std::size_t pos, const LineContext& ctx, const char* rule,
             const std::string& message) {
  const int col = pos < line.column.size() ? line.column[pos] : (line.column.empty() ? 1 : line.column.back());
  fail_column(ctx, col, rule, message);
}

void normalize_line(std::string_view raw, const LineContext& ctx, NormalizedLine& out, const NormalizeRules& rules) {
  out.text.clear();
  out.column.clear();
  out.block_delete = false;
  out.percent = false;
  out.percent_column = 0;
  bool in_comment = false;
  int comment_column = 0;
  bool seen_content = false;
  bool in_name = false;
  for (std::size_t i = 0; i < raw.size(); ++i) {
    const char c = raw[i];
    const int col = static_cast<int>(i) + 1;
    const auto uc = static_cast<unsigned char>(c);
    if (uc == 0 || (uc < 32 && c != '\t' && c != '\r' && c != '\f' && c != '\v') || uc == 127)
      fail_column(ctx, col, "not-text", fmt::format("byte 0x{:02x}: not a text file (control character)", uc));
    if (in_comment) {
      if (c == ')') in_comment = false;
      else if (c == '(') fail_column(ctx, col, "comment", "'(' inside a comment: comments do not nest");
      continue;
    }
    if (c == '(') {
      in_comment = true;
      comment_column = col;
      continue;
    }
    if (c == ';') {
      if (rules.semicolon_comment) break;
      // Fanuc's end of block: nothing but spaces and comments may follow it
      for (std::size_t j = i + 1; j < raw.size(); ++j) {
        const char d = raw[j];
        if (d == ' ' || d == '\t' || d == '\r' || d == ';') continue;
        if (d == '(') {
          const std::size_t close = raw.find(')', j);
          if (close != std::string_view::npos) {
            j = close;
            continue;
          }
        }
        fail_column(ctx, col, "semicolon",
                    fmt::format("';': ends the block here (it is no comment in dialect {}); write comments in ( )",
                                rules.dialect));
      }
      break;
    }
    if (c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v') continue;
    if (c == '%') {
      if (seen_content) fail_column(ctx, col, "percent", "'%' must stand alone on its line (tape start/end)");
      out.percent = true;
      continue;
    }
    // '%' followed by a program number (Fanuc, Haas: "%O1200(NAME)"): the front end checks it
    if (out.percent && !seen_content) out.percent_column = col;
    if (c == '/' && !seen_content) {
      out.block_delete = true;
      seen_content = true;
      continue;
    }
    if (in_name) {  // #<name>: any printable character, spaces removed, upper case
      if (c == '>') in_name = false;
      if (uc >= 128) fail_column(ctx, col, "character", fmt::format("byte 0x{:02x}: only ASCII is allowed in a parameter name", uc));
      out.text.push_back((c >= 'a' && c <= 'z') ? static_cast<char>(c - 'a' + 'A') : c);
      out.column.push_back(col);
      continue;
    }
    if (c == '<' && !out.text.empty() && out.text.back() == '#') in_name = true;
    if (uc >= 128)
      fail_column(ctx, col, "character", fmt::format("byte 0x{:02x}: only ASCII is allowed outside comments", uc));
    const char u = (c >= 'a' && c <= 'z') ? static_cast<char>(c - 'a' + 'A') : c;
    const bool ok = is_letter(u) || is_digit(u) || u == '.' || u == '+' || u == '-' || u == '*' || u == '/' ||
                    u == '[' || u == ']' || u == '#' || u == '<' || u == '>' || u == '=' || u == '_' ||
                    (u == ',' && rules.comma) || ((u == '@' || u == '^') && rules.polar);
    if ((c == '@' || c == '^') && !rules.polar)
      fail_column(ctx, col, "character",
                  fmt::format("'{}': LinuxCNC's polar coordinates (@ radius, ^ angle) are not words of dialect {}", c,
                              rules.dialect));
    if (c == ':' && !seen_content) {  // Fanuc's ISO program number ":0097" is "O0097"
      out.first_column = col;
      seen_content = true;
      out.text.push_back('O');
      out.column.push_back(col);
      continue;
    }
    if (!ok) fail_column(ctx, col, "character", fmt::format("'{}': character not allowed outside comments", c));
    if (!seen_content) out.first_column = col;
    if (out.text.empty()) out.first_column = col;
    seen_content = true;
    out.text.push_back(u);
    out.column.push_back(col);
  }
  if (in_comment) fail_column(ctx, comment_column, "comment", "'(': comment not closed on its line");
  out.column.push_back(static_cast<int>(raw.size()) + 1);
}

void parse_words(const NormalizedLine& line, const LineContext& ctx, const ParameterTable& parameters, Words& w,
                 std::vector<Assignment>& assignments, std::size_t& assignment_count) {
  w.clear();
  assignment_count = 0;
  const std::string& t = line.text;
  std::size_t pos = 0;
  bool first = true;
  while (pos < t.size()) {
    const char c = t[pos];
    const std::size_t start = pos;
    const int col = line.column[pos];
    if (first) w.first_column = col;
    if (c == '#') {  // parameter assignment #1 = value, #<name> = value
      ++pos;
      if (assignment_count == assignments.size()) assignments.emplace_back();
      Assignment& a = assignments[assignment_count];
      if (pos < t.size() && t[pos] == '<') {
        a.index = 0;
        a.name.assign(parse_parameter_name(line, pos, ctx, parameters));
      } else {
        a.index = parse_parameter_index(line, pos, start, ctx, parameters);
        a.name.clear();
      }
      if (pos >= t.size() || t[pos] != '=')
        fail_at(line, start, ctx, "syntax", fmt::format("'{}': '=' expected after a parameter at the start of a word",
                                                        excerpt(line, start)));
      ++pos;
      a.value = parse_real_value(line, pos, ctx, parameters);
      ++assignment_count;
      first = false;
      continue;
    }
    if (c == '@' || c == '^') {  // LinuxCNC polar coordinates: @ radius, ^ angle [deg] (the executor's)
      const unsigned bit = c == '@' ? 2u : 1u;
      if (w.polar & bit) fail_at(line, start, ctx, "word-twice", fmt::format("{}: word given twice", c));
      ++pos;
      const double v = parse_real_value(line, pos, ctx, parameters);
      if (c == '@') w.polar_radius = v;
      else w.polar_angle = v;
      w.polar = static_cast<std::uint8_t>(w.polar | bit);
      if (w.polar_column == 0) w.polar_column = col;
      first = false;
      continue;
    }
    if (!is_letter(c)) {
      if (is_digit(c) || c == '.' || c == '-' || c == '+')
        fail_at(line, start, ctx, "syntax", fmt::format("'{}': a number without a word letter", excerpt(line, start)));
      fail_at(line, start, ctx, "syntax", fmt::format("'{}': unexpected character '{}'", excerpt(line, start), c));
    }
    if (t.compare(pos, 5, "CONIC") == 0 || t.compare(pos, 3, "CIP") == 0) {
      const bool conic = t.compare(pos, 5, "CONIC") == 0;
      if (w.keyword != Keyword::none)
        fail_at(line, start, ctx, "word-twice", fmt::format("{}: a second CIP/CONIC in the block", conic ? "CONIC" : "CIP"));
      w.keyword = conic ? Keyword::conic : Keyword::cip;
      w.keyword_column = col;
      pos += conic ? 5 : 3;
      first = false;
      continue;
    }
    if (c == 'O')
      fail_at(line, start, ctx, "o-word",
              fmt::format("'{}': an O-word must be the first word of its line", excerpt(line, start)));
    if (c == 'N') {
      if (!first) fail_at(line, start, ctx, "n-word", fmt::format("'{}': N number not at the start of the block", excerpt(line, start)));
      ++pos;
      long n = 0;
      std::size_t digits = 0;
      while (pos < t.size() && is_digit(t[pos])) {
        if (digits < 12) n = n * 10 + (t[pos] - '0');
        ++digits;
        ++pos;
      }
      if (pos < t.size() && t[pos] == '.') {  // LinuxCNC accepts N1.5-style decimals; keep the integer part
        ++pos;
        while (pos < t.size() && is_digit(t[pos])) ++pos;
      }
      if (digits == 0 || digits > 12) fail_at(line, start, ctx, "bad-number", fmt::format("'{}': N needs 1 to 12 digits", excerpt(line, start)));
      w.n_number = n;
      w.first_column = 0;  // the block's column is that of its first word after N
      first = true;
      continue;
    }
    first = false;
    if ((c == 'I' || c == 'J' || c == 'K') && pos + 2 < t.size() && is_digit(t[pos + 1]) && t[pos + 2] == '=') {
      const int point = t[pos + 1] - '1';
      const int axis = c - 'I';
      if (point < 0 || point > 2)
        fail_at(line, start, ctx, "unknown-word", fmt::format("{}{}=: only I1= .. K3= exist (CIP, CONIC)", c, t[pos + 1]));
      if (w.has_indexed(point, axis))
        fail_at(line, start, ctx, "word-twice", fmt::format("{}{}=: word given twice", c, point + 1));
      pos += 3;
      const double v = parse_real_value(line, pos, ctx, parameters);
      w.indexed[static_cast<std::size_t>(point)][static_cast<std::size_t>(axis)] = v;
      w.indexed_column[static_cast<std::size_t>(point)][static_cast<std::size_t>(axis)] = col;
      w.indexed_present = static_cast<std::uint16_t>(w.indexed_present | (1u << (3 * point + axis)));
      continue;
    }
    if (c == 'E')
      fail_at(line, start, ctx, "unknown-word", fmt::format("'{}': unknown word letter E", excerpt(line, start)));
    ++pos;
    const double v = parse_real_value(line, pos, ctx, parameters);
    const std::string_view word = std::string_view(t).substr(start, pos - start);
    if (c == 'G' || c == 'M') {
      const double scaled = c == 'G' ? v * 10.0 : v;
      const double r = std::round(scaled);
      if (std::abs(scaled - r) > integer_tolerance * 10.0 || r < 0.0 || r > 100000.0)
        fail_at(line, start, ctx, c == 'G' ? "unknown-g-code" : "unknown-m-code",
                fmt::format("{}: unknown {} code {}{}", word, c, c, v));
      if (c == 'G') {
        if (w.g_count == static_cast<int>(w.g.size())) fail_at(line, start, ctx, "too-many-words", fmt::format("{}: more than 16 G codes in a block", word));
        w.g[static_cast<std::size_t>(w.g_count)] = static_cast<int>(r);
        w.g_leading_zero[static_cast<std::size_t>(w.g_count)] = word.size() > 2 && word[1] == '0' && is_digit(word[2]);
        w.g_column[static_cast<std::size_t>(w.g_count++)] = col;
      } else {
        if (w.m_count == static_cast<int>(w.m.size())) fail_at(line, start, ctx, "too-many-words", fmt::format("{}: more than 8 M codes in a block", word));
        w.m[static_cast<std::size_t>(w.m_count)] = static_cast<int>(r);
        w.m_column[static_cast<std::size_t>(w.m_count++)] = col;
      }
      continue;
    }
    const std::size_t bit = static_cast<std::size_t>(c - 'A');
    if (w.has(c))
      fail_at(line, start, ctx, "word-twice",
              fmt::format("{}: word given twice in the block (first at column {})", word, w.column[bit]));
    w.present |= 1u << bit;
    w.value[bit] = v;
    w.column[bit] = col;
  }
}

}  // namespace kontur::gcode::detail
