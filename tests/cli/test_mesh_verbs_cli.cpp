// `kaboum bound` and `kaboum check` as users run them: outputs, JSON fields, exit codes, and one
// clear line with exit code 2 for every class of bad input.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
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

TEST(BoundCli, JsonReportsTheRunAndTheWrittenMeshMatchesIt) {
  ScratchDir dir;
  const std::string out = dir.file("wrist-outer.obj");
  const CliResult r = runCli(
      dir, "bound " + quotedMesh("kr5-wrist.stl") + " -o '" + out + "' --ratio 0.3 --json --quiet");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_EQ(r.err, "");  // --quiet: no progress
  const nlohmann::json j = nlohmann::json::parse(r.out);
  for (const char* key : {"input_vertices", "output_vertices", "contractions", "seconds",
                          "contractions_per_second", "stop_reason", "hausdorff"}) {
    EXPECT_TRUE(j.contains(key)) << key;
  }
  const TriangleMesh written = readMesh(out);
  EXPECT_EQ(written.vertices.size(), j["output_vertices"].get<std::size_t>());
  EXPECT_EQ(j["input_vertices"].get<std::size_t>() - j["contractions"].get<std::size_t>(),
            j["output_vertices"].get<std::size_t>());
  EXPECT_EQ(j["output_vertices"].get<std::size_t>(),
            static_cast<std::size_t>(std::ceil(0.3 * j["input_vertices"].get<double>())));
  EXPECT_EQ(j["side"], "outer");
}

TEST(BoundCli, OuterAndInnerResultsAreVerifiedByCheck) {
  ScratchDir dir;
  for (const std::string side : {"outer", "inner"}) {
    const std::string out = dir.file("spot-" + side + ".ply");
    const CliResult bound = runCli(dir, "bound " + quotedMesh("spot.obj") + " -o '" + out + "' --" +
                                            side + " --vertices 400 -q");
    ASSERT_EQ(bound.exitCode, 0) << bound.err;
    const CliResult check =
        runCli(dir, "check " + quotedMesh("spot.obj") + " '" + out + "' --" + side + " --json");
    ASSERT_EQ(check.exitCode, 0) << check.out << check.err;
    const nlohmann::json j = nlohmann::json::parse(check.out);
    EXPECT_TRUE(j["verified"].get<bool>());
    EXPECT_EQ(j["violations"], 0);
    EXPECT_GT(j["samples_checked"].get<std::size_t>(), 1000u);
  }
  // The outer result is not an inner bound: check must say so with exit code 1.
  const CliResult wrong = runCli(
      dir, "check " + quotedMesh("spot.obj") + " '" + dir.file("spot-outer.ply") + "' --inner");
  EXPECT_EQ(wrong.exitCode, 1);
  EXPECT_NE(wrong.out.find("VIOLATED"), std::string::npos) << wrong.out;
}

TEST(BoundCli, CheckRejectsAnInsideOutResult) {
  ScratchDir dir;
  const std::string out = dir.file("spot-outer.obj");
  ASSERT_EQ(
      runCli(dir, "bound " + quotedMesh("spot.obj") + " -o '" + out + "' --ratio 0.2 -q").exitCode,
      0);
  TriangleMesh flipped = readMesh(out);
  for (Triangle& t : flipped.triangles) std::swap(t[1], t[2]);
  writeMesh(flipped, dir.file("flipped.obj"));
  const CliResult r =
      runCli(dir, "check " + quotedMesh("spot.obj") + " '" + dir.file("flipped.obj") + "' --json");
  EXPECT_EQ(r.exitCode, 1) << r.out << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  EXPECT_TRUE(j["inside_out"].get<bool>());
  EXPECT_FALSE(j["verified"].get<bool>());
}

