#pragma once
// The parts of the Python module (_core), each binding one area of the library.
#include <fmt/format.h>
#include <pybind11/pybind11.h>

#include <kontur/error.hpp>
#include <string>
#include <utility>
#include <vector>

#include "buffer.hpp"

namespace kontur::python {

namespace py = pybind11;

/// Curves: NurbsCurve, read_curve (bind_curves.cpp).
void bind_curves(py::module_& m);
/// Circles and conics through points, their motion tables (bind_arcs.cpp).
void bind_arcs(py::module_& m);
/// Machines, check, run, run_iter, verify (bind_runs.cpp).
void bind_runs(py::module_& m);

/// A number as in messages: the shortest text that reads back to the same double.
[[nodiscard]] inline std::string format_number(double v) { return fmt::format("{}", v); }

/// Refuses (InputError "parameter-range") any value of `values` outside [lo, hi] or NaN: a clear
/// message, never a silent clamp. `what` names the array, `range` the interval ("the curve's
/// parameter range").
inline void check_within(const DoubleView& values, double lo, double hi, const char* what, const char* range) {
  for (py::ssize_t i = 0; i < values.rows(); ++i)
    if (const double x = values(i); !(x >= lo && x <= hi))
      throw InputError("parameter-range", fmt::format("{}[{}] = {}: outside {} [{}, {}]", what, i, format_number(x),
                                                      range, format_number(lo), format_number(hi)));
}

/// Refuses a relative tolerance outside (0, 1) (InputError "tolerance-range").
inline void check_relative_tolerance(double tolerance) {
  if (!(tolerance > 0.0 && tolerance < 1.0))
    throw InputError("tolerance-range",
                     "tolerance = " + format_number(tolerance) + ": expected a relative tolerance in (0, 1)");
}

/// f applied to every value of `in`, without the GIL, as a new 1-D array.
template <class F>
[[nodiscard]] Buffer map_values(const DoubleView& in, F&& f) {
  std::vector<double> out(static_cast<std::size_t>(in.rows()));
  {
    py::gil_scoped_release release;
    for (py::ssize_t i = 0; i < in.rows(); ++i) out[static_cast<std::size_t>(i)] = f(in(i));
  }
  return Buffer::of(std::move(out), {in.rows()});
}

}  // namespace kontur::python
