// The native module: thin bindings only (docs/code-style.md point 8). One bind_x() per area.
#include <pybind11/pybind11.h>

namespace py = pybind11;

namespace sheetgen::python {
void bind_problem(py::module_& m);
void bind_environment(py::module_& m);
void bind_generate(py::module_& m);
void bind_modes(py::module_& m);
void bind_drawing(py::module_& m);
void bind_step(py::module_& m);
}  // namespace sheetgen::python

PYBIND11_MODULE(_sheetgen_native, m) {
  m.doc() = "sheetgen native core: problem loading, environment queries (SI units: m, N, Pa, rad)";
  sheetgen::python::bind_problem(m);
  sheetgen::python::bind_environment(m);
  sheetgen::python::bind_generate(m);
  sheetgen::python::bind_modes(m);
  sheetgen::python::bind_drawing(m);
  sheetgen::python::bind_step(m);
}
