#pragma once
// The one exception type of Kontur's input checks. Inputs are validated once, up front; the
// message names the field, the index or the value and the rule that was broken. Real-time code
// paths never throw.
#include <stdexcept>
#include <string>

namespace kontur {

/// Bad user input: a curve, a program, a machine file or a command-line value that breaks a rule.
class InputError : public std::runtime_error {
public:
  /// @param rule  short name of the broken rule (e.g. "knot-count"), stable for tools and tests
  /// @param message  the full human-readable message
  InputError(std::string rule, const std::string& message)
      : std::runtime_error(message), rule_(std::move(rule)) {}
  /// Short, stable name of the broken rule.
  [[nodiscard]] const std::string& rule() const noexcept { return rule_; }

private:
  std::string rule_;
};

}  // namespace kontur
