// Toy geometric preconditions for the symbolic parts of the Bartender (thesis Table 6.1) and
// Bimanual Assembly (Tables 6.5/6.6) scenarios, standing in for the geometric predicates of
// Chapter 4 so the scenarios plan without a robot model (data/pddl/contingent/scenarios).
#pragma once

#include "kaboum/symbolic/attachments.hpp"

namespace kaboum::scenarios {

using namespace kaboum::symbolic;

// Registers the condition checker `reaches(robot, place)`: robot1's workspace excludes `right`
// and `dishwasher`, robot2's excludes `left` and the pipe `o3`; everything else is reachable.
ProcedureRegistry toyGeometryProcedures();

}  // namespace kaboum::scenarios
