#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "sheetgen/pipeline/part_drawing.hpp"

namespace py = pybind11;

namespace sheetgen::python {

void bind_drawing(py::module_& m) {
  m.def(
      "write_drawing",
      [](const Problem& problem, const std::string& result_json, const std::string& load, const std::string& path,
         const std::string& paper) {
        DrawingSheetOptions o;
        if (paper != "A3" && paper != "A4") throw py::value_error("paper '" + paper + "' is not A3 or A4");
        o.paper = paper == "A3" ? PaperSize::A3 : PaperSize::A4;
        DrawingSheetLayout l;
        {
          py::gil_scoped_release release;
          l = write_load_drawing(result_json, load, problem, path, o);
        }
        py::dict d;
        d["page_width_mm"] = l.page_width_mm;
        d["page_height_mm"] = l.page_height_mm;
        d["scale_denominator"] = l.scale_denominator;
        d["extent_mm"] = py::make_tuple(l.extent_x_mm, l.extent_y_mm);
        return d;
      },
      py::arg("problem"), py::arg("result_json"), py::arg("load"), py::arg("path"), py::arg("paper") = "A3",
      "Write the drawing sheet (one-page PDF, docs/drawing.md) of `load`'s part from result.json's text to `path`. "
      "Returns {page_width_mm, page_height_mm, scale_denominator (1:n), extent_mm (x, y)}. Raises InputError "
      "(a ValueError) when the load is not in the result or has no valid part, RuntimeError naming the path "
      "when it cannot be written (nothing is left there then).");
}

}  // namespace sheetgen::python
