#pragma once
// Internal: one program line turned into its words. The raw line is first normalised (comments
// removed, spaces removed, upper case) with a map back to the raw columns; then words, parameter
// assignments and expressions are read from it. Errors throw InputError with the control-alarm
// message "file:line:column: WORD: rule".
#include <kontur/gcode/expression.hpp>

#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace kontur::gcode::detail {

/// Where errors of the current line are reported.
struct LineContext {
  std::string_view file;  ///< program name
  long line = 0;          ///< 1-based line number
};

/// A line without comments and spaces, upper case, with the raw 1-based column of every character.
struct NormalizedLine {
  std::string text;
  std::vector<int> column;  // column[i] of text[i]; one extra entry for the end of the line
  bool block_delete = false;  // the line starts with '/'
  bool percent = false;       // the line is a '%' tape mark
  int first_column = 1;       // raw column of the first character of text
};

/// Normalises `raw` (one line without its end-of-line characters) into `out` (buffers reused).
void normalize_line(std::string_view raw, const LineContext& ctx, NormalizedLine& out);

/// Block keywords of the Sinumerik style.
enum class Keyword : std::uint8_t { none, cip, conic };

/// The words of one block.
struct Words {
  std::array<double, 26> value{};     // by letter A..Z
  std::array<int, 26> column{};       // raw column of the letter
  std::uint32_t present = 0;          // bit (letter - 'A')
  int g_count = 0;
  std::array<int, 16> g{};            // G codes times 10 (G6.2 -> 62)
  std::array<int, 16> g_column{};
  std::array<std::uint8_t, 16> g_leading_zero{};  // written with a leading zero (G06.2, G01)
  int m_count = 0;
  std::array<int, 8> m{};
  std::array<int, 8> m_column{};
  std::array<std::array<double, 3>, 3> indexed{};  // [point 0..2][I J K] of I1= .. K3=
  std::array<std::array<int, 3>, 3> indexed_column{};
  std::uint16_t indexed_present = 0;  // bit 3 * point + axis
  Keyword keyword = Keyword::none;
  int keyword_column = 0;
  long n_number = -1;
  int first_column = 0;  // raw column of the first word (0 if none)

  void clear() noexcept {
    present = 0;
    g_count = 0;
    m_count = 0;
    indexed_present = 0;
    keyword = Keyword::none;
    n_number = -1;
    first_column = 0;
  }
  [[nodiscard]] bool has(char letter) const noexcept { return (present >> (letter - 'A')) & 1u; }
  [[nodiscard]] double get(char letter) const noexcept { return value[static_cast<std::size_t>(letter - 'A')]; }
  [[nodiscard]] int col(char letter) const noexcept { return column[static_cast<std::size_t>(letter - 'A')]; }
  [[nodiscard]] bool has_indexed(int point, int axis) const noexcept {
    return (indexed_present >> (3 * point + axis)) & 1u;
  }
  [[nodiscard]] bool empty() const noexcept {
    return present == 0 && g_count == 0 && m_count == 0 && indexed_present == 0 && keyword == Keyword::none;
  }
};

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

/// Evaluates a real value at text[pos..] (used by parse_words and evaluate_expression); advances pos.
double parse_real_value(const NormalizedLine& line, std::size_t& pos, const LineContext& ctx,
                        const ParameterTable& parameters);

/// Throws InputError "file:line:col: message" for the character at text[pos] of the line.
[[noreturn]] void fail_at(const NormalizedLine& line, std::size_t pos, const LineContext& ctx, const char* rule,
                          const std::string& message);
/// Throws InputError "file:line:col: message" for a raw column.
[[noreturn]] void fail_column(const LineContext& ctx, int column, const char* rule, const std::string& message);

}  // namespace kontur::gcode::detail
