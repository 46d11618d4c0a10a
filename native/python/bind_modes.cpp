#include <pybind11/eigen.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cmath>

#include "sheetgen/core/input_error.hpp"
#include "sheetgen/core/sheet_gauges.hpp"
#include "sheetgen/fem/fem_error.hpp"
#include "sheetgen/structure/envelope_analysis.hpp"
#include "sheetgen/structure/part_model.hpp"

namespace py = pybind11;

namespace sheetgen::python {

namespace {
// #N by 3 translations of a per-node mode (largest translation 1), or None when there is none.
py::object translations(const std::vector<Vector6d>& mode) {
  if (mode.empty()) return py::none();
  Eigen::MatrixXd u(mode.size(), 3);
  for (size_t i = 0; i < mode.size(); ++i) u.row(i) = mode[i].head<3>().transpose();
  return py::cast(u);
}
}  // namespace

void bind_modes(py::module_& m) {
  static py::exception<FemError> fem_error(m, "FemError", PyExc_RuntimeError);
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const FemError& e) {
      fem_error(e.what());
    }
  });

  m.def(
      "part_modes",
      [](const Problem& problem, int load_index, const std::string& part_json, const std::string& source) {
        if (load_index < 0 || load_index >= static_cast<int>(problem.loads.size()))
          throw InputError(source, "load_index", "no load " + std::to_string(load_index) + " in a problem of " +
                                                     std::to_string(problem.loads.size()) + " loads");
        const PlateGeometry geometry = plate_geometry_from_json(part_json, source);
        // The sheet the part is made of, as export-ccx reads it: a thicker gauge moves the base tab.
        std::optional<Problem> thicker;
        const Problem& sheet = problem_at_sheet(problem, sheet_thickness_from_json(part_json, source).value_or(0.0), thicker);
        PartModelOptions model_options;  // the final check's model: default mesh, the part's self-rivets
        model_options.self_rivets = self_rivet_ties_from_json(part_json, source);
        EnvelopeOptions options;
        options.keep_mode_shapes = true;
        PartModel part;
        EnvelopeResult r;
        {
          py::gil_scoped_release release;  // seconds of eigen solves
          part = build_part_model(sheet, load_index, geometry, model_options);
          ShellSolver solver;
          r = analyse_envelope(sheet, part, options, model_options.element, solver);
        }
        Eigen::MatrixXd vertices(part.model.nodes.size(), 3);
        for (size_t i = 0; i < part.model.nodes.size(); ++i) vertices.row(i) = part.model.nodes[i].transpose();
        Eigen::MatrixXi triangles(part.model.triangles.size(), 3);
        for (size_t e = 0; e < part.model.triangles.size(); ++e)
          triangles.row(e) << part.model.triangles[e][0], part.model.triangles[e][1], part.model.triangles[e][2];
        py::dict d;
        d["vertices"] = vertices;
        d["triangles"] = triangles;
        d["load_node"] = part.load_node;
        d["buckling_mode"] = translations(r.buckling_mode);
        d["vibration_mode"] = translations(r.vibration_mode);
        d["buckling_factor"] = std::isfinite(r.buckling_factor) ? py::object(py::float_(r.buckling_factor)) : py::none();
        d["buckling_case"] = r.governing_buckling >= 0 ? py::object(py::str(r.cases[r.governing_buckling].name)) : py::none();
        d["frequencies_hz"] = r.frequencies_hz;
        return d;
      },
      py::arg("problem"), py::arg("load_index"), py::arg("part_json"), py::arg("source") = "result.json",
      "The buckling mode of the governing case and the first vibration mode of one part (a result.json "
      "parts[i] as JSON text) for problem load load_index, on the final check's FEM mesh: vertices (#N by 3, m), "
      "triangles (#E by 3), load_node, buckling_mode and vibration_mode (#N by 3 translations, largest 1, or "
      "None), buckling_factor (or None: nothing buckles), buckling_case, frequencies_hz. Releases the GIL; raises "
      "InputError (bad JSON or index) or FemError (the model cannot be built or solved).");
}

}  // namespace sheetgen::python
