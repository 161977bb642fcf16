// Sinumerik expressions, with the control's priorities (highest first): NOT; * / DIV MOD; + -;
// B_AND; B_XOR; B_OR; AND; XOR; OR; <<; == <> > < >= <= (comparisons last, so that
// `IF (A==1) AND (B==2)` needs its parentheses, as on the control). Operands: numbers (`10EX-5`),
// R parameters (`R1`, `R[R2]`), DEF variables (`NAME`, `NAME[i]`), TRUE / FALSE, and the
// functions SIN COS TAN ASIN ACOS ATAN2 SQRT ABS POT TRUNC ROUND ROUNDUP MINVAL MAXVAL BOUND EXP
// LN (angles in degrees).
#include <algorithm>
#include <cmath>
#include <cstring>

#include "message_format.hpp"
#include "sinumerik_front_end.hpp"

namespace kontur::gcode::detail {
namespace {

constexpr double deg = 3.14159265358979323846 / 180.0;

bool is_ident_start(char c) noexcept { return (c >= 'A' && c <= 'Z') || c == '_'; }
bool is_ident_char(char c) noexcept { return is_ident_start(c) || (c >= '0' && c <= '9'); }

// Sinumerik compares REAL values for relative equality.
bool equal(double a, double b) noexcept {
  const double scale = std::max(std::abs(a), std::abs(b));
  return std::abs(a - b) <= 1e-12 * std::max(scale, 1.0);
}

}  // namespace

std::string_view SinumerikFrontEnd::identifier(Cursor& c) {
  c.ws();
  const std::size_t start = c.p;
  if (c.p >= c.t.size() || !is_ident_start(c.t[c.p])) return {};
  while (c.p < c.t.size() && is_ident_char(c.t[c.p])) ++c.p;
  return c.t.substr(start, c.p - start);
}

bool SinumerikFrontEnd::eat_keyword(Cursor& c, const char* word) {
  c.ws();
  const std::size_t n = std::strlen(word);
  if (c.t.compare(c.p, n, word) != 0) return false;
  if (c.p + n < c.t.size() && is_ident_char(c.t[c.p + n])) return false;
  c.p += n;
  return true;
}

std::string SinumerikFrontEnd::string_literal(Cursor& c) {
  const int col = c.col();
  if (!c.eat('"')) fail(col, "syntax", "'\"' expected (a string)");
  std::string s;
  while (c.p < c.t.size() && c.t[c.p] != '"') s.push_back(c.t[c.p++]);
  if (c.p >= c.t.size()) fail(col, "syntax", "'\"': string not closed on its line");
  ++c.p;
  return s;
}

double SinumerikFrontEnd::number_literal(Cursor& c) {
  c.ws();
  const std::size_t start = c.p;
  std::size_t q = c.p;
  while (q < c.t.size() && (std::isdigit(static_cast<unsigned char>(c.t[q])) || c.t[q] == '.')) ++q;
  if (q == start) fail(c.col(), "syntax", fmt::format("'{}': a number expected", c.t.substr(start, 16)));
  std::string s(c.t.substr(start, q - start));
  if (std::count(s.begin(), s.end(), '.') > 1 || s == ".")
    fail(c.col(), "bad-number", fmt::format("'{}': not a number", s));
  if (c.t.compare(q, 2, "EX") == 0) {  // 10EX-5
    std::size_t e = q + 2;
    std::string ex;
    if (e < c.t.size() && (c.t[e] == '-' || c.t[e] == '+')) ex.push_back(c.t[e++]);
    const std::size_t digits = e;
    while (e < c.t.size() && std::isdigit(static_cast<unsigned char>(c.t[e]))) ex.push_back(c.t[e++]);
    if (e > digits) {
      s += "e" + ex;
      q = e;
    }
  }
  c.p = q;
  return std::strtod(s.c_str(), nullptr);
}

double SinumerikFrontEnd::expr(Cursor& c) { return compare(c); }

double SinumerikFrontEnd::compare(Cursor& c) {
  double v = concat(c);
  for (;;) {
    c.ws();
    const auto rest = c.t.substr(c.p);
    if (rest.starts_with("==")) {
      c.p += 2;
      v = equal(v, concat(c)) ? 1.0 : 0.0;
    } else if (rest.starts_with("<>")) {
      c.p += 2;
      v = equal(v, concat(c)) ? 0.0 : 1.0;
    } else if (rest.starts_with("<=")) {
      c.p += 2;
      const double b = concat(c);
      v = (v < b || equal(v, b)) ? 1.0 : 0.0;
    } else if (rest.starts_with(">=")) {
      c.p += 2;
      const double b = concat(c);
      v = (v > b || equal(v, b)) ? 1.0 : 0.0;
    } else if (rest.starts_with("<") && !rest.starts_with("<<")) {
      ++c.p;
      const double b = concat(c);
      v = (v < b && !equal(v, b)) ? 1.0 : 0.0;
    } else if (rest.starts_with(">")) {
      ++c.p;
      const double b = concat(c);
      v = (v > b && !equal(v, b)) ? 1.0 : 0.0;
    } else
      return v;
  }
}

double SinumerikFrontEnd::concat(Cursor& c) {
  const double v = logic_or(c);
  c.ws();
  if (c.t.substr(c.p).starts_with("<<"))
    fail(c.col(), "unsupported", "<<: string expressions are only read in MSG (dialect sinumerik)");
  return v;
}

double SinumerikFrontEnd::logic_or(Cursor& c) {
  double v = logic_xor(c);
  while (eat_keyword(c, "OR")) {
    const double b = logic_xor(c);
    v = (v != 0.0 || b != 0.0) ? 1.0 : 0.0;
  }
  return v;
}

double SinumerikFrontEnd::logic_xor(Cursor& c) {
  double v = logic_and(c);
  while (eat_keyword(c, "XOR")) {
    const double b = logic_and(c);
    v = ((v != 0.0) != (b != 0.0)) ? 1.0 : 0.0;
  }
  return v;
}

double SinumerikFrontEnd::logic_and(Cursor& c) {
  double v = bit_or(c);
  while (eat_keyword(c, "AND")) {
    const double b = bit_or(c);
    v = (v != 0.0 && b != 0.0) ? 1.0 : 0.0;
  }
  return v;
}

double SinumerikFrontEnd::bit_or(Cursor& c) {
  double v = bit_xor(c);
  while (eat_keyword(c, "B_OR"))
    v = static_cast<double>(static_cast<long long>(v) | static_cast<long long>(bit_xor(c)));
  return v;
}

double SinumerikFrontEnd::bit_xor(Cursor& c) {
  double v = bit_and(c);
  while (eat_keyword(c, "B_XOR"))
    v = static_cast<double>(static_cast<long long>(v) ^ static_cast<long long>(bit_and(c)));
  return v;
}

double SinumerikFrontEnd::bit_and(Cursor& c) {
  double v = additive(c);
  while (eat_keyword(c, "B_AND"))
    v = static_cast<double>(static_cast<long long>(v) & static_cast<long long>(additive(c)));
  return v;
}

double SinumerikFrontEnd::additive(Cursor& c) {
  double v = term(c);
  for (;;) {
    if (c.eat('+'))
      v += term(c);
    else if (c.eat('-'))
      v -= term(c);
    else
      return v;
  }
}

double SinumerikFrontEnd::term(Cursor& c) {
  double v = unary(c);
  for (;;) {
    const int col = c.col();
    if (c.eat('*')) {
      v *= unary(c);
    } else if (c.eat('/')) {
      const double b = unary(c);
      if (b == 0.0) fail(col, "division-by-zero", "/: division by zero");
      v /= b;
    } else if (eat_keyword(c, "DIV")) {
      const double b = unary(c);
      if (b == 0.0) fail(col, "division-by-zero", "DIV: division by zero");
      v = std::trunc(v / b);
    } else if (eat_keyword(c, "MOD")) {
      const double b = unary(c);
      if (b == 0.0) fail(col, "division-by-zero", "MOD: division by zero");
      v = std::fmod(v, b);
    } else {
      return v;
    }
  }
}

double SinumerikFrontEnd::unary(Cursor& c) {
  if (eat_keyword(c, "NOT")) return unary(c) == 0.0 ? 1.0 : 0.0;
  if (eat_keyword(c, "B_NOT")) return static_cast<double>(~static_cast<long long>(unary(c)));
  if (c.eat('-')) return -unary(c);
  if (c.eat('+')) return unary(c);
  return primary(c);
}

double SinumerikFrontEnd::primary(Cursor& c) {
  const char ch = c.peek();
  const int col = c.col();
  if (ch == '(') {
    ++c.p;
    const double v = expr(c);
    if (!c.eat(')'))
      fail(c.col(), "syntax",
           fmt::format("')' expected, found '{}'",
                       c.end() ? std::string("end of line") : std::string(c.t.substr(c.p, 12))));
    return v;
  }
  if (std::isdigit(static_cast<unsigned char>(ch)) || ch == '.') return number_literal(c);
  if (ch == '$')
    fail(col, "unsupported",
         fmt::format("'{}': system variables are not known to Kontur (dialect sinumerik)",
                     c.t.substr(c.p, std::min<std::size_t>(c.t.size() - c.p, 20))));
  if (ch == '"') fail(col, "syntax", "a string where a number is expected");
  const std::string_view name = identifier(c);
  if (name.empty())
    fail(
        col, "syntax",
        fmt::format("'{}': a value expected", c.end() ? std::string("end of line") : std::string(c.t.substr(c.p, 12))));
  if (name == "TRUE") return 1.0;
  if (name == "FALSE") return 0.0;
  if (c.peek() == '(') return function(c, name, col);
  if (name == "R" && c.peek() == '[') return r_[r_index(c, col)];
  if (name.size() > 1 && name[0] == 'R' &&
      std::all_of(name.begin() + 1, name.end(), [](char d) { return d >= '0' && d <= '9'; })) {
    const long r = std::strtol(std::string(name.substr(1)).c_str(), nullptr, 10);
    if (r >= r_count || name.size() > 5)
      fail(col, "parameter-range", fmt::format("{}: R parameters are R0 .. R{}", name, r_count - 1));
    if (!find_var(name)) return r_[static_cast<std::size_t>(r)];
  }
  Variable* v = find_var(name);
  if (!v) fail(col, "undefined-variable", fmt::format("{}: variable not defined (DEF it first)", name));
  if (v->is_array) {
    return array_element(c, *v, name, col);
  }
  if (v->type == VarType::string || v->type == VarType::axis)
    fail(col, "unsupported", fmt::format("{}: a STRING or AXIS variable in an arithmetic expression", name));
  return v->value;
}

double SinumerikFrontEnd::function(Cursor& c, std::string_view name, int col) {
  ++c.p;  // '('
  std::vector<double> a;
  if (!c.eat(')')) {
    for (;;) {
      a.push_back(expr(c));
      if (c.eat(')')) break;
      if (!c.eat(',')) fail(c.col(), "syntax", fmt::format("{}(: ',' or ')' expected", name));
    }
  }
  auto need = [&](std::size_t n) {
    if (a.size() != n)
      fail(col, "syntax", fmt::format("{}: {} argument{} expected, {} given", name, n, n == 1 ? "" : "s", a.size()));
  };
  auto domain = [&](bool ok) {
    if (!ok) fail(col, "math-domain", fmt::format("{}({}): argument out of range", name, a.empty() ? "" : num(a[0])));
  };
  if (name == "SIN") {
    need(1);
    return std::sin(a[0] * deg);
  }
  if (name == "COS") {
    need(1);
    return std::cos(a[0] * deg);
  }
  if (name == "TAN") {
    need(1);
    return std::tan(a[0] * deg);
  }
  if (name == "ASIN") {
    need(1);
    domain(std::abs(a[0]) <= 1.0);
    return std::asin(a[0]) / deg;
  }
  if (name == "ACOS") {
    need(1);
    domain(std::abs(a[0]) <= 1.0);
    return std::acos(a[0]) / deg;
  }
  if (name == "ATAN2") {
    need(2);
    return std::atan2(a[0], a[1]) / deg;
  }
  if (name == "SQRT") {
    need(1);
    domain(a[0] >= 0.0);
    return std::sqrt(a[0]);
  }
  if (name == "ABS") {
    need(1);
    return std::abs(a[0]);
  }
  if (name == "POT") {
    need(1);
    return a[0] * a[0];
  }
  if (name == "TRUNC") {
    need(1);
    return std::trunc(a[0]);
  }
  if (name == "ROUND") {
    need(1);
    return std::round(a[0]);
  }
  if (name == "ROUNDUP") {
    need(1);
    return a[0] >= 0.0 ? std::ceil(a[0]) : std::floor(a[0]);
  }
  if (name == "EXP") {
    need(1);
    return std::exp(a[0]);
  }
  if (name == "LN") {
    need(1);
    domain(a[0] > 0.0);
    return std::log(a[0]);
  }
  if (name == "MINVAL") {
    need(2);
    return std::min(a[0], a[1]);
  }
  if (name == "MAXVAL") {
    need(2);
    return std::max(a[0], a[1]);
  }
  if (name == "BOUND") {
    need(3);
    return std::clamp(a[2], a[0], a[1]);
  }
  fail(col, "unknown-function", fmt::format("{}(: unknown function (dialect sinumerik)", name));
}

}  // namespace kontur::gcode::detail
