#pragma once
// Parameters and expressions as LinuxCNC (and Fanuc macro B) write them: numbered parameters
// #1 .. #5602, named parameters #<name> and #<_global> (case and spaces do not matter), bracketed
// expressions with + - * / MOD **, EQ NE GT GE LT LE, AND OR XOR, and the functions
// SIN COS TAN ASIN ACOS ATAN[y]/[x] SQRT ABS ROUND FIX FUP EXP LN EXISTS (angles in degrees).
#include <map>
#include <string>
#include <string_view>
#include <vector>

namespace kontur::gcode {

/// The parameters of a running program.
class ParameterTable {
public:
  /// Highest numbered parameter (LinuxCNC's 5602).
  static constexpr int max_numbered = 5602;

  ParameterTable();
  /// Value of #index (1..max_numbered); a numbered parameter never set is 0, as in LinuxCNC.
  [[nodiscard]] double numbered(int index) const noexcept { return numbered_[static_cast<std::size_t>(index)]; }
  /// Sets #index (1..max_numbered).
  void set_numbered(int index, double value) noexcept { numbered_[static_cast<std::size_t>(index)] = value; }
  /// Value of #<name> (name upper-case, without spaces), or nullptr if it was never set.
  [[nodiscard]] const double* named(std::string_view name) const noexcept;
  /// Sets #<name> (name upper-case, without spaces).
  void set_named(std::string_view name, double value);
  /// Number of named parameters set so far.
  [[nodiscard]] std::size_t named_count() const noexcept { return named_.size(); }

private:
  std::vector<double> numbered_;
  std::map<std::string, double, std::less<>> named_;
};

/// Evaluates one real value as it may follow a word letter: a number, #parameter, [expression],
/// a function or a signed one of those ("[#<xscale> * 53.]", "-#1", "SQRT[2]"). Spaces and case
/// do not matter. Throws InputError "column C: TEXT: rule" (division by zero, undefined parameter,
/// bad number, ...). The whole text must be consumed.
[[nodiscard]] double evaluate_expression(std::string_view text, const ParameterTable& parameters);

}  // namespace kontur::gcode
