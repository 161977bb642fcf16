#pragma once
// The parts of the Python module (_core), each binding one area of the library.
#include <fmt/format.h>
#include <pybind11/pybind11.h>

#include <string>

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

}  // namespace kontur::python
