// The compiled part of the `kontur` Python package (kontur._core): the library's curves, arcs,
// machines and runs, with arrays passed through the buffer protocol (buffer.hpp). The public API,
// with numpy and the docstrings, is python/kontur/__init__.py.
#include <kontur/error.hpp>
#include <kontur/version.hpp>

#include "bindings.hpp"
#include "buffer.hpp"

PYBIND11_MODULE(_core, m) {
  namespace py = pybind11;
  using kontur::python::Buffer;
  m.doc() = "Kontur's library, compiled (use the package kontur, not this module).";
  m.attr("__version__") = kontur::version_string;

  // A broken rule (a curve, a program, a machine, an argument) is kontur.InputError, a ValueError
  // whose message is the command's (file, line, rule) and whose `rule` names the rule.
  // (Never destroyed: Python may be finalised before the module's statics.)
  static auto* const input_error = new py::exception<kontur::InputError>(m, "InputError", PyExc_ValueError);
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const kontur::InputError& e) {
      py::object error = py::reinterpret_borrow<py::object>(input_error->ptr())(e.what());
      error.attr("rule") = e.rule();
      PyErr_SetObject(input_error->ptr(), error.ptr());
    }
  });

  py::class_<Buffer>(m, "Buffer", py::buffer_protocol(), "An array made by Kontur, viewed by numpy without a copy.")
      .def_buffer([](const Buffer& b) { return b.info(); });

  kontur::python::bind_curves(m);
  kontur::python::bind_arcs(m);
  kontur::python::bind_runs(m);
}