// The documented reduction: at 1% of the diagonal, closed inputs above 10^4 vertices shrink 10x.
// --polish lowers the distances without breaking the bound, with an --epsilon limit too.
TEST(BoundCli, PolishLowersTheDistancesAndCheckVerifiesTheResult) {
  ScratchDir dir;
  const std::string wrist = quotedMesh("kr5-wrist.stl");
  const auto sum = [](const nlohmann::json& j, const char* figure) {
    return j["hausdorff"]["original_to_result"][figure].get<double>() +
           j["hausdorff"]["result_to_original"][figure].get<double>();
  };
  for (const std::string target : {"--ratio 0.2", "--epsilon 3%"}) {
    const std::string out = dir.file("wrist.obj");
    const CliResult plain =
        runCli(dir, "bound " + wrist + " -o '" + out + "' " + target + " --json -q");
    const CliResult polished =
        runCli(dir, "bound " + wrist + " -o '" + out + "' " + target + " --polish --json -q");
    ASSERT_EQ(plain.exitCode, 0) << plain.err;
    ASSERT_EQ(polished.exitCode, 0) << polished.err;
    const nlohmann::json j0 = nlohmann::json::parse(plain.out);
    const nlohmann::json j1 = nlohmann::json::parse(polished.out);
    EXPECT_FALSE(j0["polish"]["enabled"].get<bool>()) << target;
    EXPECT_TRUE(j1["polish"]["enabled"].get<bool>()) << target;
    EXPECT_GT(j1["polish"]["moves"].get<int>(), 0) << target;
    ASSERT_TRUE(j1["polish"]["relocations"].is_number_unsigned()) << target;
    EXPECT_LE(j1["polish"]["relocations"].get<int>(), 10) << target;  // the default cap
    EXPECT_EQ(j1["output_vertices"], j0["output_vertices"]) << target;
    EXPECT_LE(sum(j1, "max_percent_of_diagonal"), sum(j0, "max_percent_of_diagonal")) << target;
    EXPECT_LT(sum(j1, "mean"), sum(j0, "mean")) << target;
    if (target == "--epsilon 3%") {
      EXPECT_LE(j1["hausdorff"]["original_to_result"]["max_percent_of_diagonal"].get<double>(),
                3.0);
      EXPECT_LE(j1["hausdorff"]["result_to_original"]["max_percent_of_diagonal"].get<double>(),
                3.0);
    }
    const CliResult check = runCli(dir, "check " + wrist + " '" + out + "' --outer");
    EXPECT_EQ(check.exitCode, 0) << target << check.out;
  }
}

TEST(BoundCli, EpsilonIsADistanceInPercentOfTheDiagonal) {
  ScratchDir dir;
  const CliResult r = runCli(dir, "bound " + quotedMesh("rocker-arm.obj") + " -o '" +
                                      dir.file("r.obj") + "' --epsilon 1% --json -q");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  EXPECT_LE(j["hausdorff"]["original_to_result"]["max_percent_of_diagonal"].get<double>(), 1.0);
  EXPECT_LE(j["hausdorff"]["result_to_original"]["max_percent_of_diagonal"].get<double>(), 1.0);
  ASSERT_GT(j["input_vertices"].get<int>(), 10000);
  EXPECT_LT(j["output_vertices"].get<int>() * 10, j["input_vertices"].get<int>());
}

// An --epsilon search simplifies several times: stderr shows one numbered progress line per run.
TEST(BoundCli, EpsilonSearchShowsOneProgressLinePerRun) {
  ScratchDir dir;
  const CliResult r = runCli(dir, "bound " + quotedMesh("kr5-wrist.stl") + " -o '" +
                                      dir.file("w.obj") + "' --epsilon 2% --json");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const int runs = nlohmann::json::parse(r.out)["runs"].get<int>();
  ASSERT_GT(runs, 1);
  std::istringstream lines(r.err);
  std::string line;
  int seen = 0;
  while (std::getline(lines, line)) {
    ++seen;
    EXPECT_TRUE(line.ends_with(fmt::format("bound run {}: 100%", seen))) << line;
  }
  EXPECT_EQ(seen, runs) << r.err;
}

