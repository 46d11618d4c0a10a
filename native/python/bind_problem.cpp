#include <pybind11/eigen.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "sheetgen/core/input_error.hpp"
#include "sheetgen/core/problem.hpp"

namespace py = pybind11;

namespace sheetgen::python {

namespace {
// #V by 3 and #F by 3 arrays for the mesh data.
Eigen::MatrixXd vertices_of(const TriangleMesh& m) {
  Eigen::MatrixXd v(m.vertices.size(), 3);
  for (size_t i = 0; i < m.vertices.size(); ++i) v.row(i) = m.vertices[i].transpose();
  return v;
}
Eigen::MatrixXi triangles_of(const TriangleMesh& m) {
  Eigen::MatrixXi f(m.triangles.size(), 3);
  for (size_t i = 0; i < m.triangles.size(); ++i) f.row(i) << m.triangles[i][0], m.triangles[i][1], m.triangles[i][2];
  return f;
}
}  // namespace

void bind_problem(py::module_& m) {
  static py::exception<InputError> input_error(m, "InputError", PyExc_ValueError);
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const InputError& e) {
      input_error(e.what());
    }
  });

  py::class_<EnvironmentMesh>(m, "EnvironmentMesh")
      .def_readonly("name", &EnvironmentMesh::name)
      .def_readonly("source", &EnvironmentMesh::source)
      .def_property_readonly("vertices", [](const EnvironmentMesh& e) { return vertices_of(e.mesh); }, "#V by 3, m")
      .def_property_readonly("triangles", [](const EnvironmentMesh& e) { return triangles_of(e.mesh); }, "#F by 3 vertex indices")
      .def_property_readonly("triangle_count", [](const EnvironmentMesh& e) { return e.mesh.triangles.size(); });

  py::class_<RivetAreaSpec>(m, "RivetArea")
      .def_readonly("name", &RivetAreaSpec::name)
      .def_readonly("mesh", &RivetAreaSpec::mesh)
      .def_readonly("faces", &RivetAreaSpec::faces)
      .def_readonly("area_m2", &RivetAreaSpec::area_m2);

  py::class_<LoadCase>(m, "LoadCase")
      .def_readonly("name", &LoadCase::name)
      .def_readonly("force", &LoadCase::force, "N, world")
      .def_readonly("moment", &LoadCase::moment, "N*m, world, about the centre of mass")
      .def_readonly("max_deflection", &LoadCase::max_deflection, "m, or None");

  py::class_<Load>(m, "Load")
      .def_readonly("name", &Load::name)
      .def_readonly("center", &Load::center, "m")
      .def_readonly("size", &Load::size, "m")
      .def_property_readonly("rotation", [](const Load& l) { return Eigen::Vector4d(l.rotation.w(), l.rotation.x(), l.rotation.y(), l.rotation.z()); },
                             "quaternion (w, x, y, z)")
      .def_readonly("force", &Load::force, "N")
      .def_readonly("moment", &Load::moment, "N*m")
      .def_readonly("mass", &Load::mass, "kg, or None")
      .def_readonly("center_of_mass", &Load::center_of_mass, "m, world")
      .def_readonly("inertia", &Load::inertia, "kg*m^2, 3 by 3, world, about the centre of mass")
      .def_readonly("cases", &Load::cases, "every static case, in order (docs/problem-format.md \"Load cases\")");

  py::class_<Material>(m, "Material")
      .def_readonly("youngs_modulus", &Material::youngs_modulus, "Pa")
      .def_readonly("poisson_ratio", &Material::poisson_ratio)
      .def_readonly("density", &Material::density, "kg/m^3")
      .def_readonly("yield_strength", &Material::yield_strength, "Pa")
      .def_readonly("ultimate_strength", &Material::ultimate_strength, "Pa")
      .def_readonly("thickness", &Material::thickness, "m")
      .def_readonly("gauges", &Material::gauges, "m, the thicker sheets a load without a part is searched in");

  py::class_<Problem>(m, "Problem")
      .def_readonly("source", &Problem::source)
      .def_readonly("meshes", &Problem::meshes)
      .def_readonly("rivet_areas", &Problem::rivet_areas)
      .def_readonly("loads", &Problem::loads)
      .def_readonly("material", &Problem::material)
      .def_property_readonly("triangle_count", &Problem::triangle_count)
      .def_property_readonly("bounds", [](const Problem& p) {
        const auto b = p.bounds();
        return std::make_pair(Vec3(b.min), Vec3(b.max));
      }, "(min, max) corners, m");

  m.def("load_problem", &load_problem, py::arg("path"), "Read and validate a sheetgen-problem/1 file; raises InputError.");
  m.def("parse_problem", &parse_problem, py::arg("json_text"), py::arg("source") = "<inline>", py::arg("base_dir") = ".",
        "Parse problem JSON text; mesh files resolve against base_dir; raises InputError.");
}

}  // namespace sheetgen::python
