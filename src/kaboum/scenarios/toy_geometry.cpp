#include "kaboum/scenarios/toy_geometry.hpp"

#include <array>
#include <string_view>
#include <utility>

namespace kaboum::scenarios {

using namespace kaboum::symbolic;

ProcedureRegistry toyGeometryProcedures() {
  ProcedureRegistry registry;
  registry.addChecker("reaches", [](const AttachmentArgs& args) {
    static constexpr std::array<std::pair<std::string_view, std::string_view>, 4> kOutOfReach = {
        {{"robot1", "right"}, {"robot1", "dishwasher"}, {"robot2", "left"}, {"robot2", "o3"}}};
    for (const auto& [robot, place] : kOutOfReach) {
      if (args.name(0) == robot && args.name(1) == place) return false;
    }
    return true;
  });
  return registry;
}

}  // namespace kaboum::scenarios
