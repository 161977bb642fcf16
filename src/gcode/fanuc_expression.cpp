// Custom Macro B values (Fanuc, Haas, Mitsubishi, Mach3): numbers, #variables (vacant ones
// included), [expressions] with Fanuc's operators and precedence, and its functions (degrees).
#include <fmt/format.h>

#include <cmath>
#include <numbers>

#include "fanuc_front_end.hpp"

namespace kontur::gcode::detail {
namespace {

constexpr int max_depth = 64;
constexpr double deg = std::numbers::pi / 180.0;

class MacroReader {
 public:
  MacroReader(const NormalizedLine& line, std::size_t& pos, const LineContext& ctx,
              const std::function<MacroValue(double, std::size_t)>& variable)
      : line_(line), t_(line.text), pos_(pos), ctx_(ctx), variable_(variable) {}

  // A word's value: a signed number, #variable, [expression] or function.
  MacroValue word_value() { return unary(0); }
  // A whole expression (comparisons lowest).
  MacroValue expression(int depth) { return comparison(depth + 1); }

  double index(int depth) {
    const std::size_t start = pos_;
    if (depth > max_depth) fail(pos_, "expression-depth", "expression nested more than 64 levels deep");
    if (pos_ >= t_.size()) fail(start, "parameter-range", "'#' without a variable number");
    MacroValue v;
    if (is_digit(t_[pos_])) {
      double n = 0.0;
      while (pos_ < t_.size() && is_digit(t_[pos_])) n = n * 10.0 + (t_[pos_++] - '0');
      return n;
    }
    if (t_[pos_] == '[')
      v = bracketed(depth + 1);
    else if (t_[pos_] == '#')
      v = variable(depth + 1);
    else
      fail(start, "parameter-range",
           fmt::format("'#{}': a variable number, #variable or [expression] is expected", excerpt(line_, start)));
    if (v.vacant)
      fail(start, "parameter-range", fmt::format("'#{}': the variable number is vacant", excerpt(line_, start)));
    return v.v;
  }

 private:
  [[noreturn]] void fail(std::size_t at, const char* rule, const std::string& message) const {
    fail_at(line_, at, ctx_, rule, message);
  }
  bool starts(std::string_view s) const noexcept { return t_.compare(pos_, s.size(), s) == 0; }

  MacroValue comparison(int depth) {
    const MacroValue a = additive(depth + 1);
    struct Name {
      std::string_view text;
      int op;
    };
    static constexpr Name names[] = {{"EQ", 0}, {"NE", 1}, {"GT", 2}, {"GE", 3}, {"LT", 4}, {"LE", 5}};
    for (const auto& n : names) {
      if (!starts(n.text)) continue;
      pos_ += 2;
      const MacroValue b = additive(depth + 1);
      bool r = false;
      // EQ / NE tell vacant from 0; the order comparisons read vacant as 0 (Fanuc)
      const bool same = a.vacant == b.vacant && (a.vacant || a.v == b.v);
      switch (n.op) {
        case 0:
          r = same;
          break;
        case 1:
          r = !same;
          break;
        case 2:
          r = a.v > b.v;
          break;
        case 3:
          r = a.v >= b.v;
          break;
        case 4:
          r = a.v < b.v;
          break;
        default:
          r = a.v <= b.v;
          break;
      }
      return MacroValue{r ? 1.0 : 0.0, false};
    }
    return a;
  }

  static long long bits(double v) { return std::llround(v); }

  MacroValue additive(int depth) {
    MacroValue a = multiplicative(depth + 1);
    for (;;) {
      const std::size_t at = pos_;
      if (starts("+") || starts("-")) {
        const bool plus = t_[pos_] == '+';
        ++pos_;
        const MacroValue b = multiplicative(depth + 1);
        a = finite(plus ? a.v + b.v : a.v - b.v, at);
      } else if (starts("OR") || starts("XOR")) {
        const bool x = t_[pos_] == 'X';
        pos_ += x ? 3 : 2;
        const MacroValue b = multiplicative(depth + 1);
        a = MacroValue{static_cast<double>(x ? (bits(a.v) ^ bits(b.v)) : (bits(a.v) | bits(b.v))), false};
      } else {
        return a;
      }
    }
  }

  MacroValue multiplicative(int depth) {
    MacroValue a = unary(depth + 1);
    for (;;) {
      const std::size_t at = pos_;
      if (starts("*")) {
        ++pos_;
        const MacroValue b = unary(depth + 1);
        a = finite(a.v * b.v, at);
      } else if (starts("/")) {
        ++pos_;
        const MacroValue b = unary(depth + 1);
        if (b.v == 0.0) fail(at, "division-by-zero", fmt::format("'{}': division by zero", excerpt(line_, at)));
        a = finite(a.v / b.v, at);
      } else if (starts("MOD")) {
        pos_ += 3;
        const MacroValue b = unary(depth + 1);
        if (b.v == 0.0) fail(at, "division-by-zero", fmt::format("'{}': MOD by zero", excerpt(line_, at)));
        a = finite(std::fmod(a.v, b.v), at);
      } else if (starts("AND")) {
        pos_ += 3;
        const MacroValue b = unary(depth + 1);
        a = MacroValue{static_cast<double>(bits(a.v) & bits(b.v)), false};
      } else {
        return a;
      }
    }
  }

  MacroValue finite(double r, std::size_t at) const {
    if (!std::isfinite(r))
      fail(at, "not-finite", fmt::format("'{}': the result is not a finite number", excerpt(line_, at)));
    return MacroValue{r, false};
  }

