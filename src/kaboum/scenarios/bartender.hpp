// Generator of the Bartender scenario's symbolic part (thesis §6.2.1, Table 6.1, Figure 6.2) for n
// bottles, the scaling instance of docs/benchmarks.md ("Knowledge representations"): two robots
// move bottles of unknown emptiness; only empty bottles go to the dishwasher. Geometry is the toy
// attachment `reaches` (toy_geometry.hpp), as in data/pddl/contingent/scenarios.
#pragma once

#include <string>

namespace kaboum::scenarios {

// Contingent PDDL domain (independent of n; the text of
// data/pddl/contingent/scenarios/bartender-domain.pddl).
std::string bartenderDomain();
// Problem for n >= 1 bottles o1..on: odd bottles stand at `left` (only robot1 reaches it), even
// ones at `right` (only robot2); whether each is empty is unknown. G = Table 6.1's ⊕ per bottle.
std::string bartenderProblem(int n);

}  // namespace kaboum::scenarios
