// `kontur arc P1 P2 P3 (--omega W | --time T) --steps N`: the circle through three points and
// the motion along it, with the report of the seed's program ARC (methods.md section 4), and
// Kontur's constant-feed mode (--feed F --period T).
#include "arc_output.hpp"
#include "commands.hpp"
#include "report_output.hpp"

#include <kontur/interpolate/arc_motion.hpp>
#include <kontur/geometry/circle_through_points.hpp>
#include <kontur/error.hpp>
#include <kontur/geometry/length.hpp>

#include <fmt/format.h>

#include <cmath>
#include <memory>
#include <numbers>

namespace kontur::app {
namespace {

struct ArcOptions {
  std::array<std::string, 3> p;
  bool full = false;
  ArcMotionOptions motion;
  std::string report;
};

void run_arc(const ArcOptions& o) {
  validate_motion_options(o.motion);
  const auto limits = parse_limits(o.motion.limits);
  const auto [r1, r2, r3] = given_points(o.p, limits);
  const CircleThroughPoints c =
      circle_through_points(r1, r2, r3, o.full ? CircleMotion::full_circle : CircleMotion::arc);
  const HelixArc arc = c.curve();

  // Everything is computed and checked before anything is printed.
  const ArcMotion motion(
      arc, c.sweep_rad, c.length_mm, c.end_point(), o.motion, [&](double u) { return u * c.sweep_rad; },
      c.to_relative, limits);
  const auto& timing = motion.timing;
  const char* seen_from_z = seen_from_plus_z(c.normal);

  if (!o.report.empty()) {
    report::Report rep;
    rep.title = "kontur arc: circle through three points";
    rep.subtitle = invocation();
    rep.summary = {{"given points [mm]", fmt::format("r1 = {}, r2 = {}, r3 = {}", point_text(r1), point_text(r2),
                                                     point_text(r3))},
                   {"motion type", o.full ? "2: full circle from r1 through r2, r3 back to r1" : "1: arc from r1 through r2 to r3"},
                   {"centre r0", point_text(c.centre) + " mm"},
                   {"radius R", num(c.radius_mm) + " mm"},
                   {"plane normal n", point_text(c.normal)},
                   {"arc angle theta", angle_text(c.sweep_rad)},
                   {"length l = R theta", num(c.length_mm) + " mm"},
                   {"direction", fmt::format("counter-clockwise about n ({} seen from +z)", seen_from_z)}};
    if (timing) {
      add_problem_summary(rep, o.motion, *timing, "theta");
      rep.summary.push_back({"speed V = l / t", num(timing->mean_speed_mm_s) + " mm/s"});
      rep.summary.push_back({"dt, dphi", fmt::format("{} s, {}", num(timing->dt_s), angle_text(timing->dphi_rad))});
    }
    add_feed_and_limits_summary(rep, motion, limits);
    rep.scene_title = "Path: the arc, the given points, the centre and the relative frame (x' towards r1, z' along n)";
    add_arc_motion(rep, arc, motion, "phi", "relative");
    rep.polylines.push_back(labelled_points("given points r1, r2, r3", {r1, r2, r3}, {"r1", "r2", "r3"}, "#000000", 8.0));
    rep.polylines.push_back(labelled_points("centre r0", {c.centre}, {"r0"}, "#8c564b", 8.0));
    add_frame_axes(rep, "relative frame", c.to_machine, 0.4 * c.radius_mm);
    report::write_html_report(rep, o.report);
    if (o.report == "-") return;
  }
  if (o.motion.csv) {
    print_motion_csv(motion);
    return;
  }
  if (o.motion.json) {
    nlohmann::ordered_json j;
    j["points_mm"] = {point_json(r1), point_json(r2), point_json(r3)};
    j["motion_type"] = o.full ? 2 : 1;
    j["centre_mm"] = point_json(c.centre);
    j["radius_mm"] = c.radius_mm;
    j["normal"] = point_json(c.normal);
    j["T"] = matrix_json(c.to_machine);
    j["T_inverse"] = matrix_json(c.to_relative);
    j["relative_points_mm"] = {point_json(c.relative_points[0]), point_json(c.relative_points[1]),
                               point_json(c.relative_points[2])};
    j["theta12_rad"] = c.theta12_rad;
    j["theta13_rad"] = c.theta13_rad;
    j["sweep_rad"] = c.sweep_rad;
    j["direction"] = "counter-clockwise about the normal";
    j["seen_from_plus_z"] = seen_from_z;
    j["length_mm"] = c.length_mm;
    add_motion_json(j, o.motion, motion, {{"speed_mm_s", timing ? timing->mean_speed_mm_s : 0.0}});
    fmt::print("{}\n", j.dump(2));
    return;
  }

  fmt::print("kontur arc: circle through three points (the seed's program ARC)\n");
  fmt::print("input [mm]\n  r1 = {}\n  r2 = {}\n  r3 = {}\n", point_text(r1), point_text(r2), point_text(r3));
  fmt::print("motion type {}: {}\n", o.full ? 2 : 1,
             o.full ? "full circle from r1 through r2, r3 back to r1" : "arc from r1 through r2 to r3");
  if (limits) fmt::print("machine limits [mm]: {}\n", limits_text(*limits));
  fmt::print("\ncentre r0 = {} mm, radius R = {} mm\n", point_text(c.centre), num(c.radius_mm));
  fmt::print("plane normal n = {}\n", point_text(c.normal));
  fmt::print("\nT (relative -> machine, homogeneous):\n{}", matrix_text(c.to_machine));
  fmt::print("T^-1 (machine -> relative):\n{}", matrix_text(c.to_relative));
  fmt::print("\nrelative coordinates [mm] (origin r0, x' towards r1, z' along n)\n");
  for (std::size_t j = 0; j < 3; ++j) fmt::print("  r{} = {}\n", j + 1, point_fixed(c.relative_points[j]));
  fmt::print("\n|r0 rj| = R; cos theta12 = {}, cos theta13 = {}\n", fixed(std::cos(c.theta12_rad), 10),
             fixed(std::cos(c.theta13_rad), 10));
  fmt::print("angles: theta12 = {}, theta13 = {}\n", angle_text(c.theta12_rad), angle_text(c.theta13_rad));
  fmt::print("direction: counter-clockwise about n ({} seen from +z)\n", seen_from_z);
  fmt::print("arc angle theta = {}, length l = R theta = {} mm\n", angle_text(c.sweep_rad), num(c.length_mm));
  if (timing) {
    print_timing(o.motion, *timing, "theta", "l", "");
    print_angular_table(motion.rows, "phi", "relative");
  }
  if (motion.feed) print_feed_table(*motion.feed, motion.feed_samples);
}

}  // namespace

void register_arc_command(CLI::App& app, int& exit_code) {
  auto opts = std::make_shared<ArcOptions>();
  CLI::App* cmd = app.add_subcommand(
      "arc", "Circle through three points in space (the seed's program ARC): centre, frames, angles, and the motion "
             "from P1 through P2 to P3 in N equal angle steps, or at a constant feed.");
  cmd->add_option("P1", opts->p[0], "start point x,y,z [mm]")->required();
  cmd->add_option("P2", opts->p[1], "intermediate point x,y,z [mm]")->required();
  cmd->add_option("P3", opts->p[2], "end point x,y,z [mm]")->required();
  cmd->add_flag("--full", opts->full, "motion type 2: the full circle from P1 through P2, P3 back to P1");
  add_motion_options(cmd, opts->motion);
  add_report_option(cmd, opts->report);
  cmd->footer("Example:\n  kontur arc 110,100,50 100,110,50 90,100,50 --omega 0.5 --steps 4\n"
              "  kontur arc 110,100,50 100,110,50 90,100,50 --omega 0.5 --steps 4 --report arc.html\n"
              "  kontur arc 100,200,300 200,250,310 260,180,400 --feed 600 --period 0.001 --csv\n"
              "Exit codes: 0 success, 1 invalid input (points, values, limits), 2 wrong command line.");
  cmd->callback([opts, &exit_code]() {
    run_arc(*opts);
    exit_code = exit_ok;
  });
}

}  // namespace kontur::app
