// Meshes and kinematics from Python, as the verbs bound, decompose and fk use them: the bounding
// mesh (thesis §4.3), the bounding convex decomposition (§4.4) and forward kinematics of a URDF
// chain (§5.1). Meshes are numpy arrays: vertices (n × 3 floats) and triangles (m × 3 indices).
#include <fmt/format.h>
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <cstdint>

#include "bindings.hpp"
#include "kaboum/core/error.hpp"
#include "kaboum/geometry/bounding_mesh.hpp"
#include "kaboum/geometry/convex_decomposition.hpp"
#include "kaboum/geometry/mesh_analysis.hpp"
#include "kaboum/geometry/mesh_cleanup.hpp"
#include "kaboum/io/mesh_io.hpp"
#include "kaboum/io/urdf_loader.hpp"
#include "kaboum/kinematics/kinematic_chain.hpp"
#include "mesh_cli.hpp"
#include "scene_world.hpp"

namespace kaboum::python {

namespace {

using geometry::TriangleMesh;

py::array_t<double> vertexArray(const TriangleMesh& mesh) {
  py::array_t<double> array({mesh.vertices.size(), std::size_t{3}});
  auto out = array.mutable_unchecked<2>();
  for (std::size_t v = 0; v < mesh.vertices.size(); ++v) {
    for (int k = 0; k < 3; ++k) out(static_cast<py::ssize_t>(v), k) = mesh.vertices[v][k];
  }
  return array;
}

py::array_t<std::uint32_t> triangleArray(const TriangleMesh& mesh) {
  py::array_t<std::uint32_t> array({mesh.triangles.size(), std::size_t{3}});
  auto out = array.mutable_unchecked<2>();
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    for (std::size_t k = 0; k < 3; ++k) {
      out(static_cast<py::ssize_t>(t), static_cast<py::ssize_t>(k)) = mesh.triangles[t][k];
    }
  }
  return array;
}

TriangleMesh meshFromArrays(
    const py::array_t<double, py::array::c_style | py::array::forcecast>& vertices,
    const py::array_t<std::int64_t, py::array::c_style | py::array::forcecast>& triangles) {
  if (vertices.ndim() != 2 || vertices.shape(1) != 3) {
    throw std::invalid_argument("vertices: expected an (n, 3) array");
  }
  if (triangles.ndim() != 2 || triangles.shape(1) != 3) {
    throw std::invalid_argument("triangles: expected an (m, 3) array of vertex indices");
  }
  TriangleMesh mesh;
  const auto v = vertices.unchecked<2>();
  for (py::ssize_t i = 0; i < v.shape(0); ++i)
    mesh.vertices.emplace_back(v(i, 0), v(i, 1), v(i, 2));
  const auto t = triangles.unchecked<2>();
  for (py::ssize_t i = 0; i < t.shape(0); ++i) {
    geometry::Triangle triangle{};
    for (py::ssize_t k = 0; k < 3; ++k) {
      if (t(i, k) < 0 || t(i, k) >= v.shape(0)) {
        throw std::invalid_argument(
            fmt::format("triangles[{}]: vertex index {} out of range", i, t(i, k)));
      }
      triangle[static_cast<std::size_t>(k)] = static_cast<std::uint32_t>(t(i, k));
    }
    mesh.triangles.push_back(triangle);
  }
  return mesh;
}

// The mesh consistently oriented with outward normals, as the algorithms need it.
TriangleMesh oriented(TriangleMesh mesh) {
  bool changed = false;
  if (!geometry::orientOutward(mesh, changed)) {
    throw InputError(
        "mesh: cannot be oriented consistently (non-orientable or non-manifold surface)");
  }
  return mesh;
}

TriangleMesh bound(const TriangleMesh& input, const std::string& side, std::size_t vertices,
                   const std::optional<std::string>& epsilon, std::size_t samples) {
  if (vertices == 0 && !epsilon) {
    throw InputError("bound: give a target with vertices or epsilon");
  }
  if (side != "outer" && side != "inner") {
    throw InputError("side: expected 'outer' or 'inner', got '" + side + "'");
  }
  const TriangleMesh mesh = oriented(input);
  geometry::BoundingMeshOptions options;
  options.side = side == "outer" ? geometry::BoundSide::Outer : geometry::BoundSide::Inner;
  options.targetVertices = vertices;
  py::gil_scoped_release unlocked;
  if (!epsilon) return geometry::simplifyBounding(mesh, options).mesh;
  geometry::HausdorffReport measured;
  return geometry::simplifyBoundingWithin(
             mesh, options, cli::parseEpsilon(*epsilon, geometry::boundingBoxDiagonal(mesh)),
             samples, measured)
      .mesh;
}

std::vector<TriangleMesh> decompose(const TriangleMesh& mesh, const std::string& epsilon,
                                    std::size_t maxPieces, std::size_t refine) {
  geometry::DecompositionOptions options;
  options.epsilon = cli::parseEpsilon(epsilon, geometry::boundingBoxDiagonal(mesh));
  options.maxPieces = maxPieces;
  options.refineRounds = refine;
  std::vector<TriangleMesh> pieces;
  py::gil_scoped_release unlocked;
  for (geometry::ConvexPiece& piece : geometry::decomposeBounding(mesh, options).pieces) {
    pieces.push_back(std::move(piece.mesh));
  }
  return pieces;
}

py::array_t<double> forwardKinematics(const std::string& urdf, const std::vector<double>& q,
                                      const std::string& tip, const std::string& base) {
  const kinematics::RobotModel model = io::loadUrdf(urdf);
  const kinematics::KinematicChain chain(model, tip, base);
  if (static_cast<int>(q.size()) != chain.dof()) {
    throw InputError(locate(urdf, fmt::format("chain to '{}' has {} joints, got {} values",
                                              chain.tipName(), chain.dof(), q.size())));
  }
  return poseArray(chain.toolPose(q));
}

}  // namespace

