#pragma once
// Internal: where the reader is in the program (file and line) and what it reports there. Errors
// throw InputError with the control-alarm message "file:line:column: message"; warnings are kept
// as "file:line:column: warning: message". Shared by the input, the dialect and the executor.
#include <kontur/error.hpp>

#include <fmt/format.h>

#include <cstddef>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace kontur::gcode::detail {

/// Where errors of the current line are reported.
struct LineContext {
  std::string_view file;  ///< program name
  long line = 0;          ///< 1-based line number
};

/// Throws InputError "file:line:column: message" for a raw column of the line in `ctx`.
[[noreturn]] inline void fail_column(const LineContext& ctx, int column, const char* rule, const std::string& message) {
  throw InputError(rule, fmt::format("{}:{}:{}: {}", ctx.file, ctx.line, column, message));
}

/// The program's name, the line being read, and the warnings so far.
class Diagnostics {
public:
  Diagnostics(std::string_view name, std::size_t max_warnings_kept)
      : name_(std::make_shared<const std::string>(name)), max_kept_(max_warnings_kept) {
    ctx_.file = *name_;
  }
  Diagnostics(const Diagnostics&) = delete;
  Diagnostics& operator=(const Diagnostics&) = delete;

  /// The program's name as given to the reader (shared with every block's SourceLocation).
  [[nodiscard]] const std::shared_ptr<const std::string>& name() const noexcept { return name_; }
  /// File and current line, for the lexer's messages.
  [[nodiscard]] const LineContext& context() const noexcept { return ctx_; }
  /// The current 1-based line (0 before the first).
  [[nodiscard]] long line() const noexcept { return ctx_.line; }
  /// The file being read changes (a subroutine in a file of its own, and back): its name goes into
  /// messages and into the blocks' SourceLocation from now on.
  void set_file(const std::shared_ptr<const std::string>& name) {
    name_ = name;
    ctx_.file = *name_;
  }
  /// Sets the current line (the input as it reads or seeks; a block reporting at its first line).
  void set_line(long line) noexcept { ctx_.line = line; }

  /// Throws the error "file:line:column: message" at the current line.
  [[noreturn]] void fail(int column, const char* rule, const std::string& message) const {
    fail_column(ctx_, column, rule, message);
  }
  /// Throws the error "file:line:column: message" at another line.
  [[noreturn]] void fail_at_line(long line, int column, const char* rule, const std::string& message) const {
    throw InputError(rule, fmt::format("{}:{}:{}: {}", *name_, line, column, message));
  }
  /// Records the warning "file:line:column: warning: message" at the current line.
  void warn(int column, const std::string& message) {
    ++count_;
    if (warnings_.size() < max_kept_)
      warnings_.push_back(fmt::format("{}:{}:{}: warning: {}", *name_, ctx_.line, column, message));
  }
  [[nodiscard]] const std::vector<std::string>& warnings() const noexcept { return warnings_; }
  [[nodiscard]] std::size_t warning_count() const noexcept { return count_; }

private:
  std::shared_ptr<const std::string> name_;
  LineContext ctx_;
  std::size_t max_kept_;
  std::vector<std::string> warnings_;
  std::size_t count_ = 0;
};

}  // namespace kontur::gcode::detail
