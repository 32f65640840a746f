// Validator tests: accepts correct plans, names the failing step and condition otherwise, and
// reports bad plan files as file:line:col errors.
#include <gtest/gtest.h>

#include "kaboum/core/error.hpp"
#include "symbolic_test_support.hpp"

namespace kaboum::symbolic {

using namespace kaboum::testing;

namespace {

using testing::pddlPath;

class Validator : public ::testing::Test {
 protected:
  ValidationResult check(const std::string& planText) {
    const std::vector<PlanStep> steps = parsePlan(planText, "plan.txt", domain_, problem_);
    AttachmentRuntime attachments(domain_, problem_, {});
    return validatePlan(domain_, problem_, steps, attachments);
  }

  Domain domain_ = loadDomain(pddlPath("adl/domain.pddl"));
  Problem problem_ = loadProblem(pddlPath("adl/problem.pddl"), domain_);
};

const char* kGoodPlan = R"((drive home a)
(drive a b)
(pick brush b)
(drive b c)
(pick box c) ; comments are ignored
(paint c)
(drive c b)
(drive b a)
(DRIVE a home)
(drop box home)
)";

TEST_F(Validator, AcceptsACorrectPlan) {
  const ValidationResult result = check(kGoodPlan);
  EXPECT_TRUE(result.valid) << result.message;
  EXPECT_EQ(result.message, "valid plan of 10 step(s)");
}

TEST_F(Validator, NamesTheFailingStepAndCondition) {
  ValidationResult result = check("(drive home b)\n");
  EXPECT_FALSE(result.valid);
  EXPECT_EQ(result.failedStep, 1u);
  EXPECT_EQ(result.message,
            "step 1 (drive home b): precondition (or (road home b) (road b home)) is false");
  result = check("(drive home a)\n(drive a b)\n(drive b c)\n(paint c)\n");
  EXPECT_EQ(result.failedStep, 4u);
  EXPECT_EQ(result.message,
            "step 4 (paint c): precondition (exists (?t - tool) (carrying ?t)) is false");
  result = check("(drive home a)\n(drive a b)\n(pick brush b)\n(drive b c)\n(paint c)\n");
  EXPECT_EQ(result.failedStep, 5u);
  EXPECT_EQ(result.message,
            "step 5 (paint c): precondition (imply (at box c) (carrying box)) is false");
  result = check("(drive home a)\n(pick box a)\n");
  EXPECT_EQ(result.message, "step 2 (pick box a): precondition (at box a) is false");
}

TEST_F(Validator, ReportsAnUnreachedGoal) {
  const ValidationResult result = check("(drive home a)\n");
  EXPECT_FALSE(result.valid);
  EXPECT_EQ(result.failedStep, 0u);
  EXPECT_EQ(result.message, "goal not reached after 1 step(s): (painted c) is false");
}

TEST_F(Validator, RejectsArgumentsOfTheWrongType) {
  const ValidationResult result = check("(pick box box)\n");
  EXPECT_EQ(result.message, "step 1 (pick box box): argument 'box' is not of type 'location'");
}

TEST_F(Validator, BadPlanFilesAreInputErrors) {
  const auto expectError = [&](const std::string& text, const std::string& message) {
    try {
      parsePlan(text, "plan.txt", domain_, problem_);
      ADD_FAILURE() << "expected " << message;
    } catch (const InputError& e) {
      EXPECT_EQ(std::string(e.what()), message);
    }
  };
  expectError("(fly home a)", "plan.txt:1:2: undefined action 'fly'");
  expectError("\n(drive home)", "plan.txt:2:1: action 'drive' takes 2 argument(s), 1 given");
  expectError("(drive home mars)", "plan.txt:1:13: undefined object 'mars'");
  expectError("(drive home a", "plan.txt:1:1: expected ')' to close the list opened here");
  expectError("drive", "plan.txt:1:1: expected '(action args ...)'");
}

}  // namespace
}  // namespace kaboum::symbolic
