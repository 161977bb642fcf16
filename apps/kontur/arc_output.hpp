#pragma once
// Shared pieces of `kontur arc` and `kontur conic`: parsing points and limits, the options of
// the motion, the motion itself (equal angle steps, constant feed), the step tables (text, CSV,
// JSON) and number formatting without NaN or "-0".
#include <kontur/interpolate/arc_motion.hpp>
#include <kontur/geometry/curve.hpp>
#include <kontur/geometry/length.hpp>
#include <kontur/machine_limits.hpp>

#include <CLI/CLI.hpp>
#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include <array>
#include <cstddef>
#include <functional>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

namespace kontur::app {

/// Options common to both commands.
struct ArcMotionOptions {
  std::optional<double> omega;   ///< --omega [rad/s]
  std::optional<double> time;    ///< --time [s]
  std::optional<int> steps;      ///< --steps N
  std::optional<double> feed;    ///< --feed [mm/min]
  std::optional<double> period;  ///< --period [s]
  std::string limits;            ///< --limits xmin,ymin,zmin,xmax,ymax,zmax [mm]
  bool json = false;
  bool csv = false;
};

/// Adds --omega, --time, --steps, --feed, --period, --limits, --json, --csv to cmd.
void add_motion_options(CLI::App* cmd, ArcMotionOptions& o);

/// Parses "x,y,z" [mm]; throws InputError "point-format" naming the point.
[[nodiscard]] Vec3 parse_point(const std::string& text, const std::string& name);
/// Parses --limits (empty: no limits); throws InputError "limits-format" or "limits-invalid".
[[nodiscard]] std::optional<MachineLimits> parse_limits(const std::string& text);
/// "xmin,ymin,zmin .. xmax,ymax,zmax" of the limits, as point_text.
[[nodiscard]] std::string limits_text(const MachineLimits& limits);

/// Parses the given points P1 .. PN and checks them (as r1 .. rN) against the limits, if any.
template <std::size_t N>
[[nodiscard]] std::array<Vec3, N> given_points(const std::array<std::string, N>& texts,
                                               const std::optional<MachineLimits>& limits) {
  std::array<Vec3, N> r;
  for (std::size_t j = 0; j < N; ++j) r[j] = parse_point(texts[j], "P" + std::to_string(j + 1));
  if (limits)
    for (std::size_t j = 0; j < N; ++j) check_inside_limits(*limits, r[j], "r" + std::to_string(j + 1));
  return r;
}

/// Checks the combination of motion options (one of --omega / --time with --steps, or --feed
/// with --period, or both) and their values; throws InputError.
void validate_motion_options(const ArcMotionOptions& o);

/// The seed's problem type and its value from the options (the options must have one).
[[nodiscard]] AngularProblem problem_of(const ArcMotionOptions& o);
[[nodiscard]] double problem_value(const ArcMotionOptions& o);

/// Checks that the samples and `dense` points along the curve lie inside the limits.
void check_path_inside(const MachineLimits& limits, const Curve& curve, const std::vector<MotionSample>& samples,
                       const char* what);

/// Number with `digits` significant digits, never "-0", never NaN.
[[nodiscard]] std::string num(double v, int digits = 10);
/// Fixed-point number with `decimals` decimals, never "-0.000".
[[nodiscard]] std::string fixed(double v, int decimals = 6);
/// "(x, y, z)" with num().
[[nodiscard]] std::string point_text(const Vec3& p, int digits = 10);
/// "(x, y, z)" with fixed(v, 9).
[[nodiscard]] std::string point_fixed(const Vec3& p);
/// A 4x4 homogeneous matrix, one row per line, indented.
[[nodiscard]] std::string matrix_text(const Eigen::Matrix4d& m);
/// JSON array of a point / a 4x4 matrix (rows).
[[nodiscard]] nlohmann::ordered_json point_json(const Vec3& p);
[[nodiscard]] nlohmann::ordered_json matrix_json(const Eigen::Matrix4d& m);

/// Applies a homogeneous matrix to a point.
[[nodiscard]] Vec3 apply(const Eigen::Matrix4d& m, const Vec3& p);

/// Degrees per radian.
inline constexpr double deg_per_rad = 180.0 / std::numbers::pi;
/// "a rad (b deg)".
[[nodiscard]] std::string angle_text(double rad);
/// The sense of a motion counter-clockwise about `normal` seen from +z: "counter-clockwise",
/// "clockwise" or "edge-on".
[[nodiscard]] const char* seen_from_plus_z(const Vec3& normal);

/// Rows of the angular table: sample, angle [rad] of the table (central or focal), and the point
/// in the relative frame.
struct AngularRow {
  MotionSample sample;
  double angle_rad = 0.0;
  Vec3 relative = Vec3::Zero();
};

/// Prints the angular step table (text), the columns named after the relative frame.
void print_angular_table(const std::vector<AngularRow>& rows, const char* angle_name, const char* frame_name);
/// CSV of the angular step table.
void print_angular_csv(const std::vector<AngularRow>& rows);
/// JSON of the angular step table.
[[nodiscard]] nlohmann::ordered_json angular_json(const std::vector<AngularRow>& rows);

/// The motion along an arc or a conic, computed and checked before anything is printed: the seed's
/// equal angle steps (with --omega or --time) and Kontur's constant feed (with --feed). Not
/// copyable: the constant-feed stepper refers to the curve and to the arc-length table.
struct ArcMotion {
  /// `sweep_rad` [rad]: the angle the seed's equal steps divide; `length_mm`: the curve's length;
  /// `end_point`: its exact end; `table_angle(u)`: the angle [rad] the step table shows at the
  /// angular stepper's u; `to_frame`: machine -> the frame of the table. Throws InputError for a
  /// step or a period outside the limits.
  ArcMotion(const Curve& curve, double sweep_rad, double length_mm, const Vec3& end_point, const ArcMotionOptions& o,
            const std::function<double(double)>& table_angle, const Eigen::Matrix4d& to_frame,
            const std::optional<MachineLimits>& limits);
  ArcMotion(const ArcMotion&) = delete;
  ArcMotion& operator=(const ArcMotion&) = delete;

