// Plan validator (thesis §3.2 plan semantics): replays an IPC-format plan on the lifted domain,
// independently of the grounder and search, and names the first failing step and condition.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "kaboum/symbolic/attachments.hpp"
#include "kaboum/symbolic/pddl.hpp"

namespace kaboum::symbolic {

struct PlanStep {
  int action = 0;
  std::vector<ObjectId> args;
  SourcePos pos;
  std::string text;  // "(action arg ...)"
};

// Parses one "(action args)" per line; ';' starts a comment. Throws InputError (file:line:col) for
// unknown actions or objects and wrong argument counts.
std::vector<PlanStep> parsePlan(std::string_view text, const std::string& file,
                                const Domain& domain, const Problem& problem);

struct ValidationResult {
  bool valid = false;
  std::size_t failedStep = 0;  // 1-based; 0 when every step applied (then the goal failed)
  std::string message;         // what failed, e.g. "precondition (clear b) is false"
};

ValidationResult validatePlan(const Domain& domain, const Problem& problem,
                              const std::vector<PlanStep>& plan, AttachmentRuntime& attachments);

}  // namespace kaboum::symbolic
