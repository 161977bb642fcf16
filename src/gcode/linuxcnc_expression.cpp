// The LinuxCNC dialect's real values: numbers, #parameters, [expressions] with LinuxCNC's
// operators and precedence, and its functions (angles in degrees).
#include "linuxcnc_lexer.hpp"

#include <kontur/error.hpp>

#include <fmt/format.h>

#include <charconv>
#include <cmath>
#include <numbers>

namespace kontur::gcode::detail {
namespace {

constexpr int max_expression_depth = 64;

class ExpressionReader {
public:
  ExpressionReader(const NormalizedLine& line, std::size_t& pos, const LineContext& ctx, const ParameterTable& params)
      : line_(line), t_(line.text), pos_(pos), ctx_(ctx), params_(params) {}

  double real_value(int depth) {
    if (depth > max_expression_depth) fail(pos_, "expression-depth", "expression nested more than 64 levels deep");
    if (pos_ >= t_.size()) fail(pos_, "value-missing", "a value is missing at the end of the line");
    const char c = t_[pos_];
    if (c == '[') return bracketed(depth + 1);
    if (c == '#') return parameter_value(depth + 1);
    if (c == '-' || c == '+') {
      const std::size_t start = pos_;
      ++pos_;
      if (pos_ >= t_.size()) fail(start, "value-missing", fmt::format("'{}' without a value", c));
      const double v = real_value(depth + 1);
      return c == '-' ? -v : v;
    }
    if (is_digit(c) || c == '.') return number();
    if (is_letter(c)) return function(depth + 1);
    fail(pos_, "value-missing", fmt::format("'{}': a number, #parameter or [expression] is expected", excerpt(line_, pos_)));
  }

private:
  [[noreturn]] void fail(std::size_t at, const char* rule, const std::string& message) const {
    fail_at(line_, at, ctx_, rule, message);
  }

  double number() { return parse_number(line_, pos_, ctx_); }

  double bracketed(int depth) {
    const std::size_t open = pos_;
    ++pos_;  // '['
    const double v = expression(depth);
    if (pos_ >= t_.size() || t_[pos_] != ']')
      fail(open, "bracket", fmt::format("'{}': ']' missing", excerpt(line_, open)));
    ++pos_;
    return v;
  }

  // Binary operators and their precedence (LinuxCNC: ** 6, * / MOD 5, + - 4, comparisons 3, logic 2).
  enum class Op { none, power, times, divide, mod, plus, minus, eq, ne, gt, ge, lt, le, and_, or_, xor_ };
  static int precedence(Op op) noexcept {
    switch (op) {
      case Op::power: return 6;
      case Op::times: case Op::divide: case Op::mod: return 5;
      case Op::plus: case Op::minus: return 4;
      case Op::eq: case Op::ne: case Op::gt: case Op::ge: case Op::lt: case Op::le: return 3;
      case Op::and_: case Op::or_: case Op::xor_: return 2;
      case Op::none: return 0;
    }
    return 0;
  }
  bool starts(std::string_view s) const noexcept { return t_.compare(pos_, s.size(), s) == 0; }
  Op peek_op(std::size_t& len) const noexcept {
    if (pos_ >= t_.size()) return Op::none;
    struct Name { std::string_view text; Op op; };
    static constexpr Name names[] = {{"**", Op::power}, {"*", Op::times}, {"/", Op::divide}, {"MOD", Op::mod},
                                     {"+", Op::plus},   {"-", Op::minus}, {"EQ", Op::eq},     {"NE", Op::ne},
                                     {"GT", Op::gt},    {"GE", Op::ge},   {"LT", Op::lt},     {"LE", Op::le},
                                     {"AND", Op::and_}, {"OR", Op::or_},  {"XOR", Op::xor_}};
    for (const auto& n : names)
      if (starts(n.text)) {
        len = n.text.size();
        return n.op;
      }
    return Op::none;
  }

