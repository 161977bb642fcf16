#pragma once
// Internal: the LinuxCNC dialect (RS274NGC as LinuxCNC reads it): lines through its lexer
// (linuxcnc_lexer.hpp), '%' tape marks, '/' block delete, parameter assignments applied after the
// whole line, and the O-word control flow (linuxcnc_o_words.cpp): sub / endsub / call / return,
// while / endwhile, do / while, repeat / endrepeat, break, continue, if / elseif / else / endif. The
// reader streams: a loop or a call seeks back to a line start it has seen; only the open frames
// and the subroutines' start offsets are kept.
#include "dialect_front_end.hpp"
#include "linuxcnc_lexer.hpp"

#include <array>
#include <cstddef>
#include <initializer_list>
#include <map>
#include <string>
#include <vector>

namespace kontur::gcode::detail {

class LinuxcncFrontEnd final : public DialectFrontEnd {
public:
  explicit LinuxcncFrontEnd(const DialectServices& services)
      : dialect_(services.dialect), input(services.input), params(services.parameters), diag(services.diagnostics), opt(services.options),
        executor(services.executor) {}

  [[nodiscard]] Dialect dialect() const noexcept override { return dialect_; }
  LineOutcome read_line(std::string_view raw, Words& words) override;
  void at_end_of_input() override;
  [[nodiscard]] bool program_marks_its_end() const noexcept override { return tape; }

private:
  Dialect dialect_;  // linuxcnc, or a dialect read the same way (grbl: with its `$` lines)
  ProgramInput& input;
  ParameterTable& params;
  Diagnostics& diag;
  const ReaderOptions& opt;
  ControlFlowBarrier& executor;

  NormalizedLine nl;
  std::vector<Assignment> assignments;
  std::size_t assignment_count = 0;
  bool tape = false;        // the program started with '%'
  bool seen_block = false;  // a line with content was read
  bool axis_words_seen = false;  // a block with an axis word (X..W) was read (grbl: homing after it moves)
  bool program_number_warned = false;  // a Fanuc / Haas program number was noted

  // grbl: a `$` line (a setting or a system command) at `column`; refused if it moves the axes.
  void grbl_command(std::string_view line, int column);

  // ================================================================ O-words (linuxcnc_o_words.cpp)
  enum class OKind { sub, endsub, call, ret, while_, endwhile, do_, repeat, endrepeat, if_, elseif, else_, endif,
                     break_, continue_ };
  struct OWord {
    std::string label;
    OKind kind = OKind::sub;
    std::size_t rest = 0;  // position in nl.text after the keyword
  };
  struct Frame {
    OKind kind;            // while_, do_, repeat, if_, call
    std::string label;
    std::size_t offset;    // while: the while line; do/repeat: the line after; call: the return line
    long line;
    long count = 0;        // repeat: iterations left; loops: iterations done
    std::array<double, 30> saved{};  // call: #1..#30 of the caller
    int call_column = 1;
  };
  struct SubStart {
    std::size_t offset;
    long line;
  };
  std::vector<Frame> frames;
  std::map<std::string, SubStart, std::less<>> subs;
  long loop_iterations = 0;  // O-word loop iterations and calls so far

  [[noreturn]] void fail(int column, const char* rule, const std::string& message) const {
    diag.fail(column, rule, message);
  }
  // Runs the O-word line in nl.
  void control_flow();
  OWord parse_oword(const NormalizedLine& line) const;
  double o_value(const OWord& o, std::size_t& at, const char* what) const;
  void o_end_of_line(std::size_t at) const;
  // Reads lines without running them until the O-word `label` with one of `kinds`; leaves nl at it.
  OWord skip_to(const std::string& label, std::initializer_list<OKind> kinds, const char* what);
  Frame* find_frame(const std::string& label);
  // The subroutine `label` from its own file on the subroutine path (ReaderOptions::subroutine_path),
  // registered in subs; fails at `col` naming the file and the path if there is none.
  std::map<std::string, SubStart, std::less<>>::iterator load_subroutine_file(const std::string& label, int col);
  void loop_guard(const std::string& label);
};

}  // namespace kontur::gcode::detail
