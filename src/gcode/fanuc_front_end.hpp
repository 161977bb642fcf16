#pragma once
// Internal: the Fanuc family's dialect (Fanuc 0i / 30i, Haas, Mitsubishi, Mach3), read as those
// controls read it (docs/gcode.md, "Dialects"): '%' tape marks, program numbers (`O1234 (NAME)`,
// `:1234`), the first program of the file the main one and later ones its subprograms, comments in
// ( ), '/' block delete, N numbers, and Custom Macro B: #variables (local #1-#33 per macro call level,
// common #100-#199 and #500-#999, vacant #0, the system variables of the machine state), expressions
// in [ ] (fanuc_expression.cpp), IF / GOTO / THEN, WHILE / DO / END, M98 / M99 / M97 subprograms and
// G65 macro calls (fanuc_control_flow.cpp). Like the LinuxCNC front end it streams: a jump seeks to a
// line start; the file is indexed (program numbers, N numbers) the first time control flow
// needs it.
#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "dialect_front_end.hpp"
#include "linuxcnc_lexer.hpp"

namespace kontur::gcode::detail {

/// A Macro B value: a number, or vacant (#0, a variable never set).
struct MacroValue {
  double v = 0.0;
  bool vacant = false;
};

/// Reads a Macro B expression (Fanuc's precedence: functions, then * / AND MOD, then + - OR XOR,
/// then EQ NE GT GE LT LE) from text[pos]; `variable(index, at)` gives #index. Advances pos.
/// `word_value`: only what may follow a word's letter (a number, #variable, [expression] or a
/// function, signed), so that `X#1+2` stops after `#1`.
MacroValue parse_macro_value(const NormalizedLine& line, std::size_t& pos, const LineContext& ctx,
                             const std::function<MacroValue(double index, std::size_t at)>& variable, bool word_value);
/// The variable number after '#' at text[pos] (digits, [expression] or another #variable); advances pos.
double parse_macro_index(const NormalizedLine& line, std::size_t& pos, const LineContext& ctx,
                         const std::function<MacroValue(double index, std::size_t at)>& variable);

class FanucFrontEnd final : public DialectFrontEnd {
 public:
  explicit FanucFrontEnd(const DialectServices& services);

  [[nodiscard]] Dialect dialect() const noexcept override { return dialect_; }
  LineOutcome read_line(std::string_view raw, Words& words) override;
  void at_end_of_input() override;
  [[nodiscard]] bool program_marks_its_end() const noexcept override { return tape; }

 private:
  Dialect dialect_;
  ProgramInput& input;
  Diagnostics& diag;
  const ReaderOptions& opt;
  ControlFlowBarrier& executor;
  ExecutorState* state;
  NormalizeRules rules;

  NormalizedLine nl;
  std::string raw_line;     // the line being read (for the messages of #3000 / #3006)
  bool tape = false;        // the file started with '%'
  bool seen_block = false;  // a line with content was read
  bool main_header_seen = false;
  std::string main_name;  // "O1234", for messages
  bool decimal_warned = false;
  bool tool_offset_warned = false;

  // The line being read: where it starts, where the next one starts, its number.
  std::size_t line_offset = 0, next_offset = 0;
  long line_no = 0;
  long resume_line = -1;  // after a jump: the line number of the line read next

  // ================================================================ variables
  struct Var {
    double v = 0.0;
    bool set = false;
  };
  std::vector<std::array<Var, 34>> locals;  // per macro call level, #1..#33
  std::array<Var, 100> common100{};         // #100..#199
  std::array<Var, 500> common500{};         // #500..#999
  // Mach3: every parameter below #5000 is the program's (LinuxCNC's numbering), 0 until set
  static constexpr int mach3_parameter_end = 5000;
  std::vector<Var> mach3_parameters;
  MacroValue read_var(double index, std::size_t at);
  void write_var(double index, const MacroValue& value, std::size_t at);
  [[nodiscard]] int var_index(double index, std::size_t at) const;
  [[nodiscard]] double units() const;  // mm per program unit
  MacroValue value_at(std::size_t& pos, bool word_value);
  std::function<MacroValue(double, std::size_t)> reader;

  // ================================================================ a line
  // The column of DPRNT / BPRNT / POPEN / PCLOS starting the raw line (after its N number), else 0.
  static int port_output(std::string_view raw);
  // Reads the statements and words of nl from `pos`; true if words were made.
  bool statements(std::size_t pos, Words& words);
  // #i = expr (several may follow each other); pos at '#'.
  void assignment(std::size_t& pos);
  // The words of the block from pos.
  void parse_words(std::size_t pos, Words& words);
  // The Fanuc codes the executor does not run: calls, returns, no-ops, refusals; unit conversions.
  void dialect_codes(Words& words);
  [[noreturn]] void refuse(int column, const std::string& what, const std::string& why) const;
  std::string comment_after(int column) const;  // the first ( comment ) of the raw line after column

  // words written as integer literals (bit per letter), for the decimal point rule and dwell units
  std::uint32_t integer_literal = 0;

  // ================================================================ control flow (fanuc_control_flow.cpp)
  struct Pos {
    std::size_t offset = 0;  // a line start
    long line = 0;           // its number
  };
  struct Program {
    long number;       // O number (-1: a name)
    std::string name;  // "O1234"
    Pos header;        // the O line
    Pos body;          // the line after it
  };
  bool programs_indexed = false, labels_indexed = false;
  std::vector<Program> programs;                          // in file order
  std::map<long, std::vector<Pos>> labels;                // N number -> lines, in file order
  std::size_t end_offset = static_cast<std::size_t>(-1);  // a closing '%'
  // Reads the whole file once for its program numbers and, with `labels` (GOTO, M97, M99 P), its
  // N numbers (memory grows with the number of N lines then; M98 alone does not need them).
  void index_file(bool labels);
  // The extent [begin, end) of the program holding `offset`.
  [[nodiscard]] std::pair<std::size_t, std::size_t> program_extent(std::size_t offset) const;
  [[nodiscard]] const Program* find_program(long number) const;

  enum class CallKind { m98, m97, g65 };
  struct Call {
    CallKind kind;
    std::string what;  // "M98 P1000", for messages
    Pos start;         // the subprogram's first line
    Pos ret;           // the line after the call
    long repeats_left;
    long line;  // of the call
    int column;
    std::size_t loops;  // loops open at the call
  };
  std::vector<Call> calls;
  struct Loop {
    int id;
    Pos head;  // the WHILE line
    std::size_t level;
  };
  std::vector<Loop> loops;
  long loop_iterations = 0;

  void jump(const Pos& to);
  void loop_guard(int column, const std::string& what);
  // Jumps to the block N n of the program holding `scope_at`: the first after `from`, else the
  // first from the program's start (Fanuc's search).
  void goto_label(double n, int column, const std::string& what, std::size_t from, std::size_t scope_at);
  void while_do(std::size_t pos, int column);
  void end_loop(int id, int column);
  void skip_to_end(int id, int column, const std::string& what);
  void call(CallKind kind, const Words& words, int column, const std::array<MacroValue, 34>* args);
  void return_from_sub(int column, bool has_p, double p);
  LineOutcome next_program_reached(int column);
};

}  // namespace kontur::gcode::detail