TEST(BoundCli, OpenInputsAreSimplifiedAndCheckSaysContainmentIsUndefined) {
  ScratchDir dir;
  const std::string out = dir.file("base.obj");
  const CliResult bound =
      runCli(dir, "bound " + quotedMesh("kr5-base-link.stl") + " -o '" + out + "' --ratio 0.5 -q");
  ASSERT_EQ(bound.exitCode, 0) << bound.err;
  EXPECT_NE(bound.out.find("containment is only defined for closed meshes"), std::string::npos);
  const CliResult check =
      runCli(dir, "check " + quotedMesh("kr5-base-link.stl") + " '" + out + "'");
  EXPECT_EQ(check.exitCode, 0);
  EXPECT_NE(check.out.find("not defined"), std::string::npos) << check.out;
}

TEST(BoundCli, EveryVerbHasHelp) {
  ScratchDir dir;
  for (const std::string verb : {"bound", "check"}) {
    const CliResult r = runCli(dir, verb + " --help");
    EXPECT_EQ(r.exitCode, 0);
    EXPECT_NE(r.out.find("--json"), std::string::npos) << verb;
  }
}

// A Möbius strip: readable, but no consistent orientation exists.
std::string writeMoebius(const ScratchDir& dir) {
  std::ostringstream obj;
  const int n = 12;
  for (int i = 0; i < n; ++i) {
    const double t = 2.0 * M_PI * i / n;
    for (const double s : {-0.3, 0.3}) {
      obj << "v " << (1 + s * std::cos(t / 2)) * std::cos(t) << " "
          << (1 + s * std::cos(t / 2)) * std::sin(t) << " " << s * std::sin(t / 2) << "\n";
    }
  }
  for (int i = 0; i < n; ++i) {
    const int a = 2 * i + 1, b = 2 * i + 2;
    const int c = i + 1 < n ? a + 2 : 2, d = i + 1 < n ? b + 2 : 1;  // the strip joins twisted
    obj << "f " << a << " " << b << " " << d << "\nf " << a << " " << d << " " << c << "\n";
  }
  return dir.write("moebius.obj", obj.str());
}

TEST(BoundCli, BadInputGivesOneLineAndExitCodeTwo) {
  ScratchDir dir;
  const std::string out = "-o '" + dir.file("out.obj") + "'";
  const std::string cow = quotedMesh("cow.obj");
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"bound '" + dir.file("missing.obj") + "' " + out + " --ratio 0.5", "missing.obj"},
      {"bound " + cow + " " + out, "give a target"},
      {"bound " + cow + " " + out + " --ratio 2", "--ratio"},
      {"bound " + cow + " " + out + " --ratio 0.5 --vertices 10", "--vertices"},
      {"bound " + cow + " " + out + " --epsilon abc", "--epsilon"},
      {"bound " + cow + " " + out + " --epsilon -1%", "--epsilon"},
      {"bound " + cow + " -o '" + dir.file("out.xyz") + "' --ratio 0.5", "out.xyz"},
      {"bound " + cow + " " + out + " --ratio 0.5 --cost volume", "--cost"},
      {"bound " + cow + " " + out + " --ratio 0.5 --polish --relocations -1", "--relocations"},
      {"bound '" + writeMoebius(dir) + "' " + out + " --ratio 0.5", "moebius.obj"},
      {"check " + cow + " '" + dir.file("missing.obj") + "'", "missing.obj"},
  };
  for (const auto& [arguments, mention] : cases) {
    const bool isBound = arguments.rfind("bound", 0) == 0;
    const CliResult r = runCli(dir, arguments + (isBound ? " -q" : ""));
    EXPECT_EQ(r.exitCode, 2) << arguments << "\n" << r.err;
    EXPECT_EQ(lineCount(r.err), 1u) << arguments << "\n" << r.err;
    EXPECT_NE(r.err.find(mention), std::string::npos) << arguments << "\n" << r.err;
  }
}

}  // namespace
}  // namespace kaboum
