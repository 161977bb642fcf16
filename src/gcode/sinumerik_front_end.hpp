#pragma once
// Internal: the Sinumerik 840D dialect. A line is read as the control reads it: `%_N_NAME_MPF`
// headers, `;` comments, `/` block delete, N and `:` block numbers, labels `NAME:`, R parameters
// and DEF variables with Sinumerik's expressions (sinumerik_expression.cpp), addresses with values
// or `=expression` (`X=R1+2`, `X=AC(5)`, `CR=`, `TURN=`), and the control flow (labels and
// GOTOF / GOTOB / GOTO / GOTOC, IF / ELSE / ENDIF, WHILE, FOR, REPEAT / UNTIL, LOOP, subprograms
// of the same file, M17 / RET) by seeking in the streamed input (sinumerik_control_flow.cpp).
// A subprogram not in the file is read from NAME.SPF beside it (the control's subprogram
// directory): while it runs, the main program's line is read again and the subprogram's lines are
// read from its own input instead.
// Drilling cycles CYCLE81 / 82 / 83 (also as MCALL) expand into several blocks, handed out by
// pending_words (sinumerik_cycles.cpp). The words go to the dialect-neutral executor with the
// codes it knows (G70 -> G20, G60 -> G61.1, SUPA -> G53, ...).
#include <array>
#include <cstddef>
#include <deque>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include "dialect_front_end.hpp"

namespace kontur::gcode::detail {

class SinumerikFrontEnd final : public DialectFrontEnd {
 public:
  explicit SinumerikFrontEnd(const DialectServices& services);

  [[nodiscard]] Dialect dialect() const noexcept override { return Dialect::sinumerik; }
  LineOutcome read_line(std::string_view raw, Words& words) override;
  // read_line for a line of the program being run (the main program's or a subprogram file's).
  LineOutcome read_program_line(std::string_view raw, Words& words);
  bool pending_words(Words& words) override;
  void at_end_of_input() override;
  [[nodiscard]] bool program_marks_its_end() const noexcept override { return false; }

  /// Highest R parameter number (R0 .. R999).
  static constexpr int r_count = 1000;

  // ---------------------------------------------------------------- expressions (sinumerik_expression.cpp)
  /// A position in the current line (upper case outside strings, comment removed).
  struct Cursor {
    std::string_view t;
    std::size_t p = 0;
    void ws() noexcept {
      while (p < t.size() && (t[p] == ' ' || t[p] == '\t')) ++p;
    }
    [[nodiscard]] bool end() noexcept {
      ws();
      return p >= t.size();
    }
    [[nodiscard]] char peek() noexcept {
      ws();
      return p < t.size() ? t[p] : '\0';
    }
    bool eat(char c) noexcept {
      if (peek() != c) return false;
      ++p;
      return true;
    }
    [[nodiscard]] int col() const noexcept { return static_cast<int>(p) + 1; }
  };

 private:
  enum class VarType { real, integer, boolean, character, string, axis };
  struct Variable {
    VarType type = VarType::real;
    double value = 0.0;
    std::string text;           // STRING, AXIS
    std::vector<double> array;  // DEF REAL A[n]
    bool is_array = false;
  };
  using Scope = std::map<std::string, Variable, std::less<>>;

  enum class FKind { if_, while_, for_, repeat, loop, call, section };
  struct Frame {
    Frame(FKind k, std::size_t o, long l) : kind(k), offset(o), line(l) {}
    FKind kind;
    std::size_t offset;  // while: its line; for / repeat / loop: the line after; call: the return line
    long line;
    std::string var;           // for: the counter
    double end = 0.0;          // for: the last value
    long repeats = 0;          // call: repetitions left (NAME P3)
    std::vector<double> args;  // call: the arguments, for a repetition
    bool external = false;     // call: of a subprogram in a file of its own
    // section (REPEAT label [label] P=n, REPEATB label P=n): offset is the first line; var the end
    // label ("" up to ENDLABEL: or the REPEAT line); repeats left; where to go on after it
    bool single = false;          // REPEATB: the labelled block alone
    std::size_t stop_offset = 0;  // the REPEAT line (the section ends before it)
    std::size_t ret_offset = 0;
    long ret_line = 0;
  };
  struct Position {
    std::size_t offset;
    long line;
  };
  struct Proc {
    Position start;  // the line after PROC / the header
    std::vector<std::pair<VarType, std::string>> params;
    bool external = false;  // in a file of its own (NAME.SPF)
  };

  ProgramInput& main_input;
  std::unique_ptr<ProgramInput> external;  // the file of the subprogram being run, if not this one
  std::string main_name;                   // the program's name, for messages after the return
  std::shared_ptr<const std::string> main_file;  // the same, as the blocks' SourceLocation holds it
  long external_line = 0;                  // the line of the subprogram file last read
  long main_line = 0;                      // the main program's line of the call
  bool deferred_return = false;            // M17 in a block of a subprogram file: return after it ran
  std::map<std::string, Position, std::less<>> saved_labels;  // of the main program, during the call
  // The input being read: the main program's, or the file of the subprogram being run.
  ProgramInput& in() noexcept { return external ? *external : main_input; }
  ParameterTable& params;
  Diagnostics& diag;
  const ReaderOptions& opt;
  ControlFlowBarrier& executor;

