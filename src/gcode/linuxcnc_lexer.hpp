#pragma once
// Internal: the LinuxCNC dialect's lexer: one program line turned into the words of a block. The
// raw line is first normalised (comments in ( ) and after ;, spaces removed, upper case, '/' block
// delete and '%' tape marks noted) with a map back to the raw columns; then words, N numbers,
// parameter assignments (#1 = .., #<name> = ..) and expressions ([..], functions, #parameters) are
// read from it. Errors throw InputError with the control-alarm message "file:line:column: WORD: rule".
#include "block_words.hpp"
#include "diagnostics.hpp"

#include <kontur/gcode/expression.hpp>

#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace kontur::gcode::detail {

/// A line without comments and spaces, upper case, with the raw 1-based column of every character.
struct NormalizedLine {
  std::string text;
  std::vector<int> column;  // column[i] of text[i]; one extra entry for the end of the line
  bool block_delete = false;  // the line starts with '/'
  bool percent = false;       // the line is a '%' tape mark (text: a program number after it, if any)
  int percent_column = 0;     // column of what follows the '%' on its line (0: nothing)
  int first_column = 1;       // raw column of the first character of text
};

/// How a dialect's lines differ in normalize_line (shared by the LinuxCNC and Fanuc front ends).
struct NormalizeRules {
  /// ';' starts a comment to the end of the line (LinuxCNC, Mach3); else it ends the block (Fanuc's
  /// EOB) and only spaces or a comment may follow it.
  bool semicolon_comment = true;
  /// ',' is kept (Fanuc's POW[a,b], ATAN[a,b], ",C" / ",R" corners); LinuxCNC refuses it.
  bool comma = false;
  /// '@' (radius) and '^' (angle) are LinuxCNC's polar coordinates; else they are refused.
  bool polar = true;
  /// The dialect's name for messages about ';' ("fanuc").
  const char* dialect = "linuxcnc";
};

/// Normalises `raw` (one line without its end-of-line characters) into `out` (buffers reused).
void normalize_line(std::string_view raw, const LineContext& ctx, NormalizedLine& out,
                    const NormalizeRules& rules = NormalizeRules{});

/// A parameter assignment of the line, applied after the whole line is read (LinuxCNC's rule).
struct Assignment {
  int index = 0;      // numbered parameter, or 0 for a named one
  std::string name;   // named parameter
  double value = 0.0;
};

/// Reads words and assignments of a normalised line. `assignments` gets `assignment_count` entries
/// (its strings are reused).
void parse_words(const NormalizedLine& line, const LineContext& ctx, const ParameterTable& parameters, Words& words,
                 std::vector<Assignment>& assignments, std::size_t& assignment_count);

/// Evaluates a real value at text[pos..] (used by parse_words and evaluate_expression); advances pos
/// (linuxcnc_expression.cpp).
double parse_real_value(const NormalizedLine& line, std::size_t& pos, const LineContext& ctx,
                        const ParameterTable& parameters);

/// After '#' (text[pos] is '<'): the name of a named parameter, upper case; advances pos past '>'.
std::string_view parse_parameter_name(const NormalizedLine& line, std::size_t& pos, const LineContext& ctx,
                                      const ParameterTable& parameters);
/// After '#' (at `start`): the number of a numbered parameter, an integer 1..5602; advances pos.
int parse_parameter_index(const NormalizedLine& line, std::size_t& pos, std::size_t start, const LineContext& ctx,
                          const ParameterTable& parameters);

/// A decimal number (digits with at most one '.') at text[pos]; advances pos. Shared by the dialects.
double parse_number(const NormalizedLine& line, std::size_t& pos, const LineContext& ctx);

/// The functions of one argument the dialects share (angles in degrees): SIN COS TAN ASIN ACOS
/// SQRT ABS ROUND FIX (down) FUP (up) EXP LN. `known` false for another name; `domain` false when
/// `a` is outside the function's domain.
double unary_function(std::string_view name, double a, bool& known, bool& domain) noexcept;

/// A G/M code or parameter number must be this close to an integer.
inline constexpr double integer_tolerance = 1e-6;
inline bool is_letter(char c) noexcept { return c >= 'A' && c <= 'Z'; }
inline bool is_digit(char c) noexcept { return c >= '0' && c <= '9'; }
/// A short excerpt of the normalised text from pos ("end of line" past it), for messages.
std::string excerpt(const NormalizedLine& line, std::size_t pos, std::size_t max_len = 24);

/// Throws InputError "file:line:col: message" for the character at text[pos] of the line.
[[noreturn]] void fail_at(const NormalizedLine& line, std::size_t pos, const LineContext& ctx, const char* rule,
                          const std::string& message);

}  // namespace kontur::gcode::detail
