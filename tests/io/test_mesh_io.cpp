// readMesh/writeMesh: every format read and written, exact round trips, real robot and model
// files, and one test per class of bad input.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <cstring>
#include <limits>
#include <random>

#include "io_test_support.hpp"
#include "kaboum/geometry/mesh_analysis.hpp"

namespace kaboum::io {

using namespace kaboum::geometry;
using namespace kaboum::testing;

namespace {

using test::expectReadError;
using test::expectSameMesh;
using test::meshData;
using test::ScratchDir;

// The cow with every coordinate moved by a random amount, so all 17 significant digits matter.
TriangleMesh fullPrecisionCow() {
  TriangleMesh mesh = readMesh(meshData("cow.obj"));
  std::mt19937_64 random(7);
  std::uniform_real_distribution<double> offset(-1e-3, 1e-3);
  for (Vec3& p : mesh.vertices) p += Vec3(offset(random), offset(random), offset(random));
  return mesh;
}

// `value` rounded to float. The volatile keeps GCC 12 -O2 from dropping the rounding: its SLP
// vectorizer turns pairs of (double)(float)x into no-ops (wrong code, seen on Debian 12's 12.2).
double throughFloat(double value) {
  volatile float rounded = static_cast<float>(value);
  return rounded;
}

class RoundTrip : public ::testing::TestWithParam<const char*> {};

TEST_P(RoundTrip, CoordinatesAndFacesComeBackExactly) {
  ScratchDir dir;
  const TriangleMesh original = fullPrecisionCow();
  const std::string path = dir.file(std::string("cow") + GetParam());
  writeMesh(original, path);
  expectSameMesh(readMesh(path), original);
}

INSTANTIATE_TEST_SUITE_P(TextAndPly, RoundTrip, ::testing::Values(".obj", ".off", ".ply", ".OBJ"));

TEST(StlRoundTrip, KeepsFloatPrecisionAndWeldsBack) {
  ScratchDir dir;
  const TriangleMesh original = readMesh(meshData("spot.obj"));
  writeMesh(original, dir.file("spot.stl"));
  const TriangleMesh read = readMesh(dir.file("spot.stl"));
  // STL stores each triangle's corners separately; welding restores the sharing.
  ASSERT_EQ(read.vertices.size(), original.vertices.size());
  ASSERT_EQ(read.triangles.size(), original.triangles.size());
  for (std::size_t t = 0; t < original.triangles.size(); ++t) {
    for (int k = 0; k < 3; ++k) {
      const Vec3& p = original.vertices[original.triangles[t][k]];
      const Vec3 expected(throughFloat(p.x()), throughFloat(p.y()), throughFloat(p.z()));
      ASSERT_EQ(read.vertices[read.triangles[t][k]], expected) << "triangle " << t;
    }
  }
}

TEST(WriteMesh, ShortestRoundTripTextIsUsed) {
  ScratchDir dir;
  TriangleMesh mesh;
  mesh.vertices = {Vec3(0.1, 1.0 / 3.0, 1e-300), Vec3(1, 0, 0), Vec3(0, 1, 0)};
  mesh.triangles = {{0, 1, 2}};
  writeMesh(mesh, dir.file("t.obj"));
  std::ifstream in(dir.file("t.obj"));
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("v 0.1 0.3333333333333333 1e-300\n"), std::string::npos) << text;
  EXPECT_NE(text.find("f 1 2 3\n"), std::string::npos) << text;
}

TEST(WriteMesh, RejectsUnknownExtensionAndUnwritablePath) {
  ScratchDir dir;
  const TriangleMesh mesh = readMesh(meshData("cube.off"));
  try {
    writeMesh(mesh, dir.file("cube.xyz"));
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()),
              dir.file("cube.xyz") + ": unknown mesh format '.xyz' (expected .obj .stl .ply .off)");
  }
  const std::string unwritable = dir.file("no-such-dir/cube.obj");
  try {
    writeMesh(mesh, unwritable);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), unwritable + ": cannot write: No such file or directory");
  }
}

