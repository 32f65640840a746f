// `kaboum validate DOMAIN PROBLEM PLAN`: replays a plan and names the first failing step.
#include <iostream>
#include <memory>

#include "kaboum/io/json_symbolic.hpp"
#include "kaboum/symbolic/sexpr.hpp"
#include "kaboum/symbolic/validator.hpp"
#include "verb.hpp"

namespace kaboum::cli {

using namespace kaboum::symbolic;

namespace {

struct ValidateOptions {
  std::string domain;
  std::string problem;
  std::string plan;
  bool json = false;
};

int runValidate(const ValidateOptions& options) {
  const symbolic::Domain domain = symbolic::loadDomain(options.domain);
  const symbolic::Problem problem = symbolic::loadProblem(options.problem, domain);
  printWarnings(domain.warnings);
  printWarnings(problem.warnings);
  const std::vector<symbolic::PlanStep> plan =
      symbolic::parsePlan(symbolic::readTextFile(options.plan), options.plan, domain, problem);
  symbolic::AttachmentRuntime attachments(domain, problem, symbolic::ProcedureRegistry{});
  const symbolic::ValidationResult result =
      symbolic::validatePlan(domain, problem, plan, attachments);
  if (options.json) {
    nlohmann::json out = io::toJson(result);
    out["steps"] = plan.size();
    std::cout << out.dump(2) << "\n";
  } else {
    std::cout << (result.valid ? "" : "invalid: ") << result.message << "\n";
  }
  return result.valid ? 0 : 1;
}

VerbRunner setupValidate(CLI::App& command) {
  auto options = std::make_shared<ValidateOptions>();
  command.add_option("domain", options->domain, "PDDL domain file")->required();
  command.add_option("problem", options->problem, "PDDL problem file")->required();
  command.add_option("plan", options->plan, "Plan file, one (action args) per line")->required();
  command.add_flag("--json", options->json, "Print the verdict as JSON");
  return [options] { return runValidate(*options); };
}

const VerbRegistration registration{
    "validate", "Check a plan against a PDDL domain and problem (exit 0 valid, 1 invalid)",
    setupValidate};

}  // namespace
}  // namespace kaboum::cli