  std::optional<AngularTiming> timing;     ///< the angular mode (--omega or --time)
  std::vector<AngularRow> rows;            ///< its step table
  ArcLengthTable table;                    ///< arc length of the curve
  std::optional<ConstantFeedStepper> feed; ///< the constant-feed mode (--feed)
  std::vector<MotionSample> feed_samples;  ///< its samples
};

/// "omega given, t = ANGLE / omega" or "t given, omega = ANGLE / t".
[[nodiscard]] std::string problem_text(const ArcMotionOptions& o, const char* angle);
/// The text of the angular mode's timing: problem type, omega, t, N, V = LENGTH / t [mm/s] (with
/// `mean_note` after it), dt, dphi.
void print_timing(const ArcMotionOptions& o, const AngularTiming& timing, const char* angle, const char* length,
                  const char* mean_note);
/// The CSV of the motion: the angular step table, else the constant-feed samples.
void print_motion_csv(const ArcMotion& m);
/// The motion's JSON fields: problem_type, omega_rad_s, time_s, steps, then `speed_fields`, dt_s,
/// dphi_rad and the table (angular mode), and constant_feed.
void add_motion_json(nlohmann::ordered_json& j, const ArcMotionOptions& o, const ArcMotion& m,
                     const nlohmann::ordered_json& speed_fields);

/// Constant-feed samples: text, CSV, JSON.
void print_feed_table(const ConstantFeedStepper& feed, const std::vector<MotionSample>& samples);
void print_feed_csv(const std::vector<MotionSample>& samples);
[[nodiscard]] nlohmann::ordered_json feed_json(const ConstantFeedStepper& feed, const std::vector<MotionSample>& samples);

}  // namespace kontur::app