  double apply(Op op, double a, double b, std::size_t at) const {
    double r = 0.0;
    switch (op) {
      case Op::power:
        if (a < 0.0 && b != std::floor(b))
          fail(at, "function-domain", fmt::format("{} ** {}: a negative number to a non-integer power", a, b));
        r = std::pow(a, b);
        break;
      case Op::times: r = a * b; break;
      case Op::divide:
        if (b == 0.0) fail(at, "division-by-zero", fmt::format("'{}': division by zero", excerpt(line_, at)));
        r = a / b;
        break;
      case Op::mod:
        if (b == 0.0) fail(at, "division-by-zero", fmt::format("'{}': MOD by zero", excerpt(line_, at)));
        r = std::fmod(a, b);
        if (r < 0.0) r += std::abs(b);
        break;
      case Op::plus: r = a + b; break;
      case Op::minus: r = a - b; break;
      case Op::eq: r = a == b ? 1.0 : 0.0; break;
      case Op::ne: r = a != b ? 1.0 : 0.0; break;
      case Op::gt: r = a > b ? 1.0 : 0.0; break;
      case Op::ge: r = a >= b ? 1.0 : 0.0; break;
      case Op::lt: r = a < b ? 1.0 : 0.0; break;
      case Op::le: r = a <= b ? 1.0 : 0.0; break;
      case Op::and_: r = (a != 0.0 && b != 0.0) ? 1.0 : 0.0; break;
      case Op::or_: r = (a != 0.0 || b != 0.0) ? 1.0 : 0.0; break;
      case Op::xor_: r = ((a != 0.0) != (b != 0.0)) ? 1.0 : 0.0; break;
      case Op::none: break;
    }
    if (!std::isfinite(r)) fail(at, "not-finite", fmt::format("'{}': the result is not a finite number", excerpt(line_, at)));
    return r;
  }

  // Precedence climbing, left-associative at every level.
  double expression(int depth) { return binary(depth, 1); }
  double binary(int depth, int min_precedence) {
    if (depth > max_expression_depth) fail(pos_, "expression-depth", "expression nested more than 64 levels deep");
    double lhs = real_value(depth + 1);
    for (;;) {
      std::size_t len = 0;
      const std::size_t at = pos_;
      const Op op = peek_op(len);
      const int prec = precedence(op);
      if (op == Op::none || prec < min_precedence) break;
      pos_ += len;
      const double rhs = binary(depth + 1, prec + 1);
      lhs = apply(op, lhs, rhs, at);
    }
    return lhs;
  }

  double parameter_value(int depth) {
    const std::size_t start = pos_;
    ++pos_;  // '#'
    if (pos_ < t_.size() && t_[pos_] == '<') {
      const std::string_view name = parameter_name();
      const double* v = params_.named(name);
      if (!v) fail(start, "undefined-parameter", fmt::format("#<{}>: undefined parameter", name));
      return *v;
    }
    const int index = parameter_index(start, depth);
    return params_.numbered(index);
  }

public:
  // After '#': the name in <...>, upper case, spaces already removed.
  std::string_view parameter_name() {
    const std::size_t open = pos_;
    const std::size_t close = t_.find('>', open);
    if (close == std::string_view::npos) fail(open, "parameter-name", fmt::format("'#{}': '>' missing", excerpt(line_, open)));
    const std::string_view name = t_.substr(open + 1, close - open - 1);
    if (name.empty()) fail(open, "parameter-name", "#<>: empty parameter name");
    pos_ = close + 1;
    return name;
  }
  // After '#': the number of a numbered parameter (a real value that is an integer in range).
  int parameter_index(std::size_t start, int depth) {
    if (pos_ >= t_.size()) fail(start, "parameter-range", "'#' without a parameter number");
    const double v = real_value(depth + 1);
    const double r = std::round(v);
    if (std::abs(v - r) > integer_tolerance || r < 1.0 || r > ParameterTable::max_numbered)
      fail(start, "parameter-range",
           fmt::format("#{}: parameter number must be an integer 1..{}", v, ParameterTable::max_numbered));
    return static_cast<int>(r);
  }

private:
  double function(int depth) {
    const std::size_t start = pos_;
    std::size_t p = pos_;
    while (p < t_.size() && is_letter(t_[p])) ++p;
    const std::string_view name = t_.substr(start, p - start);
    if (p >= t_.size() || t_[p] != '[')
      fail(start, "value-missing", fmt::format("'{}': a number, #parameter or [expression] is expected", excerpt(line_, start)));
    pos_ = p;
    constexpr double deg = std::numbers::pi / 180.0;
    if (name == "EXISTS") {
      ++pos_;
      if (pos_ >= t_.size() || t_[pos_] != '#' || pos_ + 1 >= t_.size() || t_[pos_ + 1] != '<')
        fail(pos_, "syntax", "EXISTS[#<name>]: a named parameter is expected");
      ++pos_;
      const bool exists = params_.named(parameter_name()) != nullptr;
      if (pos_ >= t_.size() || t_[pos_] != ']') fail(start, "bracket", "EXISTS[: ']' missing");
      ++pos_;
      return exists ? 1.0 : 0.0;
    }
    const double a = bracketed(depth + 1);
    auto domain = [&](bool ok) {
      if (!ok) fail(start, "function-domain", fmt::format("{}[{}]: argument outside the function's domain", name, a));
    };
    double r = 0.0;
    if (name == "ATAN") {
      if (pos_ >= t_.size() || t_[pos_] != '/') fail(start, "syntax", "ATAN[y]/[x]: '/[x]' missing");
      ++pos_;
      if (pos_ >= t_.size() || t_[pos_] != '[') fail(start, "syntax", "ATAN[y]/[x]: '[x]' missing");
      const double b = bracketed(depth + 1);
      r = std::atan2(a, b) / deg;
    } else {
      bool known = true, ok = true;
      r = unary_function(name, a, known, ok);
      if (!known) fail(start, "unknown-function", fmt::format("{}[: unknown function", name));
      domain(ok);
    }
    if (!std::isfinite(r)) fail(start, "not-finite", fmt::format("{}[{}]: the result is not a finite number", name, a));
    return r;
  }

