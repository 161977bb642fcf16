#pragma once
// G-code dialects: which control's reading a program gets (docs/gcode.md, "Dialects"), and how
// Kontur tells it from the program when the user does not say (detect_dialect).
#include <array>
#include <optional>
#include <string>
#include <string_view>

namespace kontur::gcode {

/// The G-code dialect a program is written in: how it spells comments, parameters, expressions
/// and control flow, and the few rules in which its control differs from LinuxCNC's (G80 keeping
/// the motion mode, `$` lines). The blocks it gives are the same for every dialect.
enum class Dialect {
  linuxcnc,    ///< LinuxCNC's RS274NGC: #parameters, [expressions], O-word subroutines and loops
  fanuc,       ///< Fanuc (0i/30i): O program numbers, Custom Macro B, M98 / M99, G65
  haas,        ///< Haas NGC: Fanuc's reading with Haas's codes (M97 local subprograms)
  mitsubishi,  ///< Mitsubishi M70 / M80 (Meldas): Fanuc's reading
  sinumerik,   ///< Siemens Sinumerik 840D: R parameters, DEF, labels and GOTOF, frames, cycles
  grbl,        ///< grbl 1.1: plain G-code, `$` setting lines
  mach3,       ///< Mach3 / Mach4: LinuxCNC-like G-code with O-number subprograms (M98 / M99)
};
/// Every dialect, in the order of the enum.
inline constexpr std::array<Dialect, 7> all_dialects = {Dialect::linuxcnc, Dialect::fanuc,     Dialect::haas,
                                                       Dialect::mitsubishi, Dialect::sinumerik, Dialect::grbl,
                                                       Dialect::mach3};

/// Stable lower-case name of a dialect ("linuxcnc", "haas", ...).
[[nodiscard]] const char* to_string(Dialect dialect) noexcept;
/// The dialect named `name` (lower or upper case); nullopt for an unknown name.
[[nodiscard]] std::optional<Dialect> parse_dialect(std::string_view name) noexcept;
/// "linuxcnc|fanuc|haas|mitsubishi|sinumerik|grbl|mach3", for help texts and messages.
[[nodiscard]] std::string dialect_names();

/// A dialect and why it was taken.
struct DialectChoice {
  Dialect dialect = Dialect::linuxcnc;
  /// Why, for a person: "program number O78237 on line 2", "given with --dialect".
  std::string reason;
};

/// The dialect of a program from its text (its beginning is enough: the first
/// tolerances::gcode_dialect_detection_lines lines are looked at), and the mark that told it:
/// Sinumerik's syntax (`%_N_..._MPF`, `R1=`, `DEF REAL`, `GOTOF`, `CYCLE81`, ...), LinuxCNC's
/// (`o<name> sub`, `#<name>`), a grbl `$` line, Fanuc's (program number `O1234` or `:1234`, Macro B
/// `IF [..] GOTO`, `WHILE [..] DO1`, `M98 P`, `G65 P`) refined by a control named in a comment
/// (Haas, Mitsubishi, Mach3), a control named in a comment alone, the file's extension (`.mpf`,
/// `.spf`, `.ngc`). Without any mark: LinuxCNC. `name` is the program's file name (for its
/// extension).
[[nodiscard]] DialectChoice detect_dialect(std::string_view name, std::string_view text);
/// detect_dialect on the beginning of the file `path`; throws InputError if it cannot be read.
[[nodiscard]] DialectChoice detect_dialect_of_file(const std::string& path);

/// The dialect a program is read in: `given` on the command line, else the machine file's
/// `from_machine` (named by `machine_source`), else detected from the file `path`.
[[nodiscard]] DialectChoice choose_dialect(const std::string& path, std::optional<Dialect> given,
                                           std::optional<Dialect> from_machine = std::nullopt,
                                           const std::string& machine_source = {});

}  // namespace kontur::gcode
