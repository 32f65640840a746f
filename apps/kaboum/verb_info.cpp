// `kaboum info MESH [--json]`: reads a mesh and prints what analyzeMesh finds (closed, manifold,
// oriented, volume, bounding box), as lines for people or as one JSON object.
#include <fmt/format.h>

#include <iostream>

#include "kaboum/geometry/mesh_analysis.hpp"
#include "kaboum/io/json_geometry.hpp"
#include "kaboum/io/mesh_io.hpp"
#include "verb.hpp"

namespace kaboum::cli {

using namespace kaboum::geometry;
using namespace kaboum::io;

namespace {

void printHuman(const std::string& file, const MeshAnalysis& a) {
  const auto yesNo = [](bool value) { return value ? "yes" : "no"; };
  fmt::print("file:                  {}\n", file);
  fmt::print("vertices:              {}\n", a.vertices);
  fmt::print("triangles:             {}\n", a.triangles);
  fmt::print("components:            {}\n", a.components);
  fmt::print("closed:                {} ({} border edges in {} loops)\n", yesNo(a.closed),
             a.borderEdges, a.borderLoops);
  fmt::print("edge-manifold:         {} ({} non-manifold edges, {} non-manifold vertices)\n",
             yesNo(a.edgeManifold), a.nonManifoldEdges, a.nonManifoldVertices);
  fmt::print("consistently oriented: {}\n", yesNo(a.consistentlyOriented));
  fmt::print("outward oriented:      {}\n", yesNo(a.outwardOriented));
  fmt::print("degenerate triangles:  {}\n", a.degenerateTriangles);
  fmt::print("volume:                {}\n", a.volume);
  fmt::print("bounding box:          [{}, {}, {}] .. [{}, {}, {}]\n", a.boxMin.x(), a.boxMin.y(),
             a.boxMin.z(), a.boxMax.x(), a.boxMax.y(), a.boxMax.z());
  fmt::print("diagonal:              {}\n", a.diagonal);
}

VerbRunner setupInfo(CLI::App& command) {
  struct Options {
    std::string mesh;
    bool json = false;
  };
  auto options = std::make_shared<Options>();
  command.add_option("MESH", options->mesh, "Mesh file (.stl .obj .ply .off .dae .wrl)")
      ->required();
  command.add_flag("--json", options->json, "Print one JSON object instead of lines");
  return [options] {
    const MeshAnalysis analysis = analyzeMesh(readMesh(options->mesh));
    if (options->json) {
      nlohmann::json out = toJson(analysis);
      out["file"] = options->mesh;
      std::cout << out.dump() << '\n';
    } else {
      printHuman(options->mesh, analysis);
    }
    return 0;
  };
}

const VerbRegistration registration{"info", "Read a mesh and report its topology and geometry",
                                    &setupInfo};

}  // namespace

}  // namespace kaboum::cli
