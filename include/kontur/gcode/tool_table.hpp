#pragma once
// The tool table: LinuxCNC's format, one tool a line (docs/gcode.md, "Tool table and compensation"):
//
//   T1 P1 D6.000 Z+10.000 ;comment
//
// T (required) the tool number, P the pocket, X Y Z A B C U V W the offsets (Z is the tool length;
// the others are accepted, Kontur applies Z only), D the diameter, I J Q (lathe: front angle, back
// angle, orientation) accepted and ignored; `;` starts a comment; blank lines are skipped. Values
// are in the machine's linear units (a factor to mm is given to read()).
//
// The Fanuc family's offset registers map onto it: H n is tool n's length, D n is tool n's radius
// (diameter / 2).
#include <filesystem>
#include <map>
#include <string_view>

namespace kontur::gcode {

/// One tool of the table (lengths in [mm]).
struct Tool {
  int number = 0;            ///< T
  int pocket = 0;            ///< P (0: none given)
  double length_mm = 0.0;    ///< the Z offset: the tool length applied by G43
  double diameter_mm = 0.0;  ///< D: the cutter diameter (G41 / G42 use half of it)
};

/// The tools of a machine by number.
class ToolTable {
public:
  /// The tool `number`, or nullptr if the table has none.
  [[nodiscard]] const Tool* find(int number) const noexcept;
  /// Adds or replaces the tool `tool.number`.
  void set(const Tool& tool);
  /// Number of tools.
  [[nodiscard]] std::size_t size() const noexcept { return tools_.size(); }
  /// The tools, by number.
  [[nodiscard]] const std::map<int, Tool>& tools() const noexcept { return tools_; }

  /// Reads the table file `path`; `mm_per_unit` converts its values to mm (25.4 for a machine in
  /// inches). Throws InputError("file:line: rule") at a missing file, an unknown word, a tool given
  /// twice, a value that is not a number or a negative diameter.
  [[nodiscard]] static ToolTable read(const std::filesystem::path& path, double mm_per_unit = 1.0);
  /// The same from text; `name` is used in messages.
  [[nodiscard]] static ToolTable parse(std::string_view text, std::string_view name, double mm_per_unit = 1.0);

private:
  std::map<int, Tool> tools_;
};

}  // namespace kontur::gcode
