#include <pybind11/eigen.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "sheetgen/env/environment.hpp"

namespace py = pybind11;

namespace sheetgen::python {

void bind_environment(py::module_& m) {
  py::class_<AllowedContacts>(m, "AllowedContacts")
      .def(py::init<>())
      .def(py::init([](std::vector<int> ras, std::vector<int> loads) { return AllowedContacts{std::move(ras), std::move(loads)}; }),
           py::arg("rivet_areas") = std::vector<int>{}, py::arg("loads") = std::vector<int>{})
      .def_readwrite("rivet_areas", &AllowedContacts::rivet_areas)
      .def_readwrite("loads", &AllowedContacts::loads);

  py::class_<RayHit>(m, "RayHit")
      .def_readonly("distance", &RayHit::distance, "m")
      .def_readonly("point", &RayHit::point, "m")
      .def_readonly("normal", &RayHit::normal)
      .def_readonly("mesh", &RayHit::mesh)
      .def_readonly("face", &RayHit::face)
      .def_readonly("load", &RayHit::load)
      .def_readonly("rivet_area", &RayHit::rivet_area);

  py::class_<ContactResult>(m, "ContactResult")
      .def_readonly("clear", &ContactResult::clear)
      .def_readonly("min_clearance", &ContactResult::min_clearance, "m")
      .def_readonly("worst_point", &ContactResult::worst_point, "m")
      .def_readonly("samples", &ContactResult::samples);

  py::class_<Environment>(m, "Environment")
      .def(py::init([](const Problem& p, double voxel_size, int band_voxels) {
             EnvironmentOptions o;
             o.voxel_size = voxel_size;
             o.band_voxels = band_voxels;
             py::gil_scoped_release release;  // the grid build takes a while
             return std::make_unique<Environment>(p, o);
           }),
           py::arg("problem"), py::arg("voxel_size") = 0.0, py::arg("band_voxels") = 0,
           "Build the clearance field and ray caster; voxel_size in m (0 = automatic).")
      .def_property_readonly("voxel_size", &Environment::voxel_size, "m")
      .def("clearance", [](const Environment& e, const Eigen::MatrixX3d& points) {
             Eigen::VectorXd d(points.rows());
             py::gil_scoped_release release;
             for (Eigen::Index i = 0; i < points.rows(); ++i) d[i] = e.clearance(points.row(i).transpose());
             return d;
           },
           py::arg("points"), "Distance to the nearest obstacle for #P by 3 points (m); negative inside a load box.")
      .def("clearance_gradient", &Environment::clearance_gradient, py::arg("point"))
      .def("rivet_area_distance", [](const Environment& e, int ra, const Eigen::MatrixX3d& points) {
             Eigen::VectorXd d(points.rows());
             py::gil_scoped_release release;
             for (Eigen::Index i = 0; i < points.rows(); ++i) d[i] = e.rivet_area_distance(ra, points.row(i).transpose());
             return d;
           },
           py::arg("rivet_area"), py::arg("points"))
      .def("cast_ray", &Environment::cast_ray, py::arg("origin"), py::arg("direction"), py::arg("max_distance"),
           py::call_guard<py::gil_scoped_release>(), "First hit or None.")
      .def("polygon_contact", &Environment::polygon_contact, py::arg("polygon"), py::arg("required"),
           py::arg("allowed") = AllowedContacts{}, py::arg("sample_spacing") = 0.0, py::call_guard<py::gil_scoped_release>());
}

}  // namespace sheetgen::python
