// Generator of the Stacked n Objects scenario (thesis §6.2.2, Table 6.3): move a new block o1
// under a stack o2..on using three stack locations; getOneBelow is an object fluent.
#pragma once

#include <string>

namespace kaboum::scenarios {

// PDDL domain text of Table 6.3 (independent of n).
std::string stackedObjectsDomain();
// PDDL problem text for n >= 2 objects: o2..on stacked on stack1, o1 on stack2, stack3 free; goal
// o1 on stack1 with o2..on on top of it in order.
std::string stackedObjectsProblem(int n);

}  // namespace kaboum::scenarios
