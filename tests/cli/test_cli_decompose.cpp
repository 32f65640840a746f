// `kaboum decompose` as users run it: the OBJ with one object per piece, Table 4.3's figures in
// text and JSON, the options, and one clear line with exit code 2 for every class of bad input.
#include <gtest/gtest.h>

#include <algorithm>
#include <nlohmann/json.hpp>
#include <sstream>

#include "../support/test_support.hpp"
#include "kaboum/io/mesh_io.hpp"

namespace kaboum {

using namespace kaboum::io;
using namespace kaboum::testing;

namespace {

using test::CliResult;
using test::lineCount;
using test::quotedMesh;
using test::runCli;
using test::ScratchDir;

// Lines starting with `prefix` in the file.
std::size_t linesStartingWith(const std::string& text, const std::string& prefix) {
  std::istringstream in(text);
  std::size_t count = 0;
  for (std::string line; std::getline(in, line);) count += line.rfind(prefix, 0) == 0 ? 1 : 0;
  return count;
}

TEST(DecomposeCli, JsonMatchesTheWrittenPieces) {
  ScratchDir dir;
  const std::string out = dir.file("base.obj");
  const CliResult r = runCli(
      dir, "decompose " + quotedMesh("kr5-base-link.stl") + " -o '" + out + "' --json --quiet");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_EQ(r.err, "");  // --quiet
  const nlohmann::json j = nlohmann::json::parse(r.out);
  for (const char* key : {"pieces", "total_vertices", "vertices_per_piece", "distances", "seconds",
                          "epsilon", "stop_reason", "holes_filled"}) {
    EXPECT_TRUE(j.contains(key)) << key;
  }
  EXPECT_GT(j["holes_filled"].get<int>(), 0);                              // the base link is open
  EXPECT_NEAR(j["epsilon_percent_of_diagonal"].get<double>(), 3.0, 1e-9);  // the default
  const auto pieces = j["pieces"].get<std::size_t>();
  EXPECT_GE(pieces, 1u);
  EXPECT_LE(pieces, 12u);  // the default limit
  const std::string obj = test::slurp(out);
  EXPECT_EQ(linesStartingWith(obj, "o piece_"), pieces);
  EXPECT_EQ(linesStartingWith(obj, "o piece_0"), 1u);
  EXPECT_EQ(linesStartingWith(obj, "v "), j["total_vertices"].get<std::size_t>());
  // Readable as one mesh (coincident corners of neighbouring pieces are welded on reading).
  const TriangleMesh written = readMesh(out);
  EXPECT_EQ(written.triangleCount(), linesStartingWith(obj, "f "));
  EXPECT_LE(written.vertexCount(), j["total_vertices"].get<std::size_t>());
  const auto& perPiece = j["vertices_per_piece"];
  EXPECT_LE(perPiece["min"].get<double>(), perPiece["mean"].get<double>());
  EXPECT_LE(perPiece["mean"].get<double>(), perPiece["max"].get<double>());
  const auto& distances = j["distances"];
  EXPECT_EQ(distances["uncovered_samples"].get<int>(), 0);
  for (const char* direction : {"original_to_approximation", "approximation_to_original"}) {
    const auto& d = distances[direction];
    EXPECT_LE(d["min"].get<double>(), d["mean"].get<double>()) << direction;
    EXPECT_LE(d["mean"].get<double>(), d["max"].get<double>()) << direction;
  }
}

TEST(DecomposeCli, TextReportsTable43Columns) {
  ScratchDir dir;
  const CliResult r = runCli(dir, "decompose " + quotedMesh("kr5-wrist.stl") + " -o '" +
                                      dir.file("w.obj") + "' --epsilon 4% --max-pieces 5");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  for (const char* text : {"convex pieces", "vertices per convex: min",
                           "epsilon:", "distance original->approximation: max",
                           "distance approximation->original: max", "time:"}) {
    EXPECT_NE(r.out.find(text), std::string::npos) << text << "\n" << r.out;
  }
  EXPECT_NE(r.out.find("(closed)"), std::string::npos) << r.out;
  EXPECT_NE(r.err.find("decompose:"), std::string::npos);  // progress without --quiet
}

TEST(DecomposeCli, PieceLimitAndAbsoluteEpsilonAreApplied) {
  ScratchDir dir;
  const CliResult r =
      runCli(dir, "decompose " + quotedMesh("kr5-wrist.stl") + " -o '" + dir.file("w.obj") +
                      "' --epsilon 0.004 --max-pieces 2 --json -q");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  EXPECT_LE(j["pieces"].get<int>(), 2);
  EXPECT_DOUBLE_EQ(j["epsilon"].get<double>(), 0.004);
  EXPECT_EQ(j["max_pieces"].get<int>(), 2);
}

// --refine re-cuts the worst piece after merging; the JSON counts the kept moves and the
// estimate it reports is below the one without re-cuts.
TEST(DecomposeCli, RefineReCutsAndReportsTheMoves) {
  ScratchDir dir;
  const auto run = [&](const std::string& extra) {
    const CliResult r = runCli(dir, "decompose " + quotedMesh("kr5-wrist.stl") + " -o '" +
                                        dir.file("w.obj") + "' --json -q --samples 2000" + extra);
    EXPECT_EQ(r.exitCode, 0) << r.err;
    return nlohmann::json::parse(r.out);
  };
  const nlohmann::json plain = run("");
  const nlohmann::json refined = run(" --refine 10");
  EXPECT_EQ(plain["refinements"].get<int>(), 0);
  EXPECT_GT(refined["refinements"].get<int>(), 0);
  EXPECT_LE(refined["refinements"].get<int>(), 10);
  EXPECT_LT(refined["estimated_error"].get<double>(), plain["estimated_error"].get<double>());
  EXPECT_EQ(refined["distances"]["uncovered_samples"].get<int>(), 0);
}

// Every class of bad input: exit code 2 and one line on stderr naming the culprit.
TEST(DecomposeCli, BadInputIsOneLineAndExitCode2) {
  ScratchDir dir;
  const std::string empty = dir.write("empty.obj", "# nothing\n");
  const std::string nan = dir.write("nan.obj", "v 0 0 0\nv 1 0 0\nv nan 1 0\nv 0 0 1\nf 1 2 3\n");
  const std::string flat =
      dir.write("flat.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3\nf 1 3 4\n");
  const std::string out = " -o '" + dir.file("out.obj") + "'";
  struct Case {
    std::string arguments, mentions;
  };
  const std::vector<Case> cases{
      {"decompose '" + dir.file("missing.stl") + "'" + out, "missing.stl"},
      {"decompose '" + empty + "'" + out, "empty.obj"},
      {"decompose '" + nan + "'" + out, "nan.obj"},
      {"decompose '" + flat + "'" + out, "flat.obj"},
      {"decompose " + quotedMesh("cube.off") + out + " --epsilon abc", "--epsilon"},
      {"decompose " + quotedMesh("cube.off") + out + " --epsilon -1%", "--epsilon"},
      {"decompose " + quotedMesh("cube.off") + out + " --max-pieces 0", "--max-pieces"},
      {"decompose " + quotedMesh("cube.off") + out + " --refine 1001", "--refine"},
      {"decompose " + quotedMesh("cube.off") + out + " --refine -1", "--refine"},
      {"decompose " + quotedMesh("cube.off") + " -o '" + dir.file("no/such/dir/out.obj") + "'",
       "out.obj"},
      {"decompose " + quotedMesh("cube.off"), "--output"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.arguments);
    const CliResult r = runCli(dir, c.arguments + " -q");
    EXPECT_EQ(r.exitCode, 2) << r.out << r.err;
    EXPECT_EQ(lineCount(r.err), 1u) << r.err;
    EXPECT_NE(r.err.find(c.mentions), std::string::npos) << r.err;
  }
}

}  // namespace
}  // namespace kaboum
