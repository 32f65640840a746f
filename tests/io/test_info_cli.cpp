// `kaboum info`: human and JSON output agree with analyzeMesh, and every class of bad input ends
// with exit code 2 and one stderr line naming the file.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdlib>
#include <nlohmann/json.hpp>

#include "io_test_support.hpp"
#include "kaboum/geometry/mesh_analysis.hpp"

namespace kaboum::io {

using namespace kaboum::geometry;
using namespace kaboum::testing;

namespace {

using test::meshData;
using test::ScratchDir;

using test::CliResult;
using test::runCli;

TEST(InfoCli, JsonReportsTheAnalysis) {
  ScratchDir dir;
  const std::string cow = meshData("cow.obj");
  const CliResult result = runCli(dir, "info --json '" + cow + "'");
  ASSERT_EQ(result.exitCode, 0) << result.err;
  EXPECT_EQ(result.err, "");
  const nlohmann::json json = nlohmann::json::parse(result.out);
  const MeshAnalysis expected = analyzeMesh(readMesh(cow));
  EXPECT_EQ(json.at("file"), cow);
  EXPECT_EQ(json.at("vertices"), expected.vertices);
  EXPECT_EQ(json.at("triangles"), expected.triangles);
  EXPECT_EQ(json.at("components"), expected.components);
  EXPECT_EQ(json.at("border_edges"), expected.borderEdges);
  EXPECT_EQ(json.at("border_loops"), expected.borderLoops);
  EXPECT_EQ(json.at("non_manifold_edges"), expected.nonManifoldEdges);
  EXPECT_EQ(json.at("non_manifold_vertices"), expected.nonManifoldVertices);
  EXPECT_EQ(json.at("degenerate_triangles"), expected.degenerateTriangles);
  EXPECT_EQ(json.at("closed"), expected.closed);
  EXPECT_EQ(json.at("edge_manifold"), expected.edgeManifold);
  EXPECT_EQ(json.at("consistently_oriented"), expected.consistentlyOriented);
  EXPECT_EQ(json.at("outward_oriented"), expected.outwardOriented);
  EXPECT_EQ(json.at("volume").get<double>(), expected.volume);  // shortest round-trip digits
  EXPECT_EQ(json.at("diagonal").get<double>(), expected.diagonal);
  for (int i = 0; i < 3; ++i) {
    EXPECT_EQ(json.at("box_min").at(i).get<double>(), expected.boxMin[i]);
    EXPECT_EQ(json.at("box_max").at(i).get<double>(), expected.boxMax[i]);
  }
}

TEST(InfoCli, HumanOutputNamesEachFinding) {
  ScratchDir dir;
  const CliResult result = runCli(dir, "info '" + meshData("kr5-base-link.stl") + "'");
  ASSERT_EQ(result.exitCode, 0) << result.err;
  const MeshAnalysis expected = analyzeMesh(readMesh(meshData("kr5-base-link.stl")));
  EXPECT_NE(result.out.find("closed:                no (" + std::to_string(expected.borderEdges) +
                            " border edges in " + std::to_string(expected.borderLoops) + " loops)"),
            std::string::npos)
      << result.out;
  EXPECT_NE(result.out.find("triangles:             " + std::to_string(expected.triangles)),
            std::string::npos);
  EXPECT_NE(result.out.find("outward oriented:      no"), std::string::npos);
}

TEST(InfoCli, HelpDescribesTheVerb) {
  ScratchDir dir;
  const CliResult result = runCli(dir, "info --help");
  EXPECT_EQ(result.exitCode, 0);
  EXPECT_NE(result.out.find("--json"), std::string::npos) << result.out;
  EXPECT_NE(result.out.find("MESH"), std::string::npos) << result.out;
}

// One file per class of bad input; readMesh's own tests check each message in detail.
TEST(InfoCli, BadInputExitsWithTwoAndOneLineNamingTheFile) {
  ScratchDir dir;
  std::string nanStl(84 + 50, '\0');
  nanStl[80] = 1;
  nanStl.replace(84 + 12, 4, "\xff\xff\xff\x7f");  // a NaN x coordinate
  const std::vector<std::pair<std::string, std::string>> files{
      {"unknown.xyz", "v 0 0 0\n"},
      {"empty.obj", "v 0 0 0\n"},
      {"nan.obj", "v 0 nan 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"},
      {"nan.stl", nanStl},
      {"range.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 5\n"},
      {"line.obj", "v 0 0 0\nv 1 1 1\nv 2 2 2\nf 1 2 3\n"},
      {"bad.wrl", "#VRML V2.0 utf8\nTransform { children [ Shape {\n"},
      {"garbage.stl", std::string(333, '\x5a')},
      {"truncated.ply",
       "ply\nformat binary_little_endian 1.0\nelement vertex 9\n"
       "property double x\nproperty double y\nproperty double z\nend_header\n"}};
  std::vector<std::string> paths{dir.file("missing.obj")};
  for (const auto& [name, contents] : files) paths.push_back(dir.write(name, contents));
  for (const std::string& path : paths) {
    SCOPED_TRACE(path);
    const CliResult result = runCli(dir, "info '" + path + "'");
    EXPECT_EQ(result.exitCode, 2);
    EXPECT_EQ(result.out, "");
    EXPECT_EQ(result.err.rfind("kaboum: error: " + path, 0), 0u) << result.err;
    ASSERT_FALSE(result.err.empty());
    EXPECT_EQ(result.err.find('\n'), result.err.size() - 1) << result.err;
  }
}

TEST(InfoCli, MissingArgumentIsAUsageError) {
  ScratchDir dir;
  const CliResult result = runCli(dir, "info");
  EXPECT_EQ(result.exitCode, 2);
  EXPECT_NE(result.err.find("MESH"), std::string::npos) << result.err;
}

}  // namespace
}  // namespace kaboum::io