  const NormalizedLine& line_;
  std::string_view t_;
  std::size_t& pos_;
  const LineContext& ctx_;
  const ParameterTable& params_;
};


}  // namespace

double parse_number(const NormalizedLine& line, std::size_t& pos, const LineContext& ctx) {
  const std::string_view t = line.text;
  const std::size_t start = pos;
  std::size_t p = pos;
  int dots = 0, digits = 0;
  while (p < t.size() && (is_digit(t[p]) || t[p] == '.')) {
    if (t[p] == '.') ++dots; else ++digits;
    ++p;
  }
  if (dots > 1 || digits == 0)
    fail_at(line, start, ctx, "bad-number", fmt::format("'{}': not a number", t.substr(start, p - start)));
  double v = 0.0;
  const char* first = t.data() + start;
  // from_chars does not accept a leading '.'; it does accept "5." and ".5" with chars_format::fixed
  const auto r = std::from_chars(first, t.data() + p, v, std::chars_format::fixed);
  if (r.ec != std::errc() || r.ptr != t.data() + p || !std::isfinite(v))
    fail_at(line, start, ctx, "bad-number", fmt::format("'{}': not a number", t.substr(start, p - start)));
  pos = p;
  return v;
}

double unary_function(std::string_view name, double a, bool& known, bool& domain) noexcept {
  constexpr double deg = std::numbers::pi / 180.0;
  known = true;
  domain = true;
  if (name == "SIN") return std::sin(a * deg);
  if (name == "COS") return std::cos(a * deg);
  if (name == "TAN") return std::tan(a * deg);
  if (name == "ASIN") { domain = a >= -1.0 && a <= 1.0; return domain ? std::asin(a) / deg : 0.0; }
  if (name == "ACOS") { domain = a >= -1.0 && a <= 1.0; return domain ? std::acos(a) / deg : 0.0; }
  if (name == "SQRT") { domain = a >= 0.0; return domain ? std::sqrt(a) : 0.0; }
  if (name == "ABS") return std::abs(a);
  if (name == "ROUND") return std::round(a);
  if (name == "FIX") return std::floor(a);
  if (name == "FUP") return std::ceil(a);
  if (name == "EXP") return std::exp(a);
  if (name == "LN") { domain = a > 0.0; return domain ? std::log(a) : 0.0; }
  known = false;
  return 0.0;
}

double parse_real_value(const NormalizedLine& line, std::size_t& pos, const LineContext& ctx,
                        const ParameterTable& parameters) {
  ExpressionReader r(line, pos, ctx, parameters);
  return r.real_value(0);
}

std::string_view parse_parameter_name(const NormalizedLine& line, std::size_t& pos, const LineContext& ctx,
                                      const ParameterTable& parameters) {
  ExpressionReader r(line, pos, ctx, parameters);
  return r.parameter_name();
}

int parse_parameter_index(const NormalizedLine& line, std::size_t& pos, std::size_t start, const LineContext& ctx,
                          const ParameterTable& parameters) {
  ExpressionReader r(line, pos, ctx, parameters);
  return r.parameter_index(start, 1);
}

}  // namespace kontur::gcode::detail
