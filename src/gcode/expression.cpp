#include <kontur/error.hpp>
#include <kontur/gcode/expression.hpp>

#include "linuxcnc_lexer.hpp"

#include <fmt/format.h>

namespace kontur::gcode {

ParameterTable::ParameterTable() : numbered_(static_cast<std::size_t>(max_numbered) + 1, 0.0) {}

const double* ParameterTable::named(std::string_view name) const noexcept {
  const auto it = named_.find(name);
  return it == named_.end() ? nullptr : &it->second;
}

void ParameterTable::set_named(std::string_view name, double value) {
  const auto it = named_.find(name);
  if (it != named_.end()) it->second = value;
  else named_.emplace(std::string(name), value);
}

double evaluate_expression(std::string_view text, const ParameterTable& parameters) {
  const detail::LineContext ctx{"expression", 1};
  detail::NormalizedLine line;
  detail::normalize_line(text, ctx, line);
  std::size_t pos = 0;
  if (line.text.empty()) throw InputError("value-missing", "expression:1:1: empty expression");
  const double v = detail::parse_real_value(line, pos, ctx, parameters);
  if (pos != line.text.size())
    detail::fail_at(line, pos, ctx, "syntax", fmt::format("'{}': unexpected text after the value", line.text.substr(pos)));
  return v;
}

}  // namespace kontur::gcode