TEST(ReadObj, FanTriangulatesPolygonsAndResolvesAllIndexForms) {
  ScratchDir dir;
  const std::string path = dir.write("poly.obj",
                                     "# comment\r\n"
                                     "mtllib x.mtl\r\n"
                                     "v 0 0 0\r\nv 1 0 0\r\nv 1 1 0\r\nv 0 1 0\r\nv 0.5 1.5 0\r\n"
                                     "vt 0 0\nvn 0 0 1\ng part\nusemtl red\ns off\n"
                                     "f 1/1/1 2/1/1 3//1 5 4  # a pentagon\n"
                                     "f -5 -4 -1\n"
                                     "l 1 2\n");
  const TriangleMesh mesh = readMesh(path);
  ASSERT_EQ(mesh.vertices.size(), 5u);
  const std::vector<Triangle> expected{{0, 1, 2}, {0, 2, 4}, {0, 4, 3}, {0, 1, 4}};
  EXPECT_EQ(mesh.triangles, expected);
}

TEST(ReadObj, FacesMayPrecedeTheirVertices) {
  ScratchDir dir;
  const TriangleMesh mesh =
      readMesh(dir.write("forward.obj", "f 1 2 3\nv 0 0 0\nv 1 0 0\nv 0 1 0\n"));
  EXPECT_EQ(mesh.triangles, (std::vector<Triangle>{{0, 1, 2}}));
}

TEST(ReadStl, AsciiFacetsAreWelded) {
  ScratchDir dir;
  const std::string path = dir.write("quad.stl",
                                     "solid quad\n"
                                     " facet normal 0 0 1\n  outer loop\n"
                                     "   vertex 0 0 0\n   vertex 1 0 0\n   vertex 1 1 0\n"
                                     "  endloop\n endfacet\n"
                                     " facet normal 0 0 1\n  outer loop\n"
                                     "   vertex 0 0 0\n   vertex 1 1 0\n   vertex 0 1 0\n"
                                     "  endloop\n endfacet\n"
                                     "endsolid quad\n");
  const TriangleMesh mesh = readMesh(path);
  EXPECT_EQ(mesh.vertices.size(), 4u);
  EXPECT_EQ(mesh.triangles, (std::vector<Triangle>{{0, 1, 2}, {0, 2, 3}}));
}

