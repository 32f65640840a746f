#include "page_cli.hpp"

#include <fmt/format.h>

#include <filesystem>
#include <fstream>

#include "kaboum/core/error.hpp"

namespace kaboum::cli {

web::PageSummary writePlanPage(const std::string& file, const std::string& planName,
                               const world::World& world, const symbolic::KnowledgeTask& task,
                               const tamp::PlanFileContents& plan) {
  web::PageOptions options;
  options.title = std::filesystem::path(planName).filename().string();
  const web::PlanPage page = web::planPage(world, task, plan, options);
  std::ofstream out(file, std::ios::binary);
  if (!out || !(out << page.html)) throw InputError(file + ": cannot write the page");
  return page.summary;
}

nlohmann::json pageJson(const std::string& file, const web::PageSummary& summary) {
  return {{"page", file},
          {"bytes", summary.bytes},
          {"meshes", summary.meshes},
          {"pieces", summary.pieces},
          {"actions", summary.actions},
          {"branches", summary.branches},
          {"duration", summary.duration}};
}

std::string pageLine(const std::string& file, const web::PageSummary& summary) {
  return fmt::format(
      "page: {} ({:.2f} MB, {} meshes, {} convex pieces, {} actions, {} sensing branch{}, {:.2f} "
      "s)",
      file, static_cast<double>(summary.bytes) / 1e6, summary.meshes, summary.pieces,
      summary.actions, summary.branches, summary.branches == 1 ? "" : "es", summary.duration);
}

}  // namespace kaboum::cli
