// The VRML 2.0 reader: transforms, Inline, DEF/USE, ccw, Box, skipped nodes, the Robotics Library
// files of the bimanual assembly scenario, and located errors for malformed files.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "io_test_support.hpp"
#include "kaboum/geometry/mesh_analysis.hpp"
#include "kaboum/testing/data_paths.hpp"

namespace kaboum::io {

using namespace kaboum::geometry;
using namespace kaboum::testing;

namespace {

using test::expectReadError;
using test::meshData;
using test::ScratchDir;

constexpr const char* kHeader = "#VRML V2.0 utf8\n";

// A unit right-angled tetrahedron, faces counter-clockwise seen from outside.
constexpr const char* kTetrahedronShape = R"(
  Shape {
    appearance Appearance { material Material { diffuseColor 1 0 0 } }
    geometry IndexedFaceSet {
      solid TRUE creaseAngle .5
      coord Coordinate { point [ 0 0 0, 1 0 0, 0 1 0, 0 0 1 ] }
      coordIndex [ 0 2 1 -1, 0 1 3 -1, 0 3 2 -1, 1 2 3 ]
      normal Normal { vector [ 0 0 1 ] }
      normalPerVertex FALSE
    }
  }
)";

bool hasVertex(const TriangleMesh& mesh, const Vec3& p) {
  return std::find(mesh.vertices.begin(), mesh.vertices.end(), p) != mesh.vertices.end();
}

TEST(Vrml, TransformsInlineAndDefUseGiveExactCoordinates) {
  ScratchDir dir;
  dir.write("parts/tetra.wrl", std::string(kHeader) + "# one tetrahedron\n" + kTetrahedronShape);
  const std::string scene = dir.write("scene.wrl", std::string(kHeader) + R"(
NavigationInfo { type [ "EXAMINE", "ANY" ] }
DEF moved Transform {
  translation 1 2 3
  scale 2 0.5 4
  children [ Inline { url "parts/tetra.wrl" } ]
}
Transform { translation 0 0 -8 children USE moved }
Group { children [ Transform { translation -1 0 0 children [ Inline { url [ "missing.wrl" "parts/tetra.wrl" ] } ] } ] }
)");
  const TriangleMesh mesh = readMesh(scene);
  ASSERT_EQ(mesh.triangles.size(), 12u);
  ASSERT_EQ(mesh.vertices.size(), 12u);
  // p -> (1,2,3) + diag(2, 0.5, 4) p, then the USE copy 8 lower, then the plain copy at x - 1.
  for (const Vec3& p : {Vec3(1, 2, 3), Vec3(3, 2, 3), Vec3(1, 2.5, 3), Vec3(1, 2, 7),
                        Vec3(1, 2, -5), Vec3(3, 2, -5), Vec3(1, 2.5, -5), Vec3(1, 2, -1),
                        Vec3(-1, 0, 0), Vec3(0, 0, 0), Vec3(-1, 1, 0), Vec3(-1, 0, 1)}) {
    EXPECT_TRUE(hasVertex(mesh, p)) << p.transpose();
  }
  const MeshAnalysis analysis = analyzeMesh(mesh);
  EXPECT_EQ(analysis.components, 3u);
  EXPECT_TRUE(analysis.outwardOriented);
  EXPECT_DOUBLE_EQ(analysis.volume, 2 * 4.0 / 6.0 + 1.0 / 6.0);  // scaled copies have 4x volume
}

TEST(Vrml, RotationCenterAndScaleOrientationFollowTheSpec) {
  ScratchDir dir;
  // Rotating by pi about z around centre (1,0,0) maps the origin corner to (2,0,0); scaling x by 2
  // in a frame turned by pi/2 about z scales y instead.
  const std::string path = dir.write("rotated.wrl", std::string(kHeader) + R"(
Transform { rotation 0 0 1 3.141592653589793 center 1 0 0 children [ )" +
                                                        kTetrahedronShape + R"( ] }
Transform { translation 10 0 0 scale 2 1 1 scaleOrientation 0 0 1 1.5707963267948966
            children [ )" + kTetrahedronShape + R"( ] }
)");
  const MeshAnalysis analysis = analyzeMesh(readMesh(path));
  EXPECT_NEAR((analysis.boxMin - Vec3(1, -1, 0)).norm(), 0.0, 1e-12);
  EXPECT_NEAR((analysis.boxMax - Vec3(11, 2, 1)).norm(), 0.0, 1e-12);
  EXPECT_NEAR(analysis.volume, 1.0 / 6.0 + 2.0 / 6.0, 1e-12);
  EXPECT_TRUE(analysis.outwardOriented);
}

TEST(Vrml, ClockwiseFacesAndMirroringTransformsStayOutward) {
  ScratchDir dir;
  const std::string path = dir.write("flips.wrl", std::string(kHeader) + R"(
Shape { geometry IndexedFaceSet {
  ccw FALSE
  coord Coordinate { point [ 0 0 0, 1 0 0, 0 1 0, 0 0 1 ] }
  coordIndex [ 0 1 2 -1 0 3 1 -1 0 2 3 -1 1 3 2 -1 ] } }
Transform { translation 5 0 0 scale -1 1 1 children [ )" +
                                                      kTetrahedronShape + R"( ] }
Transform { translation 9 0 0 children Shape { geometry Box { size 2 4 0.5 } } }
)");
  const MeshAnalysis analysis = analyzeMesh(readMesh(path));
  EXPECT_EQ(analysis.components, 3u);
  EXPECT_TRUE(analysis.consistentlyOriented);
  EXPECT_TRUE(analysis.outwardOriented);
  EXPECT_DOUBLE_EQ(analysis.volume, 2.0 / 6.0 + 4.0);
  EXPECT_EQ(analysis.boxMax, Vec3(10, 2, 1));
}

TEST(Vrml, LineSetsAndPolygonsWithoutTrailingSeparator) {
  ScratchDir dir;
  const std::string path = dir.write("mixed.wrl", std::string(kHeader) + R"(
Shape { geometry IndexedLineSet { coord Coordinate { point [ 0 0 0, 5 5 5 ] } coordIndex [ 0 1 ] } }
Shape { geometry IndexedFaceSet {
  coord DEF square Coordinate { point [ 0 0 0, 1 0 0, 1 1 0, 0 1 0 ] }
  coordIndex [ 0 1 2 3 ] } }
Shape { geometry IndexedFaceSet { coord USE square coordIndex [ 0, 3, 2, 1, -1 ] } }
)");
  const TriangleMesh mesh = readMesh(path);
  EXPECT_EQ(mesh.vertices.size(), 4u);  // the line set adds nothing
  EXPECT_EQ(mesh.triangles.size(), 4u);
  EXPECT_TRUE(analyzeMesh(mesh).closed);  // a square with its back face
}

TEST(Vrml, CopiedScenarioFingerWithAdapterIsItsTwoInlinedParts) {
  const std::string tools = meshData("bimanual-assembly/tools/");
  const TriangleMesh whole = readMesh(tools + "finger2-with-adapter.wrl");
  const TriangleMesh adapter = readMesh(tools + "finger-adapter.wrl");
  const TriangleMesh finger = readMesh(tools + "finger2.wrl");
  EXPECT_EQ(whole.triangles.size(), adapter.triangles.size() + finger.triangles.size());
  const MeshAnalysis analysis = analyzeMesh(whole);
  EXPECT_EQ(analysis.components, 2u);
  EXPECT_TRUE(analysis.closed);
  EXPECT_TRUE(analysis.outwardOriented);
  EXPECT_NEAR(analysis.volume, analyzeMesh(adapter).volume + analyzeMesh(finger).volume, 1e-15);
}

TEST(Vrml, CopiedScenarioTabletopHasTheDocumentedSize) {
  // tabletop.wrl: a 0.9 x 1.2 x 0.025 m slab with chamfered edges.
  const MeshAnalysis table =
      analyzeMesh(readMesh(meshData("bimanual-assembly/environment/tabletop.wrl")));
  EXPECT_EQ(table.boxMin, Vec3(-0.45, -0.6, -0.0125));
  EXPECT_EQ(table.boxMax, Vec3(0.45, 0.6, 0.0125));
  EXPECT_TRUE(table.closed);
  EXPECT_TRUE(table.outwardOriented);
}

// Every VRML file of the shared bimanual-assembly scenario loads, except three that cannot:
// frame.wrl holds only lines, and static.wrl (so scene.wrl) inlines the table-only.wrl that the
// scenario snapshot does not include.
TEST(Vrml, EveryScenarioFileLoadsOrSaysWhyNot) {
  const auto shared = kaboum::testing::sharedDir();
  if (!shared || !std::filesystem::exists(*shared / "scenarios/bimanual-assembly/scene.wrl")) {
    GTEST_SKIP() << "no shared scenario folder (optional; the copied files are tested above)";
  }
  const std::filesystem::path scenario = *shared / "scenarios/bimanual-assembly";
  const std::map<std::string, std::string> expectedErrors{
      {"frame.wrl", "empty mesh: no faces"},
      {"static.wrl", "Inline file not found: 'table-only.wrl'"},
      {"scene.wrl", "Inline file not found: 'table-only.wrl'"}};
  std::size_t loaded = 0;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(scenario)) {
    if (entry.path().extension() != ".wrl") continue;
    const std::string name = entry.path().filename().string();
    SCOPED_TRACE(entry.path().string());
    const std::string error = test::readError(entry.path().string());
    if (const auto expected = expectedErrors.find(name); expected != expectedErrors.end()) {
      EXPECT_NE(error.find(expected->second), std::string::npos) << error;
      continue;
    }
    EXPECT_EQ(error, "");
    ++loaded;
  }
  EXPECT_EQ(loaded, 27u);
}

TEST(VrmlBadInput, MalformedFilesGiveLocatedErrors) {
  ScratchDir dir;
  const auto check = [&](const std::string& name, const std::string& body, const std::string& where,
                         const std::string& what) {
    SCOPED_TRACE(name);
    expectReadError(dir.write(name, std::string(kHeader) + body), dir.file(name) + where, what);
  };
  check("unclosed.wrl", "Transform {\n  children [\n", ":4:1", "unexpected end of file");
  check("unclosed-skip.wrl", "Shape { appearance Appearance { material Material {\n}\n", ":2:31",
        "unclosed '{'");
  check("node.wrl", "Transform { children [\n  Shape { geometry Sphere { radius 1 } }\n] }\n",
        ":3:20", "unsupported VRML node 'Sphere'");
  check("use.wrl", "Group { children [ USE nothing ] }\n", ":2:24",
        "USE of undefined name 'nothing'");
  check("index.wrl",
        "Shape { geometry IndexedFaceSet {\n coord Coordinate { point [ 0 0 0, 1 0 0, 0 1 0 ] }\n"
        " coordIndex [ 0 1 2 -1\n 0 2 3 -1 ] } }\n",
        ":5:6", "coordIndex 3 out of range (3 points)");
  check("negative.wrl", "Shape { geometry IndexedFaceSet { coordIndex [ 0 -2 1 ] } }\n", ":2:50",
        "negative coordIndex -2");
  check("polygon.wrl",
        "Shape { geometry IndexedFaceSet {\n coord Coordinate { point [ 0 0 0, 1 0 0, 0 1 0 ] }\n"
        " coordIndex [ 0 1 2 -1 2 1 -1 ] } }\n",
        ":4:24", "face with fewer than 3 vertices");
  check("point.wrl",
        "Shape { geometry IndexedFaceSet { coord Coordinate { point [ 0 0 zero ] } } }\n", ":2:66",
        "expected point coordinate, found 'zero'");
  check("triple.wrl",
        "Shape { geometry IndexedFaceSet { coord Coordinate { point [ 0 0 0 1 ] } } }\n", ":2:70",
        "point list length is not a multiple of 3");
  check("ccw.wrl", "Shape { geometry IndexedFaceSet { ccw MAYBE } }\n", ":2:39",
        "expected TRUE or FALSE for ccw, found 'MAYBE'");
  check("brace.wrl", "Transform translation 1 2 3\n", ":2:11", "expected '{' in Transform");
  check("proto.wrl", "PROTO Part [] { Group {} }\n", ":2:1", "unsupported VRML statement 'PROTO'");
  check("string.wrl", "Inline { url \"part.wrl }\n", ":2:14", "unterminated string");
  check("inline.wrl", "Group { children Inline { url \"nowhere.wrl\" } }\n", ":2:31",
        "Inline file not found: 'nowhere.wrl'");
  check(
      "deep.wrl",
      [] {
        std::string nested;
        for (int i = 0; i < 300; ++i) nested += "Group { children [\n";
        return nested;
      }(),
      ":202:1", "nodes nested too deeply");
  expectReadError(dir.write("v1.wrl", "#VRML V1.0 ascii\nSeparator { }\n"),
                  dir.file("v1.wrl") + ":1:1", "VRML 1.0 is not supported");
  expectReadError(dir.write("plain.wrl", "Group { }\n"), dir.file("plain.wrl") + ":1:1",
                  "not a VRML 2.0 file");
}

TEST(VrmlBadInput, InlineCycleAndErrorsInsideInlinedFiles) {
  ScratchDir dir;
  dir.write("a.wrl", std::string(kHeader) + "Inline { url \"b.wrl\" }\n");
  dir.write("b.wrl", std::string(kHeader) + "Group { children Inline { url \"a.wrl\" } }\n");
  expectReadError(dir.file("a.wrl"), dir.file("b.wrl") + ":2:31",
                  "Inline cycle: 'a.wrl' includes itself");
  // Nesting counts across inlined files: 150 levels here and 50 more in the inlined file.
  std::string nested;
  for (int i = 0; i < 150; ++i) nested += "Group { children [\n";
  dir.write("deep-outer.wrl", kHeader + nested + "Inline { url \"deep-inner.wrl\" }\n");
  dir.write("deep-inner.wrl", kHeader + nested);
  expectReadError(dir.file("deep-outer.wrl"), dir.file("deep-inner.wrl") + ":51:1",
                  "nodes nested too deeply");
  dir.write("outer.wrl", std::string(kHeader) + "Inline { url \"inner.wrl\" }\n");
  dir.write("inner.wrl", std::string(kHeader) + "\nShape { geometry Cone { } }\n");
  expectReadError(dir.file("outer.wrl"), dir.file("inner.wrl") + ":3:18",
                  "unsupported VRML node 'Cone'");
}

}  // namespace
}  // namespace kaboum::io
