#pragma once
#include <kontur/gcode/dialect.hpp>
// The machine a program runs on: per-axis velocity, acceleration and jerk limits, path feed
// limits, chord tolerance and servo period. Read from Kontur's TOML machine file or from a
// LinuxCNC INI file; an embedded default serves when none is given. All values in [mm], [s].
#include <filesystem>
#include <limits>
#include <optional>
#include <string>
#include <vector>

namespace kontur {

/// Limits of one axis.
struct AxisLimits {
  char name = 'X';                        ///< axis letter: X Y Z U V W (linear), A B C (rotary)
  bool rotary = false;                    ///< A B C: units are [deg] instead of [mm]
  double max_velocity = 0.0;              ///< [mm/s] (rotary: [deg/s])
  double max_acceleration = 0.0;          ///< [mm/s^2] (rotary: [deg/s^2])
  double max_jerk = 0.0;                  ///< [mm/s^3] (rotary: [deg/s^3])
  double min_position = -std::numeric_limits<double>::infinity();  ///< soft limit [mm]
  double max_position = std::numeric_limits<double>::infinity();   ///< soft limit [mm]
};

/// A machine's limits and timing.
struct Machine {
  std::string name;                 ///< a name for reports
  std::string source;               ///< where it was read from ("embedded default", a path)
  std::vector<AxisLimits> axes;     ///< in coordinate order; at least one of X, Y, Z
  double max_feed_mm_s = 0.0;       ///< largest programmed path feed honoured [mm/s]
  double rapid_feed_mm_s = 0.0;     ///< path speed of G0 moves [mm/s]
  double chord_tolerance_mm = 0.0;  ///< largest bow height of a servo cycle's chord [mm]
  double path_tolerance_mm = 0.0;   ///< G64 corner tolerance when the program gives none [mm]
  double servo_period_s = 0.0;      ///< servo (interpolation) period [s]
  /// The G-code dialect of the machine's control (TOML `dialect`, INI `[KONTUR] DIALECT`); none:
  /// each program's dialect is detected (gcode::detect_dialect). `--dialect` overrides it.
  std::optional<gcode::Dialect> dialect;
  /// Folders searched for subroutines in files of their own (TOML `subroutine_path`, INI
  /// `[RS274NGC] SUBROUTINE_PATH`, relative to the machine file); `--subroutine-path` overrides it.
  std::vector<std::string> subroutine_path;
  /// LinuxCNC's INI [RS274NGC] CENTER_ARC_RADIUS_TOLERANCE_MM [mm] and _INCH [in]: how far the two
  /// radii of a centre-format arc may differ (gcode::ReaderOptions); none: LinuxCNC's defaults.
  std::optional<double> arc_radius_tolerance_mm;
  std::optional<double> arc_radius_tolerance_inch;
  /// The tool table file (LinuxCNC's format; TOML `tool_table`, INI `[EMCIO] TOOL_TABLE`, relative to
  /// the machine file; empty: none) and its unit [mm per table unit] (the INI's LINEAR_UNITS: inch
  /// 25.4; TOML `tool_table_units = "inch"`). `--tool-table` overrides the file.
  std::string tool_table;
  double tool_table_mm_per_unit = 1.0;

  /// The limits of axis `name` (X Y Z A B C U V W), or nullptr.
  [[nodiscard]] const AxisLimits* axis(char name) const noexcept;
};

/// Coordinate index of a linear axis letter: X = 0, Y = 1, Z = 2; -1 for any other letter.
[[nodiscard]] constexpr int linear_axis_index(char name) noexcept {
  return name == 'X' ? 0 : name == 'Y' ? 1 : name == 'Z' ? 2 : -1;
}

/// Kontur's default machine (a 3-axis mill): X Y Z 200 mm/s, 2000 mm/s^2, 50000 mm/s^3; path
/// feed 10000 mm/min, rapid 12000 mm/min; chord tolerance 1 um; G64 tolerance 10 um; 1 ms.
[[nodiscard]] Machine default_machine();

/// Checks every value: limits finite and > 0 (a limit of zero would stop the machine), servo
/// period in [10 us, 100 ms], min_position < max_position, a linear axis present, no axis twice. Throws
/// InputError naming the source, the field and the value.
void validate(const Machine& machine);

/// Reads Kontur's TOML machine file (documented in docs/machine.md); top-level fields not given
/// keep the default machine's values; [axes.*] sections, if any, are all the machine's axes. Throws InputError with file, line and field.
[[nodiscard]] Machine read_machine_toml(const std::filesystem::path& file);
/// Reads a LinuxCNC INI file: [TRAJ] COORDINATES, LINEAR_UNITS (mm or inch), MAX_LINEAR_VELOCITY,
/// MAX_VELOCITY and MAX_ACCELERATION; [EMCMOT] SERVO_PERIOD [ns]; per axis of COORDINATES (X Y Z
/// A B C U V W) [AXIS_X] (2.8+), [AXIS_n] (numbered by the letter, X = 0 .. C = 5, U = 6 .. W = 8,
/// as LinuxCNC 2.7 does) or [JOINT_n] (in coordinate order) MAX_VELOCITY, MAX_ACCELERATION,
/// MAX_JERK, MIN_LIMIT, MAX_LIMIT, in the machine's units per second (A B C in degrees); an
/// [AXIS_<letter>] section for a letter COORDINATES lacks is an error. Kontur's own keys in a [KONTUR] section: CHORD_TOLERANCE,
/// PATH_TOLERANCE [units], JERK_TIME [s] (the jerk of an axis without MAX_JERK is
/// MAX_ACCELERATION / JERK_TIME; default 0.01 s).
[[nodiscard]] Machine read_linuxcnc_ini(const std::filesystem::path& file);
/// By the file's extension: .ini → LinuxCNC, otherwise TOML.
[[nodiscard]] Machine read_machine(const std::filesystem::path& file);
/// The machine as Kontur's TOML (what `kontur machine` prints).
[[nodiscard]] std::string to_toml(const Machine& machine);

}  // namespace kontur
