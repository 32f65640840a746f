// Semantic attachment tests: procedures registered in code and loaded from a shared library that
// the test builds, memoization counts, and every binding error.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>

#include "kaboum/core/error.hpp"
#include "kaboum/symbolic/sexpr.hpp"
#include "kaboum/testing/data_paths.hpp"
#include "symbolic_test_support.hpp"

namespace kaboum::symbolic {

using namespace kaboum::testing;

namespace {

using testing::planAndValidate;

const std::string kExamples = kaboum::testing::exampleFile("attachments");

// The grid domain of the example, with procedures named for code registration.
std::string registeredGridDomain() {
  std::string text = readTextFile(kExamples + "/grid-domain.pddl");
  for (const std::string suffix : {"@libgrid_procedures.so"}) {
    for (std::size_t at = text.find(suffix); at != std::string::npos; at = text.find(suffix)) {
      text.erase(at, suffix.size());
    }
  }
  return text;
}

// A 4x4 maze with a wall column at x = 1 except at y = 3, key at (0, 3).
ProcedureRegistry mazeProcedures() {
  static const char* kMaze[4] = {".#..", ".#..", ".#..", "k..."};
  const auto target = [](const AttachmentArgs& args, long& x, long& y) {
    x = static_cast<long>(args.reads[0]);
    y = static_cast<long>(args.reads[1]);
    const std::string_view d = args.name(0);
    x += d == "east" ? 1 : d == "west" ? -1 : 0;
    y += d == "south" ? 1 : d == "north" ? -1 : 0;
    return x >= 0 && y >= 0 && x < 4 && y < 4 && kMaze[y][x] != '#';
  };
  ProcedureRegistry registry;
  registry.addChecker("canMove", [target](const AttachmentArgs& args) {
    long x = 0, y = 0;
    return target(args, x, y);
  });
  registry.addApplicator("applyMove", [target](const AttachmentArgs& args, std::span<double> out) {
    long x = 0, y = 0;
    if (!target(args, x, y)) return false;
    out[0] = static_cast<double>(x);
    out[1] = static_cast<double>(y);
    return true;
  });
  registry.addChecker("atKey", [](const AttachmentArgs& args) {
    return args.reads[0] == 0.0 && args.reads[1] == 3.0;
  });
  return registry;
}

TEST(Attachments, ProceduresRegisteredInCode) {
  const Domain domain = parseDomain(registeredGridDomain(), "grid.pddl");
  const Problem problem = parseProblem(
      "(define (problem p) (:domain grid-attachments) (:init (= (x) 0) (= (y) 0))"
      " (:goal (and (has-key) (= (x) 3) (= (y) 0))))",
      "p.pddl", domain);
  SearchOptions options;
  options.mode = "bfs";
  const PlanReport report = planAndValidate(domain, problem, options, mazeProcedures());
  ASSERT_EQ(report.search.status, PlannerStatus::Solved);
  // Down to the key (3), then around the wall and up: east 3, north 3.
  EXPECT_EQ(report.plan.size(), 3u + 1u + 3u + 3u);
  ASSERT_EQ(report.modules.size(), 3u);
  EXPECT_EQ(report.modules[0].name, "free");
  EXPECT_GT(report.modules[0].calls, 0u);
  // Each (direction, x, y) is evaluated once; everything else comes from the memo.
  EXPECT_LE(report.modules[0].calls - report.modules[0].cacheHits, 4u * 16u);
  EXPECT_GT(report.modules[1].cacheHits, 0u);
}

TEST(Attachments, UnsolvableWhenTheProcedureBlocksEveryPath) {
  const Domain domain = parseDomain(registeredGridDomain(), "grid.pddl");
  const Problem problem = parseProblem(
      "(define (problem p) (:domain grid-attachments) (:init (= (x) 0) (= (y) 0))"
      " (:goal (= (x) 9)))",
      "p.pddl", domain);
  SearchOptions options;
  options.mode = "bfs";
  EXPECT_EQ(plan(domain, problem, mazeProcedures(), options).search.status,
            PlannerStatus::Unsolvable);
}

// Builds examples/attachments/grid_procedures.cpp into `dir` with the system compiler.
std::string buildGridLibrary(const std::filesystem::path& dir) {
  std::filesystem::create_directories(dir);
  const std::string library = (dir / "libgrid_procedures.so").string();
  const std::string command =
      "c++ -std=c++20 -O1 -shared -fPIC -o " + library + " " + kExamples + "/grid_procedures.cpp";
  if (std::system(command.c_str()) != 0) return "";
  return library;
}

TEST(Attachments, ProceduresLoadedFromASharedLibrary) {
  const auto dir =
      std::filesystem::temp_directory_path() / ("kaboum_grid_" + std::to_string(::getpid()));
  ASSERT_FALSE(buildGridLibrary(dir).empty()) << "could not compile the grid procedures";
  // The library is found next to the domain file.
  std::filesystem::copy_file(kExamples + "/grid-domain.pddl", dir / "grid-domain.pddl",
                             std::filesystem::copy_options::overwrite_existing);
  const Domain domain = loadDomain((dir / "grid-domain.pddl").string());
  const Problem problem = loadProblem(kExamples + "/grid-problem.pddl", domain);
  SearchOptions options;
  options.mode = "bfs";
  const PlanReport report = planAndValidate(domain, problem, options);
  ASSERT_EQ(report.search.status, PlannerStatus::Solved);
  EXPECT_EQ(report.plan.size(), 24u);
  EXPECT_EQ(report.plan[0], "(move south)");
  SearchOptions greedy;
  EXPECT_EQ(planAndValidate(domain, problem, greedy).search.status, PlannerStatus::Solved);
  std::filesystem::remove_all(dir);
}

void expectBindingError(const std::string& modules, const std::string& message) {
  const Domain domain = parseDomain("(define (domain m) (:modules " + modules + "))", "m.pddl");
  const Problem problem =
      parseProblem("(define (problem p) (:domain m) (:goal (and)))", "p.pddl", domain);
  try {
    AttachmentRuntime runtime(domain, problem, ProcedureRegistry{});
    ADD_FAILURE() << "expected: " << message;
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()).substr(0, message.size()), message);
  }
}

TEST(Attachments, BindingErrorsNameTheModule) {
  expectBindingError("(m conditionchecker nowhere)",
                     "m.pddl:1:30: module 'm': no condition checker named 'nowhere' is registered");
  expectBindingError("(m effect nowhere)",
                     "m.pddl:1:30: module 'm': no effect applicator named 'nowhere' is registered");
  expectBindingError("(m conditionchecker f@libkaboum_missing.so)",
                     "m.pddl:1:30: module 'm': cannot load library 'libkaboum_missing.so'");
  // libm exists on every Linux system but has no symbol of this name.
  expectBindingError("(m conditionchecker noSuchSymbol@libm.so.6)",
                     "m.pddl:1:30: module 'm': symbol 'noSuchSymbol' not found in 'libm.so.6'");
}

}  // namespace
}  // namespace kaboum::symbolic
