// The viewer's page (docs/viewer.md): the packed geometry unpacks to the meshes within their
// quantization step, the page holds the scene, the plan timed as `kaboum execute` times it and the
// viewer script, and `kaboum view` writes it or reports bad input in one line. The page in a real
// browser: viewer/test/browser_test.mjs (ViewerBrowser.*).
#include <gtest/gtest.h>
#include <zlib.h>

#include <nlohmann/json.hpp>

#include "../exec/exec_fixtures.hpp"
#include "kaboum/web/geometry_pack.hpp"
#include "kaboum/web/plan_page.hpp"
#include "kaboum/web/viewer_script.hpp"

namespace kaboum::web {

namespace {

std::vector<std::uint8_t> fromBase64(const std::string& text) {
  const std::string alphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::vector<std::uint8_t> out;
  std::uint32_t word = 0;
  int bits = 0;
  for (const char c : text) {
    if (c == '=') break;
    word = (word << 6) | static_cast<std::uint32_t>(alphabet.find(c));
    bits += 6;
    if (bits >= 8) {
      bits -= 8;
      out.push_back(static_cast<std::uint8_t>((word >> bits) & 0xff));
    }
  }
  return out;
}

// The values of one packed stream: base64, then inflated.
template <typename Value>
std::vector<Value> unpack(const std::string& text, std::size_t count) {
  const std::vector<std::uint8_t> deflated = fromBase64(text);
  std::vector<Value> values(count);
  uLongf size = static_cast<uLongf>(count * sizeof(Value));
  EXPECT_EQ(uncompress(reinterpret_cast<Bytef*>(values.data()), &size, deflated.data(),
                       static_cast<uLong>(deflated.size())),
            Z_OK);
  EXPECT_EQ(size, count * sizeof(Value));
  return values;
}

// The page's data element.
nlohmann::json pageData(const std::string& html) {
  const std::string open = "<script type=\"application/json\" id=\"kaboum-data\">";
  const std::size_t start = html.find(open) + open.size();
  return nlohmann::json::parse(html.substr(start, html.find("</script>", start) - start));
}

std::string quoted(const std::string& path) {
  return "'" + path + "' ";
}

std::string pickAndPlaceFiles() {
  const auto example = [](const std::string& file) {
    return quoted(testing::exampleFile("pick-and-place/" + file));
  };
  return "--domain " + example("domain.pddl") + "--problem " + example("problem.pddl") +
         "--scene " + example("scene.yaml") + test::sharedCacheOption() + " ";
}

// Exit code 2 and one line on stderr containing `message`.
void expectBadInput(const test::CliResult& result, const std::string& message) {
  EXPECT_EQ(result.exitCode, 2) << result.out << result.err;
  EXPECT_EQ(test::lineCount(result.err), 1U) << result.err;
  EXPECT_NE(result.err.find(message), std::string::npos) << result.err;
}

}  // namespace

TEST(GeometryPack, UnpacksEveryMeshWithinItsQuantizationStep) {
  const geometry::TriangleMesh mesh{{{0, 0, 0}, {1, 0, 0}, {0, 0.3, 0}, {0.123456, 0.2, -0.7}},
                                    {{0, 1, 2}, {0, 2, 3}, {0, 3, 1}, {1, 3, 2}}};
  const std::vector<Vec3> piece{{5, 5, 5}, {5.5, 5, 5}, {5, 5.25, 5}, {5, 5, 6}};
  GeometryPack pack;
  EXPECT_EQ(pack.addMesh(mesh), 0U);
  EXPECT_EQ(pack.addPoints(piece), 1U);
  const nlohmann::json json = pack.json();
  const std::vector<std::uint16_t> positions = unpack<std::uint16_t>(json["positions"], 8 * 3);
  const std::vector<std::uint32_t> indices = unpack<std::uint32_t>(json["indices"], 12);
  const auto check = [&](const nlohmann::json& entry, std::span<const Vec3> points) {
    const std::size_t first = entry["positions"][0];
    ASSERT_EQ(entry["positions"][1], points.size());
    for (std::size_t i = 0; i < points.size(); ++i) {
      for (int axis = 0; axis < 3; ++axis) {
        const double step = entry["step"][axis];
        const double value = double(entry["min"][axis]) + positions[(first + i) * 3 + axis] * step;
        EXPECT_NEAR(value, points[i][axis], step / 2 + 1e-12) << i << " " << axis;
      }
    }
  };
  check(json["entries"][0], mesh.vertices);
  check(json["entries"][1], piece);
  EXPECT_EQ(json["entries"][0]["indices"], nlohmann::json::array({0, 12}));
  EXPECT_EQ(json["entries"][1]["indices"][1], 0);
  EXPECT_EQ(indices[4], 2U);
  EXPECT_EQ(indices[10], 3U);
}

TEST(PlanPage, HoldsTheSceneThePlanTimedAsExecutionTimesItAndTheViewerScript) {
  exec::ExampleRun& run = exec::bartender();
  const PlanPage page = planPage(run.world(), run.task(), run.plan(), {"bartender-1", {}});
  EXPECT_NE(page.html.find(viewerScript()), std::string::npos);
  EXPECT_GT(viewerScript().size(), 100000U);  // three.js is in
  EXPECT_EQ(page.summary.bytes, page.html.size());
  const nlohmann::json data = pageData(page.html);
  EXPECT_EQ(data["title"], "bartender-1");
  ASSERT_EQ(data["robots"].size(), run.world().robots().size());
  EXPECT_EQ(data["robots"][0]["links"].size(),
            run.world().robots()[0].collision.model().links().size());
  EXPECT_EQ(data["objects"].size(), run.world().description().objects.size());
  EXPECT_EQ(data["locations"].size(), run.world().description().locations.size());
  EXPECT_EQ(page.summary.branches, 1U);
  EXPECT_GT(page.summary.pieces, page.summary.meshes);

  // The true outcome's way: the page's action durations add up to the executed duration.
  exec::ExecutionOptions options;
  options.sensing = [](const exec::SensingQuery&) { return true; };
  const exec::ExecutionResult executed =
      exec::execute(run.world(), run.task(), run.plan(), options);
  double seconds = 0;
  for (int n = data["root"]; data["nodes"][n]["kind"] != "goal";) {
    const nlohmann::json& node = data["nodes"][n];
    if (node["kind"] == "branch") {
      n = node["on_true"];
    } else {
      seconds += double(node["duration"]);
      n = node["next"];
    }
  }
  EXPECT_NEAR(seconds, executed.schedule.duration(), 1e-9);
  EXPECT_NEAR(page.summary.duration, executed.schedule.duration(), 1e-9);
}

TEST(PlanPage, LinkPosesAtTheStartAreTheRobotsAtHome) {
  exec::ExampleRun& run = exec::pickAndPlace();
  const std::vector<double> times{0.0};
  const nlohmann::json poses = linkPosesAt(run.world(), run.task(), run.plan(), {}, times);
  const world::WorldRobot& robot = run.world().robots()[0];
  const kinematics::RobotModel& model = robot.collision.model();
  std::vector<Pose> home(model.links().size());
  model.linkPoses(robot.home, home);
  const nlohmann::json& links = poses[0]["robots"][robot.name];
  ASSERT_EQ(links.size(), home.size());
  for (std::size_t l = 0; l < home.size(); ++l) {
    const Vec3 expected = (robot.collision.basePose() * home[l]).translation();
    const nlohmann::json& position = links[model.links()[l].name]["position"];
    for (int axis = 0; axis < 3; ++axis) EXPECT_NEAR(position[axis], expected[axis], 1e-12);
  }
}

TEST(ViewCli, WritesTheSelfContainedPageAndItsSummary) {
  test::ScratchDir dir;
  const test::CliResult result =
      test::runCli(dir, "view " + quoted(exec::execData("pick-and-place.plan.json")) +
                            pickAndPlaceFiles() + "-o " + quoted(dir.file("page.html")) + "--json");
  ASSERT_EQ(result.exitCode, 0) << result.err;
  const nlohmann::json summary = nlohmann::json::parse(result.out);
  const std::string html = test::slurp(dir.file("page.html"));
  EXPECT_EQ(summary["bytes"], html.size());
  EXPECT_EQ(summary["actions"], 2);
  EXPECT_EQ(summary["branches"], 0);
  EXPECT_GT(summary["duration"], 1.0);
  EXPECT_EQ(pageData(html)["title"], "pick-and-place.plan.json");
}

TEST(SolveCli, HtmlWritesThePageOfThePlanItFound) {
  test::ScratchDir dir;
  const auto example = [](const std::string& file) {
    return quoted(testing::exampleFile("pick-and-place/" + file));
  };
  const std::string solve = "solve " + example("domain.pddl") + example("problem.pddl") +
                            example("scene.yaml") + test::sharedCacheOption() + " --quiet --html ";
  const test::CliResult result = test::runCli(dir, solve + quoted(dir.file("page.html")));
  ASSERT_EQ(result.exitCode, 0) << result.err;
  const nlohmann::json data = pageData(test::slurp(dir.file("page.html")));
  std::size_t actions = 0;
  for (const nlohmann::json& node : data["nodes"]) actions += node["kind"] == "action" ? 1 : 0;
  EXPECT_EQ(actions, 2U);
  expectBadInput(test::runCli(dir, solve + quoted(dir.file("missing/page.html"))),
                 "page.html: cannot write the page");
}

TEST(ViewCli, BadInputIsOneLineWithExitCodeTwo) {
  test::ScratchDir dir;
  const std::string plan = test::slurp(exec::execData("pick-and-place.plan.json"));
  nlohmann::json noScene = nlohmann::json::parse(plan);
  noScene["domain"] = testing::exampleFile("pick-and-place/domain.pddl");
  noScene["problem"] = testing::exampleFile("pick-and-place/problem.pddl");
  noScene.erase("scene");
  const std::string noSceneFile = dir.write("no-scene.json", noScene.dump());
  expectBadInput(
      test::runCli(dir, "view " + quoted(noSceneFile) + "-o " + quoted(dir.file("page.html"))),
      "no-scene.json: scene: expected the scene file's name (or give --scene)");
  const std::string planFile = quoted(exec::execData("pick-and-place.plan.json"));
  expectBadInput(test::runCli(dir, "view " + planFile + "-o " + quoted(dir.file("page.html"))),
                 "pick-and-place.plan.json: domain: 'examples/pick-and-place/domain.pddl' does not "
                 "exist here");
  expectBadInput(
      test::runCli(dir, "view " + planFile + pickAndPlaceFiles() + "--link-poses-at 0,soon"),
      "--link-poses-at: 'soon' is no time in seconds (>= 0)");
  expectBadInput(test::runCli(dir, "view " + planFile + pickAndPlaceFiles()),
                 "-o: give the page file to write");
  expectBadInput(test::runCli(dir, "view " + planFile + pickAndPlaceFiles() + "-o " +
                                       quoted(dir.file("missing/folder/page.html"))),
                 "page.html: cannot write the page");
}

}  // namespace kaboum::web
