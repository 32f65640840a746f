// Generator of the Bimanual Circular Rearrange scenario (thesis §6.2.1, Table 6.1, Figure 6.3):
// n bottles stand on a circle of locations loc1..locn on a table between two arms, and each must
// move to the next location (o1 to loc2, …, on to loc1), so every goal location is blocked by
// another bottle at first. Reference: examples/circular-rearrange/README.md.
#pragma once

#include <string>

namespace kaboum::scenarios {

// The most bottles whose circle of locations fits the table.
inline constexpr int kCircularRearrangeMaxObjects = 16;

// PDDL domain of Table 6.1 (pickup, putdown) with the geometric attachments pickUp, putDown and
// moveHome on the fluent (geometry) (docs/tamp.md), plus `retract` (moveHome) in place of the
// thesis's random `move`; with `handover`, also the action handover(robot, bottle, robot') bound to
// the handover attachment. Independent of n.
std::string circularRearrangeDomain(bool handover = false);
// Problem for 2 <= n <= kCircularRearrangeMaxObjects bottles: oi at loci, both hands empty; goal
// o1 at loc2, o2 at loc3, …, on at loc1. Throws InputError for another n.
std::string circularRearrangeProblem(int n);
// Scene file (docs/scene-format.md) for n bottles: two KUKA KR5 sixx R650 arms (Debian's
// dart-doc) 1 m apart facing each other across the table, as in examples/bartender; the bottles
// on a circle around the table's centre, loc1 on robot1's side, so that the bottles on either
// half of the circle are reached by one arm only; `any`, a strip across the middle inside the
// circle, by both. Throws InputError for an n the problem rejects.
std::string circularRearrangeScene(int n);

}  // namespace kaboum::scenarios
