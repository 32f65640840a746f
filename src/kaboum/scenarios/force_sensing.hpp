// Generator of the Force Sensing scenario (thesis §3.3.3, Table 3.1, Figure 3.2): transfer n
// containers; a container must be carried upright unless weighing shows it is empty.
#pragma once

#include <string>

namespace kaboum::scenarios {

// Contingent PDDL domain of Table 3.1 in the PKS syntax (independent of n).
std::string forceSensingDomain();
// Problem for n >= 1 containers o1..on: I = K(emptyGripper) ∧ K(¬isRemoved(oi)), isSpillable(oi)
// unknown; G = K(emptyGripper) ∧ K(isRemoved(oi)).
std::string forceSensingProblem(int n);

}  // namespace kaboum::scenarios
