#include "symbolic_test_support.hpp"

#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "kaboum/core/error.hpp"

namespace kaboum::symbolic::testing {

using namespace kaboum::testing;

std::string errorOf(const std::string& domain, const std::string& problem) {
  try {
    const ContingentProblem contingent = parseContingent(domain, "d.pddl", problem, "p.pddl");
    KnowledgeTask task(contingent, ProcedureRegistry{});
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

ContingentResult solveAndValidate(KnowledgeTask& task, const ContingentOptions& options) {
  ContingentResult result = solveContingent(task, options);
  if (result.status == PlannerStatus::Solved) {
    const std::string text = formatPlanTree(task, result.plan);
    const PlanTree parsed = parsePlanTree(text, "plan", task);
    const TreeValidation validation = validatePlanTree(task, parsed, "plan");
    EXPECT_TRUE(validation.valid) << validation.message << "\n" << text;
    const TreeMetrics original = measure(result.plan);
    EXPECT_EQ(validation.metrics.actions, original.actions);
    EXPECT_EQ(validation.metrics.leaves, original.leaves);
  }
  return result;
}

CommandResult runCli(const std::string& arguments) {
  CommandResult result;
  const std::string command = std::string(KABOUM_CLI) + " " + arguments + " 2>&1";
  FILE* pipe = popen(command.c_str(), "r");
  if (pipe == nullptr) return result;
  std::array<char, 4096> buffer{};
  std::size_t n = 0;
  while ((n = fread(buffer.data(), 1, buffer.size(), pipe)) > 0)
    result.output.append(buffer.data(), n);
  const int status = pclose(pipe);
  result.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return result;
}

std::string writeTempFile(const std::string& name, const std::string& text) {
  const auto dir = std::filesystem::temp_directory_path() /
                   ("kaboum_symbolic_test_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const auto path = dir / name;
  std::ofstream(path) << text;
  return path.string();
}

}  // namespace kaboum::symbolic::testing
