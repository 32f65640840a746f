// Generator of the Stacked n Objects scenario (thesis §6.2.2, Table 6.3, Figures 6.4 and 6.5): move
// a new block o1 under a stack o2..on using three stack locations; getOneBelow is an object fluent.
// Symbolic (Table 6.3), and with geometry: a mobile manipulator at three stands, a domain whose
// pickup and putdown are the geometric attachments pickUp and putDown (docs/tamp.md).
#pragma once

#include <string>

namespace kaboum::scenarios {

// PDDL domain text of Table 6.3 (independent of n).
std::string stackedObjectsDomain();
// PDDL problem text for n >= 2 objects: o2..on stacked on stack1, o1 on stack2, stack3 free; goal
// o1 on stack1 with o2..on on top of it in order.
std::string stackedObjectsProblem(int n);

// The largest n the geometric scenario's arm reaches (the final stack on a side stand).
inline constexpr int kStackedGeometryMaxObjects = 20;

// The domain with geometry (independent of n): Table 6.3's move split into pickup (pickUp) and
// putdown (putDown into the stack location of the object or stack put on), on the fluent
// (geometry); instack records which stack each object is in.
std::string stackedObjectsGeometryDomain();
// Its problem for 2 <= n <= kStackedGeometryMaxObjects: Table 6.3's initial state and goal, the
// robot `mobile` with an empty hand (also at the goal), (geometry) at the scene's initial state.
std::string stackedObjectsGeometryProblem(int n);
// The scene for n objects: the mobile manipulator of examples/robots/mobile-5axis.urdf (named by
// `urdf`, relative to the scene file's folder or absolute) at its home, three stands around the
// arm's base (stack1 on its left, stack2 in front, stack3 on its right), the locations stack1..3
// above them as high as n blocks, blocks 4 × 4 × 1.2 cm (o1 on stack2, o2..on on stack1), each
// with one grasp from above.
std::string stackedObjectsScene(int n, const std::string& urdf);

}  // namespace kaboum::scenarios