  MacroValue unary(int depth) {
    if (depth > max_depth) fail(pos_, "expression-depth", "expression nested more than 64 levels deep");
    if (pos_ >= t_.size()) fail(pos_, "value-missing", "a value is missing at the end of the line");
    const char c = t_[pos_];
    if (c == '-' || c == '+') {
      const std::size_t start = pos_;
      ++pos_;
      if (pos_ >= t_.size()) fail(start, "value-missing", fmt::format("'{}' without a value", c));
      MacroValue v = unary(depth + 1);
      if (c == '-') v.v = -v.v;  // a signed vacant variable stays vacant
      return v;
    }
    if (c == '[') return bracketed(depth + 1);
    if (c == '#') return variable(depth + 1);
    if (is_digit(c) || c == '.') return MacroValue{parse_number(line_, pos_, ctx_), false};
    if (is_letter(c)) return function(depth + 1);
    fail(pos_, "value-missing",
         fmt::format("'{}': a number, #variable or [expression] is expected", excerpt(line_, pos_)));
  }

  MacroValue bracketed(int depth) {
    const std::size_t open = pos_;
    ++pos_;
    const MacroValue v = comparison(depth + 1);
    if (pos_ >= t_.size() || t_[pos_] != ']')
      fail(open, "bracket", fmt::format("'{}': ']' missing", excerpt(line_, open)));
    ++pos_;
    return v;
  }

  MacroValue variable(int depth) {
    const std::size_t start = pos_;
    ++pos_;  // '#'
    const double i = index(depth + 1);
    return variable_(i, start);
  }

  // The second argument of ATAN[a]/[b], ATAN[a,b] or POW[a,b].
  bool second_argument(int depth, double& b) {
    if (pos_ + 1 < t_.size() && t_[pos_] == '/' && t_[pos_ + 1] == '[') {
      ++pos_;
      b = bracketed(depth + 1).v;
      return true;
    }
    return false;
  }

  MacroValue function(int depth) {
    const std::size_t start = pos_;
    std::size_t p = pos_;
    while (p < t_.size() && is_letter(t_[p])) ++p;
    const std::string_view name = t_.substr(start, p - start);
    if (p >= t_.size() || t_[p] != '[')
      fail(start, "value-missing",
           fmt::format("'{}': a number, #variable or [expression] is expected", excerpt(line_, start)));
    pos_ = p + 1;
    const double a = comparison(depth + 1).v;
    double b = 0.0;
    bool two = false;
    if (pos_ < t_.size() && t_[pos_] == ',') {
      ++pos_;
      b = comparison(depth + 1).v;
      two = true;
    }
    if (pos_ >= t_.size() || t_[pos_] != ']')
      fail(start, "bracket", fmt::format("'{}': ']' missing", excerpt(line_, start)));
    ++pos_;
    if (name == "ATAN" && !two) two = second_argument(depth, b);
    auto domain = [&](bool ok) {
      if (!ok) fail(start, "function-domain", fmt::format("{}[{}]: argument outside the function's domain", name, a));
    };
    double r = 0.0;
    if (name == "ATAN") {
      // Fanuc: 0 to 360 degrees for two arguments
      if (two) {
        r = std::atan2(a, b) / deg;
        if (r < 0.0) r += 360.0;
      } else {
        r = std::atan(a) / deg;
      }
    } else if (two && name == "POW") {
      domain(!(a < 0.0 && b != std::floor(b)));
      r = std::pow(a, b);
    } else if (two) {
      fail(start, "syntax", fmt::format("{}[: takes one argument", name));
    } else if (name == "FIX") {
      r = std::trunc(a);  // Fanuc: the fraction discarded
    } else if (name == "FUP") {
      r = a < 0.0 ? -std::ceil(-a) : std::ceil(a);  // Fanuc: the fraction raised to a unit (away from 0)
    } else if (name == "ADP") {
      r = a;  // Kontur reads whole units already: adding the decimal point changes nothing
    } else if (name == "BIN" || name == "BCD") {
      domain(a >= 0.0 && a == std::floor(a) && a < 1e15);
      auto n = static_cast<unsigned long long>(a);
      unsigned long long out = 0, scale = 1;
      if (name == "BIN") {  // BCD to binary
        for (; n > 0; n >>= 4, scale *= 10) {
          domain((n & 15u) < 10u);
          out += (n & 15u) * scale;
        }
      } else {  // binary to BCD
        for (int shift = 0; n > 0; n /= 10, shift += 4) out |= (n % 10) << shift;
      }
      r = static_cast<double>(out);
    } else {
      bool known = true, ok = true;
      r = unary_function(name, a, known, ok);
      if (!known)
        fail(start, "unknown-function",
             fmt::format(
                 "{}[: unknown function (SIN COS TAN ASIN ACOS ATAN SQRT ABS ROUND FIX FUP LN EXP POW ADP BIN BCD)",
                 name));
      domain(ok);
    }
    if (!std::isfinite(r)) fail(start, "not-finite", fmt::format("{}[{}]: the result is not a finite number", name, a));
    return MacroValue{r, false};
  }

  const NormalizedLine& line_;
  std::string_view t_;
  std::size_t& pos_;
  const LineContext& ctx_;
  const std::function<MacroValue(double, std::size_t)>& variable_;
};

}  // namespace

MacroValue parse_macro_value(const NormalizedLine& line, std::size_t& pos, const LineContext& ctx,
                             const std::function<MacroValue(double index, std::size_t at)>& variable, bool word_value) {
  MacroReader r(line, pos, ctx, variable);
  return word_value ? r.word_value() : r.expression(0);
}

double parse_macro_index(const NormalizedLine& line, std::size_t& pos, const LineContext& ctx,
                         const std::function<MacroValue(double index, std::size_t at)>& variable) {
  MacroReader r(line, pos, ctx, variable);
  return r.index(0);
}

}  // namespace kontur::gcode::detail
