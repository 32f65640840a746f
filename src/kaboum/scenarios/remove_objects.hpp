// Generator of the Remove n Objects scenario (seed 003 §IV-A, Table II; Fig. 6): a KUKA KR5 arm
// removes n objects from a table into a bin beside it, with pickUp/putDown attachments
// (docs/tamp.md). Two layouts: objects at seeded random places, or in a line where only the
// nearest object can be picked up, because the side grasp approaches along the line.
#pragma once

#include <cstdint>
#include <string>

namespace kaboum::scenarios {

enum class RemoveObjectsLayout { Random, Line };

// "random" or "line"; throws InputError naming the word otherwise.
RemoveObjectsLayout parseRemoveObjectsLayout(const std::string& word);
std::string layoutName(RemoveObjectsLayout layout);

// The largest n: the line of n objects fits the table in the arm's reach up to it.
inline constexpr int kMaxRemovedObjects = 20;

struct RemoveObjectsScenario {
  std::string domain;   // PDDL domain (independent of n and the layout)
  std::string problem;  // PDDL problem: every object from the table into the bin, the hand empty
  std::string scene;    // scene file (docs/scene-format.md)
};

// The scenario for 1 <= n <= kMaxRemovedObjects objects (else InputError). In the line layout the
// objects are o1..on with o1 at the far end, so the only feasible order is on, ..., o1; in the
// random layout `seed` places them (the same seed gives the same scene).
RemoveObjectsScenario removeObjects(int n, RemoveObjectsLayout layout, std::uint64_t seed = 1);

}  // namespace kaboum::scenarios
