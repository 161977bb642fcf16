// Circles through three points and conics through five points in space (seed 001, methods.md
// sections 4 and 5) for Python: every field of the seed programs' reports (ARC, SOCADI) and the
// motion tables of both problem types (equal angle steps) and of constant feed.
#include <pybind11/stl.h>

#include <array>
#include <functional>
#include <kontur/error.hpp>
#include <kontur/geometry/circle_through_points.hpp>
#include <kontur/geometry/conic_through_points.hpp>
#include <kontur/geometry/helix_arc.hpp>
#include <kontur/geometry/length.hpp>
#include <kontur/interpolate/arc_motion.hpp>
#include <memory>
#include <string>
#include <vector>

#include "bindings.hpp"
#include "buffer.hpp"

namespace kontur::python {
namespace {

Vec3 point3(const py::buffer& b, const char* what) {
  const DoubleView v(b, 1, what);
  if (v.rows() != 3) throw py::value_error(std::string(what) + ": expected 3 coordinates (x, y, z)");
  return {v(0), v(1), v(2)};
}

py::list vec(const Vec3& p) { return py::cast(std::vector<double>{p.x(), p.y(), p.z()}); }
py::list matrix(const Eigen::Matrix4d& m) {
  py::list rows;
  for (int i = 0; i < 4; ++i) rows.append(py::cast(std::vector<double>{m(i, 0), m(i, 1), m(i, 2), m(i, 3)}));
  return rows;
}
template <std::size_t N>
py::list vecs(const std::array<Vec3, N>& ps) {
  py::list out;
  for (const Vec3& p : ps) out.append(vec(p));
  return out;
}
Vec3 apply(const Eigen::Matrix4d& m, const Vec3& p) { return (m * p.homogeneous()).head<3>(); }

// An arc (circle or conic) with what its motion needs: the curve, its exact length and table, the
// angle the seed's table shows, and the frame of the table's relative coordinates.
class PyArc {
 public:
  PyArc(std::unique_ptr<Curve> curve, double sweep_rad, const Vec3& end_point, std::function<double(double)> table_angle,
        const Eigen::Matrix4d& to_frame)
      : curve_(std::move(curve)),
        table_(std::make_unique<ArcLengthTable>(*curve_)),
        sweep_(sweep_rad),
        end_(end_point),
        table_angle_(std::move(table_angle)),
        to_frame_(to_frame) {}
  py::dict fields;  // the report's fields

  // The seed's mode: `steps` equal steps of the angle; problem 1: omega [rad/s] given, 2: time [s].
  py::tuple angular(int problem, double value, int steps) const {
    const AngularTiming timing = angular_timing(sweep_, table_->length_mm(), static_cast<AngularProblem>(problem), value, steps);
    const AngularStepper stepper(*curve_, timing, end_);
    const SpeedVariation speed = angular_speed_variation(*curve_, timing);
    const int n = stepper.samples();
    std::vector<double> rows;
    rows.reserve(static_cast<std::size_t>(n) * 9);
    for (int i = 0; i < n; ++i) {
      const MotionSample s = stepper.sample(i);
      const Vec3 r = apply(to_frame_, s.point);
      rows.insert(rows.end(), {s.time_s, s.u, table_angle_(s.u), s.point.x(), s.point.y(), s.point.z(), r.x(), r.y(), r.z()});
    }
    py::dict t;
    t["problem_type"] = problem;
    t["sweep"] = timing.sweep_rad;
    t["length"] = timing.length_mm;
    t["omega"] = timing.omega_rad_s;
    t["time"] = timing.time_s;
    t["steps"] = timing.steps;
    t["dt"] = timing.dt_s;
    t["dphi"] = timing.dphi_rad;
    t["mean_speed"] = timing.mean_speed_mm_s;
    t["min_speed"] = speed.min_mm_s;
    t["max_speed"] = speed.max_mm_s;
    t["speed_variation"] = speed.relative_variation();
    return py::make_tuple(t, Buffer::of(std::move(rows), {n, 9}));
  }

  // Kontur's mode: constant feed [mm/min], one setpoint per period [s].
  py::tuple constant_feed(double feed_mm_min, double period_s, long max_samples) const {
    const ConstantFeedStepper stepper(*curve_, *table_, end_, feed_mm_min, period_s, max_samples);
    const long n = stepper.samples();
    std::vector<double> rows(static_cast<std::size_t>(n) * 6);
    {
      py::gil_scoped_release release;
      for (long k = 0; k < n; ++k) {
        const MotionSample s = stepper.sample(k);
        double* r = rows.data() + k * 6;
        r[0] = s.time_s;
        r[1] = s.arc_mm;
        r[2] = s.u;
        r[3] = s.point.x();
        r[4] = s.point.y();
        r[5] = s.point.z();
      }
    }
    py::dict t;
    t["feed"] = stepper.feed_mm_min();
    t["period"] = stepper.period_s();
    t["step"] = stepper.step_mm();
    t["periods"] = n - 1;
    t["time"] = stepper.time_s();
    t["length"] = stepper.length_mm();
    return py::make_tuple(t, Buffer::of(std::move(rows), {static_cast<py::ssize_t>(n), 6}));
  }

  // Points at parameters u [the curve's parameter]: (n, 3).
  Buffer evaluate(const py::buffer& u_values) const {
    const DoubleView u(u_values, 1, "u");
    check_within(u, curve_->u_min(), curve_->u_max(), "u", "the arc's parameter range");
    std::vector<double> out;
    out.reserve(static_cast<std::size_t>(u.rows()) * 3);
    for (py::ssize_t i = 0; i < u.rows(); ++i) {
      const Vec3 p = curve_->point(u(i));
      out.insert(out.end(), {p.x(), p.y(), p.z()});
    }
    return Buffer::of(std::move(out), {u.rows(), 3});
  }

