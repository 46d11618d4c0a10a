// STEP of a run's part (docs/cad.md): thin binding of write_load_step.
#include <pybind11/pybind11.h>

#include "sheetgen/pipeline/step_files.hpp"

namespace py = pybind11;

namespace sheetgen::python {

namespace {

py::dict report_dict(const StepSolidReport& r) {
  py::dict d;
  d["solids"] = r.solids;
  d["valid"] = r.valid;
  d["volume_mm3"] = r.volume_mm3;
  d["faces"] = r.faces;
  d["bend_faces"] = r.bend_faces;
  d["box_mm"] = py::make_tuple(r.box_min_mm[0], r.box_min_mm[1], r.box_min_mm[2], r.box_max_mm[0], r.box_max_mm[1],
                               r.box_max_mm[2]);
  return d;
}

}  // namespace

void bind_step(py::module_& m) {
  m.def(
      "write_step",
      [](const Problem& problem, const GenerateResult& result, const std::string& load, const std::string& part_path,
         const std::string& flat_path) {
        LoadStepReport r;
        {
          py::gil_scoped_release release;
          r = write_load_step(problem, result, load, part_path, flat_path);
        }
        py::dict d;
        d["part"] = report_dict(r.part);
        if (!flat_path.empty()) d["flat"] = report_dict(r.flat);
        return d;
      },
      py::arg("problem"), py::arg("result"), py::arg("load"), py::arg("part_path"), py::arg("flat_path") = "",
      "Write `load`'s bent part as STEP (AP214, mm; docs/cad.md) to `part_path` and, when given, its flat pattern "
      "as a STEP solid to `flat_path`. Returns {part: {solids, valid, volume_mm3, faces, bend_faces, box_mm}, "
      "flat: {...}}. Raises InputError (a ValueError) when the load is not in the run or has no valid part, "
      "RuntimeError naming the path when a file cannot be written (nothing is left there then).");
}

}  // namespace sheetgen::python
