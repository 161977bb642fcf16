// NURBS curves for Python: evaluation (vectorised), length (Kontur's default and the seed's
// Simpson-Runge with its table), u(s), span polynomials and forward differences (seed 002).
#include <pybind11/stl.h>

#include <cmath>
#include <kontur/error.hpp>
#include <kontur/geometry/length.hpp>
#include <kontur/geometry/nurbs.hpp>
#include <kontur/geometry/span_polynomial.hpp>
#include <kontur/interpolate/curve_interpolator.hpp>
#include <kontur/interpolate/forward_difference.hpp>
#include <kontur/io/curve_json.hpp>
#include <memory>
#include <string>
#include <vector>

#include "bindings.hpp"
#include "buffer.hpp"

namespace kontur::python {
namespace {

// A curve with its arc-length table, built on first use (the table keeps a reference to the
// curve: both live here, never moved).
class PyNurbs {
 public:
  explicit PyNurbs(NurbsCurve curve) : curve_(std::make_unique<NurbsCurve>(std::move(curve))) {}
  [[nodiscard]] const NurbsCurve& curve() const noexcept { return *curve_; }
  const ArcLengthTable& table() {
    if (!table_) table_ = std::make_unique<ArcLengthTable>(*curve_);
    return *table_;
  }

 private:
  std::unique_ptr<NurbsCurve> curve_;
  std::unique_ptr<ArcLengthTable> table_;
};

NurbsData make_data(int degree, std::vector<double> knots, const py::buffer& points, std::vector<double> weights) {
  const DoubleView p(points, 2, "points");
  if (p.cols() != 3) throw py::value_error("points: expected 3 columns (x, y, z)");
  NurbsData d;
  d.degree = degree;
  d.knots = std::move(knots);
  d.points.reserve(static_cast<std::size_t>(p.rows()));
  for (py::ssize_t i = 0; i < p.rows(); ++i) d.points.emplace_back(p(i, 0), p(i, 1), p(i, 2));
  d.weights = std::move(weights);
  return d;
}

Buffer evaluate(const PyNurbs& self, const py::buffer& u_values, int order, int dim) {
  if (order < 0 || order > 3)
    throw InputError("derivatives-range", "derivatives = " + std::to_string(order) + ": expected 0, 1, 2 or 3");
  const DoubleView u(u_values, 1, "u");
  const NurbsCurve& c = self.curve();
  check_within(u, c.u_min(), c.u_max(), "u", "the curve's parameter range");
  const py::ssize_t n = u.rows();
  const int per = (order + 1) * dim;
  std::vector<double> out(static_cast<std::size_t>(n) * static_cast<std::size_t>(per));
  {
    py::gil_scoped_release release;
    double* o = out.data();
    for (py::ssize_t i = 0; i < n; ++i) {
      const Derivatives d = c.derivatives(u(i), order);
      for (int k = 0; k <= order; ++k)
        for (int a = 0; a < dim; ++a) *o++ = d[k][a];
    }
  }
  if (order == 0) return Buffer::of(std::move(out), {n, dim});
  return Buffer::of(std::move(out), {n, order + 1, dim});
}

py::dict length_result(const LengthResult& r) {
  py::dict d;
  d["length"] = r.length_mm;
  d["error_estimate"] = r.error_estimate_mm;
  d["evaluations"] = r.evaluations;
  d["converged"] = r.converged;
  py::list history;
  for (const auto& [n, l] : r.history) history.append(py::make_tuple(n, l));
  d["history"] = history;
  return d;
}

Interpolator interpolator_of(const std::string& name) {
  if (name == "exact") return Interpolator::arc_length_exact;
  if (name == "taylor1") return Interpolator::taylor_first_order;
  if (name == "taylor2") return Interpolator::taylor_second_order;
  throw InputError("interpolator-name",
                   "interpolator = '" + name + "': expected 'exact', 'taylor1' or 'taylor2'");
}

void check_feed(double feed_mm_min, double period_s) {
  if (!(feed_mm_min > 0.0) || !std::isfinite(feed_mm_min))
    throw InputError("feed-positive", "feed = " + format_number(feed_mm_min) + ": expected a finite feed > 0 [mm/min]");
  if (!(period_s > 0.0) || !std::isfinite(period_s))
    throw InputError("period-positive", "period = " + format_number(period_s) + ": expected a finite period > 0 [s]");
}

}  // namespace

void bind_curves(py::module_& m) {
  py::class_<PyNurbs>(m, "NurbsCurve", "A validated NURBS curve (the library's kontur::NurbsCurve); see kontur.NurbsCurve.")
      .def(py::init([](int degree, std::vector<double> knots, const py::buffer& points, std::vector<double> weights) {
             return PyNurbs(NurbsCurve(make_data(degree, std::move(knots), points, std::move(weights))));
           }),
           py::arg("degree"), py::arg("knots"), py::arg("points"), py::arg("weights"))
      .def_property_readonly("degree", [](const PyNurbs& s) { return s.curve().degree(); })
      .def_property_readonly("knots", [](const PyNurbs& s) { return s.curve().knots(); })
      .def_property_readonly("points",
                             [](const PyNurbs& s) {
                               std::vector<double> v;
                               for (const Vec3& p : s.curve().points()) v.insert(v.end(), {p.x(), p.y(), p.z()});
                               const auto n = static_cast<py::ssize_t>(s.curve().points().size());
                               return Buffer::of(std::move(v), {n, 3});
                             })
      .def_property_readonly("weights", [](const PyNurbs& s) { return s.curve().weights(); })
      .def_property_readonly("rational", [](const PyNurbs& s) { return s.curve().rational(); })
      .def_property_readonly("u_min", [](const PyNurbs& s) { return s.curve().u_min(); })
      .def_property_readonly("u_max", [](const PyNurbs& s) { return s.curve().u_max(); })
      .def_property_readonly("breakpoints", [](const PyNurbs& s) { return s.curve().breakpoints(); })
      .def("evaluate", &evaluate, py::arg("u"), py::arg("order"), py::arg("dim"))
      .def(
          "length",
          [](const PyNurbs& s, double tolerance) {
            check_relative_tolerance(tolerance);
            LengthResult r;
            {
              py::gil_scoped_release release;
              r = gauss_kronrod_length(s.curve(), tolerance);
            }
            return length_result(r);
          },
          py::arg("tolerance"))
      .def(
          "length_simpson",
          [](const PyNurbs& s, const std::string& scheme, double tolerance, int max_halvings) {
            if (scheme != "whole_curve" && scheme != "per_span")
              throw InputError("scheme-name", "scheme = '" + scheme + "': expected 'whole_curve' or 'per_span'");
            check_relative_tolerance(tolerance);
            if (max_halvings < 1 || max_halvings > 40)
              throw InputError("halvings-range",
                               "max_halvings = " + std::to_string(max_halvings) + ": expected 1 to 40");
            LengthResult r;
            {
              py::gil_scoped_release release;
              r = simpson_runge_length(s.curve(),
                                       scheme == "per_span" ? SimpsonScheme::per_span : SimpsonScheme::whole_curve,
                                       tolerance, max_halvings);
            }
            return length_result(r);
          },
          py::arg("scheme"), py::arg("tolerance"), py::arg("max_halvings"))
      .def(
          "u_of_s",
          [](PyNurbs& s, const py::buffer& s_values) {
            const DoubleView sv(s_values, 1, "s");
            const ArcLengthTable& t = s.table();
            check_within(sv, 0.0, t.length_mm(), "s", "the curve's length");
            return map_values(sv, [&](double x) { return t.u_of_s(x); });
          },
          py::arg("s"))
      .def(
          "s_of_u",
          [](PyNurbs& s, const py::buffer& u_values) {
            const DoubleView uv(u_values, 1, "u");
            check_within(uv, s.curve().u_min(), s.curve().u_max(), "u", "the curve's parameter range");
            const ArcLengthTable& t = s.table();
            return map_values(uv, [&](double x) { return t.s_of_u(x); });
          },
          py::arg("u"))
      .def(
          "span_polynomials",
          [](const PyNurbs& s, bool global) {
            const SpanPolynomialCurve spans(s.curve());
            py::list out;
            for (const SpanPolynomial& sp : spans.spans()) {
              const int p = sp.degree;
              std::vector<double> c;
              c.reserve(static_cast<std::size_t>(4 * (p + 1)));
              for (int axis = 0; axis < 4; ++axis) {
                const PolyCoeffs k = sp.coefficients(axis, global ? 0.0 : sp.u_start);
                c.insert(c.end(), k.begin(), k.begin() + p + 1);
              }
              py::dict d;
              d["u_start"] = sp.u_start;
              d["u_end"] = sp.u_end;
              d["knot_index"] = sp.knot_index;
              d["degree"] = p;
              d["rational"] = sp.rational;
              d["coefficients"] = Buffer::of(std::move(c), {4, p + 1});
              out.append(d);
            }
            return out;
          },
          py::arg("global_parameter"))
      .def(
          "forward_differences",
          [](const PyNurbs& s, double step, bool compensated, int dim, long max_steps) {
            if (!(step > 0.0) || !std::isfinite(step))
              throw InputError("step-positive", "step = " + format_number(step) + ": expected a finite step > 0");
            const double range = s.curve().u_max() - s.curve().u_min();
            if (range / step > static_cast<double>(max_steps))
              throw InputError("too-many-steps", "step = " + format_number(step) + ": " + format_number(range / step) +
                                                     " steps over the parameter range, more than max_steps = " +
                                                     std::to_string(max_steps));
            const SpanPolynomialCurve spans(s.curve());
            ForwardDifferenceStepper st(spans, step, compensated ? Summation::compensated : Summation::plain);
            const long n = st.cycles() + 1;
            std::vector<double> u(static_cast<std::size_t>(n)), pts(static_cast<std::size_t>(n * dim));
            std::vector<std::int64_t> span(static_cast<std::size_t>(n));
            {
              py::gil_scoped_release release;
              long i = 0;
              do {
                u[static_cast<std::size_t>(i)] = st.u();
                span[static_cast<std::size_t>(i)] = static_cast<std::int64_t>(st.span());
                const Vec3 p = st.point();
                for (int a = 0; a < dim; ++a) pts[static_cast<std::size_t>(i * dim + a)] = p[a];
                ++i;
              } while (i < n && st.step());
            }
            return py::make_tuple(Buffer::of(std::move(u), {n}), Buffer::of(std::move(pts), {n, dim}),
                                  Buffer::of(std::move(span), {n}));
          },
          py::arg("step"), py::arg("compensated"), py::arg("dim"), py::arg("max_steps"))
      .def(
          "interpolate",
          [](const PyNurbs& s, double feed_mm_min, double period_s, const std::string& kind, int dim, long max_steps) {
            check_feed(feed_mm_min, period_s);
            const Interpolator k = interpolator_of(kind);
            const double ds = feed_mm_min / 60.0 * period_s;
            CurveInterpolator ip(s.curve(), k);
            std::vector<double> u{ip.u()}, sv{0.0}, pts;
            const Vec3 p0 = ip.point();
            pts.insert(pts.end(), p0.data(), p0.data() + dim);
            {
              py::gil_scoped_release release;
              while (!ip.at_end()) {
                if (static_cast<long>(u.size()) > max_steps) break;
                ip.advance(ds);
                u.push_back(ip.u());
                sv.push_back(ip.s_mm());
                const Vec3 p = ip.point();
                pts.insert(pts.end(), p.data(), p.data() + dim);
              }
            }
            if (!ip.at_end())
              throw InputError("too-many-steps", "feed = " + format_number(feed_mm_min) + " mm/min, period = " +
                                                     format_number(period_s) + " s: more than max_steps = " +
                                                     std::to_string(max_steps) + " setpoints");
            const auto n = static_cast<py::ssize_t>(u.size());
            return py::make_tuple(Buffer::of(std::move(u), {n}), Buffer::of(std::move(sv), {n}),
                                  Buffer::of(std::move(pts), {n, dim}));
          },
          py::arg("feed"), py::arg("period"), py::arg("interpolator"), py::arg("dim"), py::arg("max_steps"))
      .def(
          "feed_fluctuation",
          [](const PyNurbs& s, double feed_mm_min, double period_s, const std::string& kind) {
            check_feed(feed_mm_min, period_s);
            const Interpolator k = interpolator_of(kind);
            FeedFluctuation f;
            {
              py::gil_scoped_release release;
              f = measure_feed_fluctuation(s.curve(), k, feed_mm_min / 60.0, period_s);
            }
            py::dict d;
            d["cycles"] = f.cycles;
            d["max_relative"] = f.max_relative;
            d["mean_relative"] = f.mean_relative;
            d["max_chord_error"] = f.max_chord_error_mm;
            d["final_gap"] = f.final_gap_mm;
            return d;
          },
          py::arg("feed"), py::arg("period"), py::arg("interpolator"));

  m.def(
      "read_curve",
      [](const std::string& path) {
        const NurbsCurve c = read_curve_json(path);
        return PyNurbs(c);
      },
      py::arg("path"));
}

}  // namespace kontur::python