TEST(ReadStl, BinaryWhoseHeaderStartsWithSolidIsStillBinary) {
  ScratchDir dir;
  writeMesh(readMesh(meshData("cube.off")), dir.file("cube.stl"));
  std::string bytes;
  {
    std::ifstream in(dir.file("cube.stl"), std::ios::binary);
    bytes.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  bytes.replace(0, 10, "solid cube");
  const TriangleMesh mesh = readMesh(dir.write("solid-header.stl", bytes));
  EXPECT_EQ(mesh.vertices.size(), 8u);
  EXPECT_EQ(mesh.triangles.size(), 12u);
}

TEST(ReadPly, AsciiTriangleStripsAlternateWindingAndRestartAtMinusOne) {
  ScratchDir dir;
  const std::string path = dir.write("strip.ply",
                                     "ply\nformat ascii 1.0\ncomment a strip\n"
                                     "element vertex 6\nproperty float x\nproperty float y\n"
                                     "property float z\nproperty uchar red\n"
                                     "element tristrips 1\nproperty list int int vertex_indices\n"
                                     "end_header\n"
                                     "0 0 0 255\n1 0 0 255\n0 1 0 255\n1 1 0 255\n0 2 0 255\n"
                                     "5 5 5 0\n"
                                     "8 0 1 2 3 -1 0 2 4\n");
  const TriangleMesh mesh = readMesh(path);
  EXPECT_EQ(mesh.vertices.size(), 5u);  // vertex 5 is unreferenced
  const std::vector<Triangle> expected{{0, 1, 2}, {2, 1, 3}, {0, 2, 4}};
  EXPECT_EQ(mesh.triangles, expected);
}

std::string bigEndianFloat(float value) {
  std::uint32_t bits = 0;
  std::memcpy(&bits, &value, 4);
  return {static_cast<char>(bits >> 24), static_cast<char>(bits >> 16),
          static_cast<char>(bits >> 8), static_cast<char>(bits)};
}

TEST(ReadPly, BinaryBigEndianWithPolygonsAndExtraElements) {
  ScratchDir dir;
  std::string bytes =
      "ply\nformat binary_big_endian 1.0\nelement vertex 4\nproperty float x\n"
      "property float y\nproperty float z\nproperty float nx\n"
      "element face 1\nproperty list uchar int vertex_indices\nproperty uchar flags\n"
      "element edge 2\nproperty int vertex1\nproperty int vertex2\nend_header\n";
  const float corners[4][3] = {{0, 0, 0}, {2, 0, 0}, {2, 3, 0}, {0, 3, 0.5f}};
  for (const auto& c : corners) {
    for (const float v : c) bytes += bigEndianFloat(v);
    bytes += bigEndianFloat(9.0f);  // nx, skipped
  }
  bytes += '\x04';
  for (const char index : {'\0', '\1', '\2', '\3'}) bytes += std::string{'\0', '\0', '\0', index};
  bytes += '\x07';                   // flags, skipped
  bytes += std::string(16, '\x01');  // two edges, skipped
  const TriangleMesh mesh = readMesh(dir.write("quad.ply", bytes));
  ASSERT_EQ(mesh.vertices.size(), 4u);
  EXPECT_EQ(mesh.vertices[3], Vec3(0, 3, 0.5));
  EXPECT_EQ(mesh.triangles, (std::vector<Triangle>{{0, 1, 2}, {0, 2, 3}}));
}

TEST(ReadOff, ColouredPolygonsAndComments) {
  ScratchDir dir;
  const std::string path = dir.write("quad.off",
                                     "COFF\n# a quad and a triangle\n5 2 0\n"
                                     "0 0 0 255 0 0 255\n1 0 0 255 0 0 255\n1 1 0 0 0 0 255\n"
                                     "0 1 0 0 0 0 255\n0.5 0.5 1 0 0 0 255\n"
                                     "4 0 1 2 3 0.5 0.5 0.5\n3 0 1 4\n");
  const TriangleMesh mesh = readMesh(path);
  EXPECT_EQ(mesh.vertices.size(), 5u);
  EXPECT_EQ(mesh.triangles, (std::vector<Triangle>{{0, 1, 2}, {0, 2, 3}, {0, 1, 4}}));
}

TEST(ReadRealFiles, ModelsAndRobotLinksInEveryFormat) {
  // Welded counts as listed in ../shared/meshes/README.md.
  EXPECT_EQ(readMesh(meshData("cow.obj")).vertices.size(), 2903u);
  EXPECT_EQ(readMesh(meshData("spot.obj")).vertices.size(), 2930u);
  const TriangleMesh fandisk = readMesh(meshData("fandisk.obj"));
  EXPECT_EQ(fandisk.vertices.size(), 6475u);
  EXPECT_EQ(fandisk.triangles.size(), 12946u);
  // Binary STL: 440 facets of 3 separate corners each, welded to a closed surface
  // (V = F / 2 + 2 for a closed genus-0 triangle mesh).
  const TriangleMesh wrist = readMesh(meshData("kr5-wrist.stl"));
  EXPECT_EQ(wrist.triangles.size(), 440u);
  EXPECT_EQ(wrist.vertices.size(), wrist.triangles.size() / 2 + 2);
}

TEST(ReadDae, WamLinkMatchesTheSameLinkInStl) {
  const MeshAnalysis dae = analyzeMesh(readMesh(meshData("wam2.dae")));
  const MeshAnalysis stl = analyzeMesh(readMesh(meshData("wam2.stl")));
  EXPECT_GT(dae.triangles, 100u);
  // Two independent exports of one link: same frame and extent to within half a millimetre.
  EXPECT_LT((dae.boxMin - stl.boxMin).norm(), 5e-4);
  EXPECT_LT((dae.boxMax - stl.boxMax).norm(), 5e-4);
}

TEST(ReadDae, NodeTransformsAndUnitApplyButUpAxisDoesNot) {
  ScratchDir dir;
  const std::string path = dir.write("quad.dae", R"(<?xml version="1.0" encoding="utf-8"?>
<COLLADA xmlns="http://www.collada.org/2005/11/COLLADASchema" version="1.4.1">
  <asset><unit name="centimeter" meter="0.01"/><up_axis>Z_UP</up_axis></asset>
  <library_geometries><geometry id="g"><mesh>
    <source id="p"><float_array id="pa" count="12">0 0 0 1 0 0 1 2 0 0 2 0</float_array>
      <technique_common><accessor source="#pa" count="4" stride="3">
        <param name="X" type="float"/><param name="Y" type="float"/><param name="Z" type="float"/>
      </accessor></technique_common></source>
    <vertices id="v"><input semantic="POSITION" source="#p"/></vertices>
    <polylist count="1"><input semantic="VERTEX" source="#v" offset="0"/>
      <vcount>4</vcount><p>0 1 2 3</p></polylist>
  </mesh></geometry></library_geometries>
  <library_visual_scenes><visual_scene id="s"><node id="n"><translate>0 0 5</translate>
    <instance_geometry url="#g"/></node></visual_scene></library_visual_scenes>
  <scene><instance_visual_scene url="#s"/></scene>
</COLLADA>)");
  const MeshAnalysis quad = analyzeMesh(readMesh(path));
  EXPECT_EQ(quad.triangles, 2u);
  EXPECT_NEAR((quad.boxMin - Vec3(0, 0, 0.05)).norm(), 0.0, 1e-8);
  EXPECT_NEAR((quad.boxMax - Vec3(0.01, 0.02, 0.05)).norm(), 0.0, 1e-8);
}

// --- Bad input: one test per class, each a one-line error naming the file. ---

TEST(BadInput, MissingFile) {
  ScratchDir dir;
  expectReadError(dir.file("absent.obj"), dir.file("absent.obj"),
                  "cannot open: No such file or directory");
  expectReadError(dir.file("absent.wrl"), dir.file("absent.wrl"), "cannot open");
  expectReadError(dir.file("absent.dae"), dir.file("absent.dae"), "cannot open");
}

TEST(BadInput, DirectoryInsteadOfFile) {
  ScratchDir dir;
  std::filesystem::create_directories(dir.file("folder.stl"));
  expectReadError(dir.file("folder.stl"), dir.file("folder.stl"), "is a directory");
}

TEST(BadInput, UnknownFormat) {
  ScratchDir dir;
  expectReadError(dir.write("mesh.xyz", "1 2 3\n"), dir.file("mesh.xyz"),
                  "unknown mesh format '.xyz' (expected .stl .obj .ply .off .dae .wrl)");
  expectReadError(dir.write("mesh", "v 0 0 0\n"), dir.file("mesh"), "no file extension");
}

TEST(BadInput, EmptyMeshInEveryFormat) {
  ScratchDir dir;
  for (const auto& [name, contents] : std::vector<std::pair<std::string, std::string>>{
           {"points.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n"},
           {"nothing.obj", ""},
           {"empty.off", "OFF\n3 0 0\n0 0 0\n1 0 0\n0 1 0\n"},
           {"empty.stl", "solid empty\nendsolid empty\n"},
           {"empty.ply",
            "ply\nformat ascii 1.0\nelement vertex 0\nproperty float x\n"
            "property float y\nproperty float z\nend_header\n"},
           {"empty.wrl", "#VRML V2.0 utf8\nGroup { children [] }\n"}}) {
    expectReadError(dir.write(name, contents), dir.file(name), "empty mesh: no faces");
  }
  std::string binary(84, '\0');  // header and a facet count of zero
  expectReadError(dir.write("empty-binary.stl", binary), dir.file("empty-binary.stl"),
                  "empty mesh: no faces");
}

TEST(BadInput, NonFiniteCoordinates) {
  ScratchDir dir;
  expectReadError(dir.write("nan.obj", "v 0 0 0\nv 1 nan 0\nv 0 1 0\nf 1 2 3\n"),
                  dir.file("nan.obj") + ":2:5", "non-finite vertex coordinate 'nan'");
  expectReadError(dir.write("inf.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 -inf\n3 0 1 2\n"),
                  dir.file("inf.off") + ":5:5", "non-finite vertex coordinate '-inf'");
  expectReadError(dir.write("huge.obj", "v 0 0 0\nv 1 0 0\nv 0 1e999 0\nf 1 2 3\n"),
                  dir.file("huge.obj") + ":3:5", "non-finite vertex coordinate '1e999'");
  // Binary STL: a NaN float in the second corner of the only facet.
  std::string bytes(84 + 50, '\0');
  bytes[80] = 1;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  std::memcpy(&bytes[84 + 24], &nan, 4);
  expectReadError(dir.write("nan.stl", bytes), dir.file("nan.stl"),
                  "vertex 1 has a non-finite coordinate");
}

TEST(BadInput, OutOfRangeIndices) {
  ScratchDir dir;
  expectReadError(dir.write("range.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 2 9\n"),
                  dir.file("range.obj") + ":5:7", "vertex index 9 out of range (3 vertices)");
  expectReadError(dir.write("zero.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n"),
                  dir.file("zero.obj") + ":4:3", "vertex index 0 is invalid");
  expectReadError(dir.write("relative.obj", "v 0 0 0\nv 1 0 0\nf -1 -2 -3\n"),
                  dir.file("relative.obj") + ":3:9", "relative vertex index -3 out of range");
  expectReadError(dir.write("range.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n"),
                  dir.file("range.off") + ":6:7", "vertex index 3 out of range (3 vertices)");
  expectReadError(dir.write("range.ply",
                            "ply\nformat ascii 1.0\nelement vertex 3\n"
                            "property float x\nproperty float y\nproperty float z\n"
                            "element face 1\nproperty list uchar int vertex_indices\n"
                            "end_header\n0 0 0\n1 0 0\n0 1 0\n3 0 7 1\n"),
                  dir.file("range.ply") + ":13:5", "vertex index 7 out of range (3 vertices)");
}

TEST(BadInput, ZeroAreaOnly) {
  ScratchDir dir;
  expectReadError(dir.write("line.obj", "v 0 0 0\nv 1 1 1\nv 2 2 2\nf 1 2 3\nf 3 2 1\n"),
                  dir.file("line.obj"), "all 2 faces have zero area");
  expectReadError(dir.write("point.off", "OFF\n3 1 0\n1 1 1\n1 1 1\n1 1 1\n3 0 1 2\n"),
                  dir.file("point.off"), "all 1 faces have zero area");
}

TEST(BadInput, GarbageBinaryStl) {
  ScratchDir dir;
  std::mt19937 random(3);
  std::string bytes(1000, '\0');
  for (char& c : bytes) c = static_cast<char>(random());
  bytes.replace(0, 5, "xolid");
  expectReadError(dir.write("garbage.stl", bytes), dir.file("garbage.stl"),
                  "not a valid binary STL");
  expectReadError(dir.write("short.stl", "abc"), dir.file("short.stl"), "not an STL file: 3 bytes");
  // Truncated: the header announces more facets than the file holds.
  std::string truncated(84 + 50, '\0');
  truncated[80] = 2;
  expectReadError(dir.write("truncated.stl", truncated), dir.file("truncated.stl"),
                  "header announces 2 facets (184 bytes) but the file has 134 bytes");
}

TEST(BadInput, ParseErrorsAreLocated) {
  ScratchDir dir;
  expectReadError(dir.write("short.obj", "v 0 0 0\nv 1 0\n"), dir.file("short.obj") + ":2:6",
                  "expected vertex coordinate, found end of line");
  expectReadError(dir.write("word.obj", "v 0 0 0\nv 1 zero 0\n"), dir.file("word.obj") + ":2:5",
                  "expected vertex coordinate, found 'zero'");
  expectReadError(dir.write("line.obj", "v 0 0 0\nv 1 0 0\nf 1 2\n"), dir.file("line.obj") + ":3:1",
                  "face with fewer than 3 vertices");
  expectReadError(dir.write("header.off", "OF\n"), dir.file("header.off") + ":1:1",
                  "expected 'OFF' header");
  expectReadError(dir.write("short.off", "OFF\n3 1 0\n0 0 0\n"), dir.file("short.off") + ":4:1",
                  "file ends after 1 of 3 vertices");
  expectReadError(dir.write("ascii.stl", "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0\n"),
                  dir.file("ascii.stl") + ":5:1", "expected vertex coordinate");
  expectReadError(dir.write("magic.ply", "plx\n"), dir.file("magic.ply") + ":1:1",
                  "not a PLY file");
  expectReadError(dir.write("type.ply",
                            "ply\nformat ascii 1.0\nelement vertex 1\n"
                            "property quad x\nend_header\n"),
                  dir.file("type.ply") + ":4:10", "unknown property type 'quad'");
  expectReadError(dir.write("noz.ply",
                            "ply\nformat ascii 1.0\nelement vertex 1\n"
                            "property float x\nproperty float y\nend_header\n0 0\n"),
                  dir.file("noz.ply") + ":3:9", "vertex element has no scalar 'z'");
  std::string truncated =
      "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\n"
      "property float y\nproperty float z\nend_header\n";
  truncated += std::string(20, '\0');
  expectReadError(dir.write("truncated.ply", truncated), dir.file("truncated.ply"),
                  "binary data ends early (element 'vertex' 1 of 3)");
}

// Random byte damage to valid files of every format: each read either succeeds or throws
// InputError; never a crash, hang or another exception.
TEST(BadInput, DamagedFilesNeverCrash) {
  ScratchDir dir;
  const TriangleMesh cube = readMesh(meshData("cube.off"));
  std::vector<std::string> sources;
  for (const char* extension : {".obj", ".off", ".ply", ".stl"}) {
    writeMesh(cube, dir.file(std::string("cube") + extension));
    sources.push_back(dir.file(std::string("cube") + extension));
  }
  sources.push_back(meshData("bimanual-assembly/environment/tabletop.wrl"));
  std::mt19937 random(11);
  for (const std::string& source : sources) {
    std::string original;
    {
      std::ifstream in(source, std::ios::binary);
      original.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    }
    const std::string extension = std::filesystem::path(source).extension().string();
    for (int trial = 0; trial < 150; ++trial) {
      std::string damaged = original;
      const int edits = 1 + static_cast<int>(random() % 4);
      for (int e = 0; e < edits; ++e) {
        const std::size_t at = random() % damaged.size();
        switch (random() % 3) {
          case 0:
            damaged[at] = static_cast<char>(random());
            break;
          case 1:
            damaged.erase(at, 1 + random() % 8);
            break;
          default:
            damaged.resize(at);
        }
        if (damaged.empty()) damaged = "x";
      }
      const std::string path = dir.write("damaged" + extension, damaged);
      try {
        readMesh(path);
      } catch (const InputError& e) {
        EXPECT_EQ(std::string(e.what()).rfind(path, 0), 0u) << e.what();
      }
    }
  }
}

}  // namespace
}  // namespace kaboum::io
