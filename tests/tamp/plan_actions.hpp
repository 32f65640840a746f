// The actions of a plan file without branches (docs/plan-format.md), by name in execution order:
// what tests of a scenario's plans assert on. Shared by the tamp tests.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace kaboum::tamp {

inline std::vector<std::string> planActions(const nlohmann::json& plan) {
  std::vector<std::string> names;
  for (int node = plan["root"]; plan["nodes"][node]["kind"] == "action";
       node = plan["nodes"][node]["next"]) {
    names.push_back(plan["nodes"][node]["action"]);
  }
  return names;
}

}  // namespace kaboum::tamp
