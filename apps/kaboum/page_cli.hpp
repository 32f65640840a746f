// Writing a plan's web page for the verbs that do (`kaboum view`, `kaboum solve --html`;
// docs/viewer.md): the page file, and the summary they print.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "kaboum/web/plan_page.hpp"

namespace kaboum::cli {

// Writes the page of `plan` to `file` (its title the plan file's name `planName`) and returns its
// summary. Throws InputError naming `file` when it cannot be written.
web::PageSummary writePlanPage(const std::string& file, const std::string& planName,
                               const world::World& world, const symbolic::KnowledgeTask& task,
                               const tamp::PlanFileContents& plan);

// {"page", "bytes", "meshes", "pieces", "actions", "branches", "duration"}.
nlohmann::json pageJson(const std::string& file, const web::PageSummary& summary);

// "page: plan.html (1.2 MB, 14 meshes, 212 convex pieces, 4 actions, 1 sensing branch, 12.3 s)".
std::string pageLine(const std::string& file, const web::PageSummary& summary);

}  // namespace kaboum::cli
