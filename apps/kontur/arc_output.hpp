#pragma once
// Shared pieces of `kontur arc` and `kontur conic`: parsing points and limits, the options of
// the motion, the step tables (text, CSV, JSON) and number formatting without NaN or "-0".
#include <kontur/interpolate/arc_motion.hpp>
#include <kontur/geometry/curve.hpp>
#include <kontur/machine_limits.hpp>

#include <CLI/CLI.hpp>
#include <Eigen/Core>
#include <nlohmann/json.hpp>

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

/// Constant-feed samples: text, CSV, JSON.
void print_feed_table(const ConstantFeedStepper& feed, const std::vector<MotionSample>& samples);
void print_feed_csv(const std::vector<MotionSample>& samples);
[[nodiscard]] nlohmann::ordered_json feed_json(const ConstantFeedStepper& feed, const std::vector<MotionSample>& samples);

}  // namespace kontur::app