void bindGeometry(py::module_& module) {
  py::class_<TriangleMesh>(module, "Mesh", "A triangle mesh: flat vertex and triangle arrays.")
      .def(py::init(&meshFromArrays), py::arg("vertices"), py::arg("triangles"),
           "From an (n, 3) array of points and an (m, 3) array of vertex indices.")
      .def_property_readonly("vertices", &vertexArray, "(n, 3) float64 array.")
      .def_property_readonly("triangles", &triangleArray, "(m, 3) uint32 array.")
      .def_property_readonly(
          "volume", [](const TriangleMesh& self) { return geometry::analyzeMesh(self).volume; })
      .def("__repr__", [](const TriangleMesh& self) {
        return fmt::format("<kaboum.Mesh {} vertices, {} triangles>", self.vertices.size(),
                           self.triangles.size());
      });
  module.def("read_mesh", &io::readMesh, py::arg("path"),
             "Reads an OBJ, STL, PLY, OFF or any format Assimp reads, welded. Raises InputError "
             "naming the file.");
  module.def("write_mesh", &io::writeMesh, py::arg("mesh"), py::arg("path"),
             "Writes the mesh in the format of the path's extension.");
  module.def("bound", &bound, py::arg("mesh"), py::kw_only(), py::arg("side") = "outer",
             py::arg("vertices") = 0, py::arg("epsilon") = py::none(), py::arg("samples") = 20000,
             "The bounding mesh (thesis §4.3) as `kaboum bound`: an outer (enclosing) or inner "
             "(enclosed) simplification to `vertices`, or as far as the measured distance stays "
             "within `epsilon` ('0.002' in the mesh's units, or '1%' of its diagonal).");
  module.def("decompose", &decompose, py::arg("mesh"), py::kw_only(), py::arg("epsilon") = "3%",
             py::arg("max_pieces") = 11, py::arg("refine") = 0,
             "The bounding convex decomposition (thesis §4.4) as `kaboum decompose`: convex "
             "pieces whose union contains the mesh, within `epsilon` where `max_pieces` allows.");
  module.def("forward_kinematics", &forwardKinematics, py::arg("urdf"), py::arg("q"), py::kw_only(),
             py::arg("tip") = "", py::arg("base") = "",
             "The tip link's pose (4x4) in the base link's frame for joint values `q`, as "
             "`kaboum fk`.");
}

}  // namespace kaboum::python
