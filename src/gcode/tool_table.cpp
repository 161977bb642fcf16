// The tool table in LinuxCNC's format (include/kontur/gcode/tool_table.hpp).
#include <kontur/error.hpp>
#include <kontur/gcode/tool_table.hpp>

#include <fmt/format.h>

#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>

namespace kontur::gcode {

const Tool* ToolTable::find(int number) const noexcept {
  const auto it = tools_.find(number);
  return it == tools_.end() ? nullptr : &it->second;
}

void ToolTable::set(const Tool& tool) { tools_[tool.number] = tool; }

namespace {

[[noreturn]] void fail(std::string_view name, long line, const char* rule, const std::string& message) {
  throw InputError(rule, fmt::format("{}:{}: {}: {}", name, line, rule, message));
}

// The number of a word ("+10.000", "-.5"), or fails.
double number_of(std::string_view token, std::string_view name, long line) {
  const std::string text(token.substr(1));
  const char* begin = text.c_str();
  char* end = nullptr;
  errno = 0;
  const double v = std::strtod(begin, &end);
  if (text.empty() || end != begin + text.size() || errno == ERANGE || !std::isfinite(v))
    fail(name, line, "not-a-number", fmt::format("{}: the value is not a number", token));
  return v;
}

}  // namespace

ToolTable ToolTable::parse(std::string_view text, std::string_view name, double mm_per_unit) {
  ToolTable table;
  long line_number = 0;
  std::size_t at = 0;
  while (at <= text.size()) {
    const std::size_t eol = text.find('\n', at);
    std::string_view line = text.substr(at, eol == std::string_view::npos ? std::string_view::npos : eol - at);
    at = eol == std::string_view::npos ? text.size() + 1 : eol + 1;
    ++line_number;
    if (const auto semicolon = line.find(';'); semicolon != std::string_view::npos) line = line.substr(0, semicolon);
    Tool tool;
    bool has_t = false;
    std::size_t i = 0;
    while (i < line.size()) {
      if (std::isspace(static_cast<unsigned char>(line[i]))) {
        ++i;
        continue;
      }
      std::size_t j = i;
      while (j < line.size() && !std::isspace(static_cast<unsigned char>(line[j]))) ++j;
      const std::string_view token = line.substr(i, j - i);
      i = j;
      const char letter = static_cast<char>(std::toupper(static_cast<unsigned char>(token[0])));
      if (std::string_view("TPXYZABCUVWDIJQ").find(letter) == std::string_view::npos)
        fail(name, line_number, "unknown-word",
             fmt::format("{}: unknown word (expected T P X Y Z A B C U V W D I J Q)", token));
      const double v = number_of(token, name, line_number);
      switch (letter) {
        case 'T':
          if (v != std::floor(v) || v < 0.0 || v > 1e9)
            fail(name, line_number, "tool-number", fmt::format("{}: the tool number must be an integer >= 0", token));
          tool.number = static_cast<int>(v);
          has_t = true;
          break;
        case 'P':
          if (v != std::floor(v) || v < 0.0 || v > 1e9)
            fail(name, line_number, "pocket", fmt::format("{}: the pocket must be an integer >= 0", token));
          tool.pocket = static_cast<int>(v);
          break;
        case 'Z': tool.length_mm = v * mm_per_unit; break;
        case 'D':
          if (v < 0.0) fail(name, line_number, "negative-diameter", fmt::format("{}: the diameter must be >= 0", token));
          tool.diameter_mm = v * mm_per_unit;
          break;
        default: break;  // the other offsets and the lathe fields: accepted, not applied
      }
    }
    if (line.find_first_not_of(" \t\r") == std::string_view::npos) continue;
    if (!has_t) fail(name, line_number, "tool-missing", "T (the tool number) missing");
    if (table.find(tool.number) != nullptr)
      fail(name, line_number, "tool-twice", fmt::format("T{}: the tool is in the table twice", tool.number));
    table.set(tool);
  }
  return table;
}

ToolTable ToolTable::read(const std::filesystem::path& path, double mm_per_unit) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError("tool-table", fmt::format("{}: tool-table: cannot open the tool table", path.string()));
  std::ostringstream text;
  text << in.rdbuf();
  return parse(text.str(), path.string(), mm_per_unit);
}

}  // namespace kontur::gcode
