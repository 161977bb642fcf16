#pragma once
// The HTML reports of `kontur spline`, `kontur arc` and `kontur conic` (docs/report.md): the
// pieces they share, built on the library's report model (kontur/report/html_report.hpp).
#include <kontur/interpolate/arc_motion.hpp>
#include <kontur/geometry/curve.hpp>
#include <kontur/report/html_report.hpp>
#include <optional>
#include <string>
#include <vector>

#include "arc_output.hpp"

namespace kontur::app {

/// The command line as typed (set by main), shown under the report's title.
[[nodiscard]] const std::string& invocation();
void set_invocation(int argc, char** argv);

/// Adds `--report FILE` to a subcommand.
void add_report_option(CLI::App* cmd, std::string& path);

/// A marker polyline with one label per point.
[[nodiscard]] report::Polyline labelled_points(const std::string& name, const std::vector<Vec3>& points,
                                               const std::vector<std::string>& labels, const std::string& color,
                                               double size_px = 7.0);

/// The three axes of a frame (homogeneous matrix frame -> machine, columns x', y', z' and the
/// origin) as short lines of length `length_mm`, named "<name> x'" etc.
void add_frame_axes(report::Report& r, const std::string& name, const Eigen::Matrix4d& to_machine, double length_mm);

/// The motion along an arc or a conic: the path coloured by path speed, the steps, the plots of
/// path speed and of each axis's velocity, acceleration and jerk over time, and the step tables
/// with links to the plots. `angular` holds the seed's mode (timing and rows), `feed` Kontur's
/// constant-feed mode; either may be absent. The report refers to feed_samples (its setpoint
/// table is made lazily), which must outlive it.
void add_arc_motion(report::Report& r, const Curve& curve, const std::optional<AngularTiming>& timing,
                    const std::vector<AngularRow>& rows, const char* angle_name, const char* frame_name,
                    const ConstantFeedStepper* feed, const std::vector<MotionSample>& feed_samples);

/// add_arc_motion for the motion of `kontur arc` or `kontur conic` (which must outlive the report).
void add_arc_motion(report::Report& r, const Curve& curve, const ArcMotion& motion, const char* angle_name,
                    const char* frame_name);

/// The summary rows of the angular mode's problem: "problem type" (problem_text with `angle`) and
/// "omega, t, N".
void add_problem_summary(report::Report& r, const ArcMotionOptions& o, const AngularTiming& timing, const char* angle);

/// The summary rows of the constant feed and of the machine limits, where given.
void add_feed_and_limits_summary(report::Report& r, const ArcMotion& motion, const std::optional<MachineLimits>& limits);

}  // namespace kontur::app