  std::string text;  // the current line: upper case outside strings, without its comment
  Cursor cur;
  std::vector<double> r_;
  std::vector<Scope> scopes;
  std::vector<Frame> frames;
  std::map<std::string, Position, std::less<>> labels;
  std::map<std::string, Proc, std::less<>> procs;
  std::set<std::string, std::less<>> warned;  // keywords warned once
  long loop_iterations = 0;
  bool seen_header = false;
  bool seen_block = false;
  bool end_requested = false;    // RET of a program of its own, a PROC after the main program
  bool g9_restore = false;       // G9 ran in the last block: the path mode goes back
  int path_g = 640;              // the executor's path code in effect (G64 / G61.1)
  double path_tolerance = -1.0;  // ADIS given (mm), -1 none
  bool adis_given = false;       // ADIS= in the block being read
  int motion_g = 0;              // the last G0/G1/G2/G3 (times 10; G0 at the start, as the control), for cycles
  double spindle_rpm = 0.0;
  int plane_g = 170;  // G17 / G18 / G19 (times 10), for cycles
  bool inch = false;

  // cycles
  std::deque<Words> pending;
  bool mcall_active = false;
  std::string mcall_text;  // the cycle call text of MCALL, re-read for every position
  int mcall_column = 1;

  // ---- lines
  void prepare(std::string_view raw);
  [[noreturn]] void fail(int column, const char* rule, const std::string& message) const {
    diag.fail(column, rule, message);
  }
  void warn_once(const std::string& key, int column, const std::string& message);
  // The leading block number, label and block-delete of the line in `text`; false for a deleted line.
  struct Head {
    long n = -1;
    std::string label;
    bool deleted = false;
  };
  Head read_head(Cursor& c, bool record);
  bool statement(Words& words);  // a control-flow or definition line: true if it was one
  LineOutcome block(Words& words);
  void read_words(Words& words);
  bool keyword_word(std::string_view name, int col, Words& words);
  void add_g(Words& words, int g, int col);
  void address(char letter, int col, Words& words);
  double number_literal(Cursor& c);

  // ---- variables
  [[nodiscard]] Variable* find_var(std::string_view name);
  void define(Cursor& c);
  double* lvalue(Cursor& c, std::string_view name, int col, VarType* type);
  // The type a DEF or PROC parameter names (REAL INT BOOL CHAR STRING AXIS); none for another word.
  [[nodiscard]] static std::optional<VarType> var_type_named(std::string_view name);
  // After "R" at '[': the index of R[expression], checked against R0 .. R(r_count - 1).
  std::size_t r_index(Cursor& c, int col);
  // After an array variable's name: its element [expression], the index checked against its size.
  double& array_element(Cursor& c, Variable& v, std::string_view name, int col);
  void assign(Cursor& c, std::string_view name, int col);
  static double store(VarType type, double v);

  // ---- expressions (sinumerik_expression.cpp)
 public:
  double expr(Cursor& c);

 private:
  double compare(Cursor& c);
  double concat(Cursor& c);
  double logic_or(Cursor& c);
  double logic_xor(Cursor& c);
  double logic_and(Cursor& c);
  double bit_or(Cursor& c);
  double bit_xor(Cursor& c);
  double bit_and(Cursor& c);
  double additive(Cursor& c);
  double term(Cursor& c);
  double unary(Cursor& c);
  double primary(Cursor& c);
  double function(Cursor& c, std::string_view name, int col);
  static bool eat_keyword(Cursor& c, const char* word);
  static std::string_view identifier(Cursor& c);
  std::string string_literal(Cursor& c);

  // ---- control flow (sinumerik_control_flow.cpp)
  void loop_guard(const char* what);
  void jump(std::string_view how, Cursor& c, int col);
  bool scan_forward(const std::string& label, long number);
  bool scan_backward(const std::string& label, long number);
  // Reads lines without running them to the `close` (or `middle`) of the construct `open` at
  // depth 0; returns the keyword found. The input is then after that line.
  std::string skip_to(const char* open, const char* middle, const char* close);
  void control(std::string_view kw, Cursor& c, int col);
  void call(const std::string& name, Cursor& c, int col);
  void enter_proc(const Frame& f, bool fresh);
  std::vector<std::pair<VarType, std::string>> proc_params(Cursor& c);
  // What the control can do and Kontur does not: the feature named `name` stands for, or nullptr.
  static const char* refusal_of(std::string_view name) noexcept;
  void end_of_sub(int col);
  // The repeated section ends with this line: again from its start, or on after the REPEAT line.
  void end_section();
  // REPEAT / REPEATB with a label: a program section run again P times.
  void repeat_section(Cursor& c, int col, bool single);
  bool find_proc(const std::string& name);
  // Opens NAME.SPF beside the program for a call; false if there is none.
  bool open_external(const std::string& name, int col);
  void close_external();
  void define_proc(Cursor& c, int col, bool as_main);
  // The first word of a line read while scanning (after its number and label), or "" for a
  // deleted or empty line; `single_if`: an IF with its GOTO on the line.
  std::string scan_keyword(bool& single_if, Head& head);
  // Reads the next line with content of this program without running it, into kw / single_if /
  // head (scan_keyword); false at the end of the input or at a '%' header (the next program).
  bool next_scanned_line(std::string& kw, bool& single_if, Head& head);
  [[nodiscard]] bool in_call() const noexcept;

  // ---- cycles (sinumerik_cycles.cpp)
  bool cycle_call(std::string_view name, Cursor& c, int col, Words& words);
  void expand_cycle(std::string_view name, const std::vector<std::optional<double>>& a, int col);
  std::vector<std::optional<double>> cycle_arguments(Cursor& c, std::string_view name);
};

}  // namespace kontur::gcode::detail
