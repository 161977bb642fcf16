// `kontur conic P1 P2 P3 P4 P5 (--omega W | --time T) --steps N`: the conic through five points
// and the motion along it, with the report of the seed's program SOCADI (methods.md section 5),
// the arc length by quadrature, and Kontur's constant-feed mode (--feed F --period T).
#include "arc_output.hpp"
#include "commands.hpp"
#include "report_output.hpp"

#include <kontur/interpolate/arc_motion.hpp>
#include <kontur/geometry/conic_through_points.hpp>
#include <kontur/error.hpp>
#include <kontur/geometry/length.hpp>

#include <fmt/format.h>

#include <cmath>
#include <memory>
#include <numbers>

namespace kontur::app {
namespace {

struct ConicCommandOptions {
  std::array<std::string, 5> p;
  double plane_tolerance_mm = 0.0;
  ArcMotionOptions motion;
  std::string report;
};

void run_conic(const ConicCommandOptions& o) {
  validate_motion_options(o.motion);
  const auto limits = parse_limits(o.motion.limits);
  const std::array<Vec3, 5> r = given_points(o.p, limits);
  ConicOptions options;
  options.plane_tolerance_mm = o.plane_tolerance_mm;
  const ConicThroughPoints k = conic_through_points(r, options);
  const ConicArc arc = k.curve();
  const LengthResult len = gauss_kronrod_length(arc);

  // Everything is computed and checked before anything is printed.
  const ArcMotion motion(
      arc, k.theta15_rad, len.length_mm, r[4], o.motion,
      [&](double u) { return k.focal_angles_rad[0] + u; },  // focal angle theta01 + phi_i
      k.machine_to_focal, limits);
  const auto& timing = motion.timing;
  std::optional<SpeedVariation> speeds;
  if (timing) speeds = angular_speed_variation(arc, *timing);
  const Vec3 normal = k.focal_to_machine.block<3, 1>(0, 2);
  const char* seen_from_z = seen_from_plus_z(normal);
  const bool has_axes = k.type == ConicType::ellipse || k.type == ConicType::hyperbola || k.type == ConicType::circle;

  if (!o.report.empty()) {
    report::Report rep;
    rep.title = fmt::format("kontur conic: arc of a conic through five points ({})", to_string(k.type));
    rep.subtitle = invocation();
    std::string given;
    for (std::size_t j = 0; j < 5; ++j) given += fmt::format("{}r{} = {}", j ? ", " : "", j + 1, point_text(r[j]));
    rep.summary = {{"given points [mm]", given},
                   {"type", to_string(k.type)},
                   {"eccentricity e", num(k.eccentricity)},
                   {"focal parameter p", num(k.focal_parameter_mm) + " mm"}};
    if (has_axes) {
      rep.summary.push_back({"semi-axes a, b; focal distance c", fmt::format("{} mm, {} mm; {} mm", num(k.a_mm), num(k.b_mm), num(k.c_mm))});
      rep.summary.push_back({"centre", point_text(k.centre) + " mm"});
    }
    rep.summary.push_back({"vertex", point_text(k.vertex) + " mm"});
    rep.summary.push_back({"foci", fmt::format("{} and {} mm", point_text(k.foci[0]), point_text(k.foci[1]))});
    rep.summary.push_back({"focal frame origin (focus used)", point_text(k.focus) + " mm"});
    rep.summary.push_back({"polar equation", fmt::format("rho = {} / (1 - {} cos phi) [mm]", num(k.focal_parameter_mm), num(k.eccentricity))});
    rep.summary.push_back({"swept focal angle theta15", angle_text(k.theta15_rad)});
    rep.summary.push_back({"arc length l15", fmt::format("{} mm (Gauss-Kronrod, error estimate {:.2g} mm)", num(len.length_mm, 13), len.error_estimate_mm)});
    rep.summary.push_back({"direction", fmt::format("counter-clockwise about the normal ({} seen from +z)", seen_from_z)});
    rep.summary.push_back({"plane distance of r4, r5", fmt::format("{} mm (tolerance {} mm)", num(k.plane_distance_mm, 3), num(k.plane_tolerance_mm, 3))});
    if (timing) {
      add_problem_summary(rep, o.motion, *timing, "theta15");
      rep.summary.push_back({"path speed", fmt::format("mean {} mm/s, from {} to {} mm/s", num(timing->mean_speed_mm_s),
                                                        num(speeds->min_mm_s, 7), num(speeds->max_mm_s, 7))});
    }
    add_feed_and_limits_summary(rep, motion, limits);
    rep.scene_title = "Path: the conic arc, the given points, the foci (and centre) and the focal frame (origin the focus, z' the normal)";
    add_arc_motion(rep, arc, motion, "theta", "focal");
    rep.polylines.push_back(labelled_points("given points r1..r5", {r.begin(), r.end()}, {"r1", "r2", "r3", "r4", "r5"}, "#000000", 8.0));
    if (k.type == ConicType::ellipse || k.type == ConicType::hyperbola)
      rep.polylines.push_back(labelled_points("foci", {k.foci[0], k.foci[1]}, {"F1", "F2"}, "#8c564b", 8.0));
    else
      rep.polylines.push_back(labelled_points("focus", {k.foci[0]}, {"F"}, "#8c564b", 8.0));
    if (has_axes) rep.polylines.push_back(labelled_points("centre", {k.centre}, {"C"}, "#e377c2", 8.0));
    rep.polylines.push_back(labelled_points("vertex", {k.vertex}, {"V"}, "#17becf", 7.0));
    add_frame_axes(rep, "focal frame", k.focal_to_machine, 0.3 * k.extent_mm);
    report::write_html_report(rep, o.report);
    if (o.report == "-") return;
  }
  if (o.motion.csv) {
    print_motion_csv(motion);
    return;
  }
  if (o.motion.json) {
    nlohmann::ordered_json j;
    auto& pts = j["points_mm"] = nlohmann::ordered_json::array();
    for (const auto& q : r) pts.push_back(point_json(q));
    j["type"] = to_string(k.type);
    j["relative_frame"]["lambda"] = k.lambda;
    j["relative_frame"]["T"] = matrix_json(k.relative_to_machine);
    j["relative_frame"]["T_inverse"] = matrix_json(k.machine_to_relative);
    j["plane_distance_mm"] = k.plane_distance_mm;
    j["plane_tolerance_mm"] = k.plane_tolerance_mm;
    j["coefficients_ABCDE"] = std::vector<double>(k.coefficients.begin(), k.coefficients.end());
    j["rotation_rad"] = k.rotation_rad;
    j["rotated_coefficients_ACDE"] = std::vector<double>(k.rotated_coefficients.begin(), k.rotated_coefficients.end());
    j["eccentricity"] = k.eccentricity;
    j["focal_parameter_mm"] = k.focal_parameter_mm;
    if (has_axes) {
      j["a_mm"] = k.a_mm;
      j["b_mm"] = k.b_mm;
      j["c_mm"] = k.c_mm;
      j["centre_mm"] = point_json(k.centre);
    }
    j["vertex_mm"] = point_json(k.vertex);
    j["foci_mm"] = {point_json(k.foci[0]), point_json(k.foci[1])};
    j["axis_angle_rad"] = k.axis_angle_rad;
    if (k.type == ConicType::hyperbola) j["branch"] = k.branch;
    j["focus_mm"] = point_json(k.focus);
    j["T"] = matrix_json(k.focal_to_machine);
    j["T_inverse"] = matrix_json(k.machine_to_focal);
    auto& fp = j["focal_points_mm"] = nlohmann::ordered_json::array();
    for (const auto& q : k.focal_points) fp.push_back(point_json(q));
    j["focal_angles_rad"] = std::vector<double>(k.focal_angles_rad.begin(), k.focal_angles_rad.end());
    j["swept_angles_rad"] = std::vector<double>(k.swept_angles_rad.begin(), k.swept_angles_rad.end());
    j["theta15_rad"] = k.theta15_rad;
    j["direction"] = "counter-clockwise about the normal";
    j["seen_from_plus_z"] = seen_from_z;
    j["length_mm"] = len.length_mm;
    j["length_error_estimate_mm"] = len.error_estimate_mm;
    nlohmann::ordered_json speed_fields;
    if (timing)
      speed_fields = {{"mean_speed_mm_s", timing->mean_speed_mm_s},
                      {"min_speed_mm_s", speeds->min_mm_s},
                      {"max_speed_mm_s", speeds->max_mm_s}};
    add_motion_json(j, o.motion, motion, speed_fields);
    fmt::print("{}\n", j.dump(2));
    return;
  }

  fmt::print("kontur conic: arc of a conic through five points (the seed's program SOCADI)\n");
  fmt::print("input [mm]\n");
  for (std::size_t j = 0; j < 5; ++j) fmt::print("  r{} = {}\n", j + 1, point_text(r[j]));
  if (limits) fmt::print("machine limits [mm]: {}\n", limits_text(*limits));
  fmt::print("\nrelative frame: origin r1, x along r2 - r1, lambda = {}; r4, r5 within {} mm of the plane "
             "(tolerance {} mm)\n",
             num(k.lambda), num(k.plane_distance_mm, 3), num(k.plane_tolerance_mm, 3));
  fmt::print("equation A x^2 + B xy + C y^2 + D x + E y = 0 (relative frame, mm): A = {}, B = {}, C = {}, D = {}, E = {}\n",
             num(k.coefficients[0]), num(k.coefficients[1]), num(k.coefficients[2]), num(k.coefficients[3]),
             num(k.coefficients[4]));
  fmt::print("rotation theta = {}: A' = {}, C' = {}, D' = {}, E' = {}\n", angle_text(k.rotation_rad),
             num(k.rotated_coefficients[0]), num(k.rotated_coefficients[1]), num(k.rotated_coefficients[2]),
             num(k.rotated_coefficients[3]));
  fmt::print("\ntype: {}\n", to_string(k.type));
  fmt::print("eccentricity e = {}\nfocal parameter p = {} mm\n", num(k.eccentricity), num(k.focal_parameter_mm));
  if (has_axes) {
    fmt::print("semi-axes a = {} mm, b = {} mm, focal distance c = {} mm\n", num(k.a_mm), num(k.b_mm), num(k.c_mm));
    fmt::print("centre = {} mm\n", point_text(k.centre));
  }
  fmt::print("vertex = {} mm\n", point_text(k.vertex));
  if (k.type == ConicType::ellipse || k.type == ConicType::hyperbola)
    fmt::print("foci = {} and {} mm\n", point_text(k.foci[0]), point_text(k.foci[1]));
  else
    fmt::print("focus = {} mm\n", point_text(k.foci[0]));
  fmt::print("focal axis angle (relative frame) = {}\n", angle_text(k.axis_angle_rad));
  if (k.type == ConicType::hyperbola)
    fmt::print("branch: {} (of the rotated frame), decided by r1\n", k.branch > 0 ? "right/upper" : "left/lower");
  fmt::print("polar equation rho = p / (1 - e cos phi) = {} / (1 - {} cos phi) [mm]\n", num(k.focal_parameter_mm),
             num(k.eccentricity));
  fmt::print("\nfocal frame: origin r0 = focus {} mm, x' away from the near directrix, z' the normal\n",
             point_text(k.focus));
  fmt::print("T (focal -> machine, homogeneous):\n{}", matrix_text(k.focal_to_machine));
  fmt::print("T^-1 (machine -> focal):\n{}", matrix_text(k.machine_to_focal));
  fmt::print("\nfocal coordinates [mm], |r0 rj| [mm], cos theta0j, theta0j, theta1j\n");
  for (std::size_t j = 0; j < 5; ++j) {
    const Vec3& q = k.focal_points[j];
    const double rho = q.head<2>().norm();
    fmt::print("  r{} = {}  |{}|  cos {}  theta0{} = {}  theta1{} = {} deg\n", j + 1, point_fixed(q), num(rho),
               fixed(q.x() / rho, 10), j + 1, angle_text(k.focal_angles_rad[j]), j + 1,
               num(k.swept_angles_rad[j] * deg_per_rad, 10));
  }
  fmt::print("direction: counter-clockwise about the normal ({} seen from +z); points in order along one arc\n",
             seen_from_z);
  fmt::print("swept focal angle theta15 = {}\n", angle_text(k.theta15_rad));
  fmt::print("arc length l15 = {} mm (Gauss-Kronrod, error estimate {:.2g} mm)\n", num(len.length_mm, 13),
             len.error_estimate_mm);
  if (timing) {
    print_timing(o.motion, *timing, "theta15", "l15", " (mean)");
    fmt::print("speed along the path varies from {} to {} mm/s ({} % of the mean): equal focal-angle steps are not "
               "equal path steps\n",
               num(speeds->min_mm_s, 7), num(speeds->max_mm_s, 7), num(100.0 * speeds->relative_variation(), 4));
    print_angular_table(motion.rows, "theta", "focal");
  }
  if (motion.feed) print_feed_table(*motion.feed, motion.feed_samples);
}

}  // namespace

void register_conic_command(CLI::App& app, int& exit_code) {
  auto opts = std::make_shared<ConicCommandOptions>();
  CLI::App* cmd = app.add_subcommand(
      "conic", "Arc of an ellipse, parabola or hyperbola through five points in space (the seed's program SOCADI): "
               "type, parameters, frames, focal angles, length, and the motion from P1 to P5 in N equal focal-angle "
               "steps, or at a constant feed.");
  for (std::size_t j = 0; j < 5; ++j)
    cmd->add_option(fmt::format("P{}", j + 1), opts->p[j],
                    fmt::format("point {} of 5, in order along the arc, x,y,z [mm]", j + 1))
        ->required();
  cmd->add_option("--plane-tolerance", opts->plane_tolerance_mm,
                  "largest distance [mm] of P4, P5 from the plane of P1, P2, P3 (default 1e-9 x the extent)");
  add_motion_options(cmd, opts->motion);
  add_report_option(cmd, opts->report);
  cmd->footer("Example:\n  kontur conic 105,200,300 104,201.08,301.44 103,201.44,301.92 100,201.8,302.4 "
              "96,201.08,301.44 --omega 0.5 --steps 4\n"
              "  kontur conic 105,200,300 104,201.08,301.44 103,201.44,301.92 100,201.8,302.4 "
              "96,201.08,301.44 --omega 0.5 --steps 4 --report conic.html\n"
              "Exit codes: 0 success, 1 invalid input (points, values, limits), 2 wrong command line.");
  cmd->callback([opts, &exit_code]() {
    run_conic(*opts);
    exit_code = exit_ok;
  });
}

}  // namespace kontur::app