 private:
  std::unique_ptr<Curve> curve_;
  std::unique_ptr<ArcLengthTable> table_;
  double sweep_;
  Vec3 end_;
  std::function<double(double)> table_angle_;
  Eigen::Matrix4d to_frame_;
};

PyArc circle(const py::buffer& p1, const py::buffer& p2, const py::buffer& p3, bool full_circle) {
  const CircleThroughPoints c = circle_through_points(point3(p1, "p1"), point3(p2, "p2"), point3(p3, "p3"),
                                                      full_circle ? CircleMotion::full_circle : CircleMotion::arc);
  const double sweep = c.sweep_rad;
  PyArc arc(std::make_unique<HelixArc>(c.curve()), sweep, c.end_point(), [sweep](double u) { return u * sweep; },
            c.to_relative);
  py::dict& f = arc.fields;
  f["kind"] = "circle";
  f["motion_type"] = full_circle ? 2 : 1;
  f["points"] = vecs(c.points);
  f["centre"] = vec(c.centre);
  f["radius"] = c.radius_mm;
  f["eccentricity"] = 0.0;
  f["p"] = c.radius_mm;
  f["a"] = c.radius_mm;
  f["b"] = c.radius_mm;
  f["normal"] = vec(c.normal);
  f["T"] = matrix(c.to_machine);
  f["T_inverse"] = matrix(c.to_relative);
  f["relative_points"] = vecs(c.relative_points);
  f["theta12"] = c.theta12_rad;
  f["theta13"] = c.theta13_rad;
  f["sweep"] = c.sweep_rad;
  f["length"] = c.length_mm;
  f["end_point"] = vec(c.end_point());
  return arc;
}

PyArc conic(const py::list& points, double plane_tolerance_mm) {
  if (points.size() != 5)
    throw InputError("points-count", "points: expected 5 points r1..r5, got " + std::to_string(points.size()));
  std::array<Vec3, 5> r;
  for (std::size_t j = 0; j < 5; ++j)
    r[j] = point3(points[j].cast<py::buffer>(), ("r" + std::to_string(j + 1)).c_str());
  ConicOptions options;
  options.plane_tolerance_mm = plane_tolerance_mm;
  const ConicThroughPoints k = conic_through_points(r, options);
  const double theta01 = k.focal_angles_rad[0];
  PyArc arc(std::make_unique<ConicArc>(k.curve()), k.theta15_rad, k.points[4],
            [theta01](double u) { return theta01 + u; }, k.machine_to_focal);
  const LengthResult len = gauss_kronrod_length(k.curve());
  py::dict& f = arc.fields;
  f["kind"] = to_string(k.type);
  f["points"] = vecs(k.points);
  f["extent"] = k.extent_mm;
  f["lambda"] = k.lambda;
  f["relative_T"] = matrix(k.relative_to_machine);
  f["relative_T_inverse"] = matrix(k.machine_to_relative);
  f["relative_points"] = vecs(k.relative_points);
  f["plane_distance"] = k.plane_distance_mm;
  f["plane_tolerance"] = k.plane_tolerance_mm;
  f["coefficients"] = py::cast(std::vector<double>(k.coefficients.begin(), k.coefficients.end()));
  f["rotation"] = k.rotation_rad;
  f["rotated_coefficients"] = py::cast(std::vector<double>(k.rotated_coefficients.begin(), k.rotated_coefficients.end()));
  f["eccentricity"] = k.eccentricity;
  f["p"] = k.focal_parameter_mm;
  f["a"] = k.a_mm;
  f["b"] = k.b_mm;
  f["c"] = k.c_mm;
  f["centre"] = vec(k.centre);
  f["vertex"] = vec(k.vertex);
  f["foci"] = vecs(k.foci);
  f["axis_angle"] = k.axis_angle_rad;
  f["branch"] = k.branch;
  f["focus"] = vec(k.focus);
  f["T"] = matrix(k.focal_to_machine);
  f["T_inverse"] = matrix(k.machine_to_focal);
  f["focal_points"] = vecs(k.focal_points);
  f["focal_angles"] = py::cast(std::vector<double>(k.focal_angles_rad.begin(), k.focal_angles_rad.end()));
  f["swept_angles"] = py::cast(std::vector<double>(k.swept_angles_rad.begin(), k.swept_angles_rad.end()));
  f["theta15"] = k.theta15_rad;
  f["sweep"] = k.theta15_rad;
  f["length"] = len.length_mm;
  f["length_error_estimate"] = len.error_estimate_mm;
  f["end_point"] = vec(k.points[4]);
  return arc;
}

}  // namespace

void bind_arcs(py::module_& m) {
  py::class_<PyArc>(m, "Arc", "A circle or conic arc with its motion tables; see kontur.CircleArc, kontur.ConicArc.")
      .def_readonly("fields", &PyArc::fields)
      .def("angular", &PyArc::angular, py::arg("problem"), py::arg("value"), py::arg("steps"))
      .def("constant_feed", &PyArc::constant_feed, py::arg("feed"), py::arg("period"), py::arg("max_samples"))
      .def("evaluate", &PyArc::evaluate, py::arg("u"));
  m.def("circle_through_points", &circle, py::arg("p1"), py::arg("p2"), py::arg("p3"), py::arg("full_circle"));
  m.def("conic_through_points", &conic, py::arg("points"), py::arg("plane_tolerance"));
}

}  // namespace kontur::python
