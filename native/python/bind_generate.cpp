#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "sheetgen/pipeline/generate.hpp"
#include "sheetgen/pipeline/output_files.hpp"
#include "sheetgen/pipeline/result_json.hpp"

namespace py = pybind11;

namespace sheetgen::python {

void bind_generate(py::module_& m) {
  py::class_<GenerateProgress>(m, "GenerateProgress",
                               "Progress of a generate() call, readable from another thread; cancel() stops it within a second.")
      .def(py::init<>())
      .def_property_readonly("stage", [](const GenerateProgress& p) { return std::string(to_string(static_cast<Stage>(p.stage.load()))); })
      .def_property_readonly("load", [](const GenerateProgress& p) { return p.load.load(); })
      .def_property_readonly("loads", [](const GenerateProgress& p) { return p.loads.load(); })
      .def_property_readonly("iterations", [](const GenerateProgress& p) { return p.discovery.iterations.load(); })
      .def_property_readonly("total_iterations", [](const GenerateProgress& p) { return p.discovery.total.load(); })
      .def_property_readonly("segments", [](const GenerateProgress& p) { return p.discovery.segments.load(); })
      .def_property_readonly("evaluated", [](const GenerateProgress& p) { return p.compose.evaluated.load(); })
      .def_property_readonly("best_cost_m2", [](const GenerateProgress& p) { return p.compose.best_cost.load(); })
      .def_property_readonly("gauge", [](const GenerateProgress& p) { return p.gauge.load(); },
                             "0: the problem's sheet; k: the load is searched again at its k-th thicker gauge")
      .def("cancel", [](GenerateProgress& p) { p.cancel = true; })
      .def_property_readonly("cancelled", [](const GenerateProgress& p) { return p.cancel.load(); });

  py::class_<GenerateResult>(m, "GenerateResult")
      .def_property_readonly("all_ok", &GenerateResult::all_ok)
      .def_readonly("cancelled", &GenerateResult::cancelled)
      .def_readonly("seconds", &GenerateResult::seconds);

  m.def(
      "generate",
      [](const Problem& problem, GenerateProgress* progress, std::optional<std::uint64_t> seed, std::optional<int> chains,
         std::optional<int> iterations, std::optional<int> beam_width, std::optional<int> threads, bool right_angles) {
        GenerateOptions o;
        o.seed = seed;
        o.chains = chains;
        o.iterations = iterations;
        o.beam_width = beam_width;
        o.threads = threads;
        o.right_angles = right_angles;
        py::gil_scoped_release release;  // the caller's UI keeps running; progress is read through atomics
        return generate(problem, o, progress);
      },
      py::arg("problem"), py::arg("progress") = nullptr, py::arg("seed") = py::none(), py::arg("chains") = py::none(),
      py::arg("iterations") = py::none(), py::arg("beam_width") = py::none(), py::arg("threads") = py::none(),
      py::arg("right_angles") = false,
      "Design a part for every load (docs/architecture.md \"Pipeline\"). Releases the GIL; pass a GenerateProgress to watch or cancel.");

  m.def(
      "result_json",
      [](const Problem& problem, const GenerateResult& result, const std::string& problem_ref) {
        return result_json(problem, result, problem_ref).dump();
      },
      py::arg("problem"), py::arg("result"), py::arg("problem_ref") = "",
      "The sheetgen-result/1 document as JSON text.");

  m.def("write_outputs", &write_outputs, py::arg("dir"), py::arg("problem"), py::arg("result"), py::arg("problem_path"),
        py::call_guard<py::gil_scoped_release>(),
        "Write result.json and per-load part.obj, flat.dxf, flat.svg, bends.csv, history.csv, convergence.png "
        "(staged, then renamed).");
}

}  // namespace sheetgen::python
