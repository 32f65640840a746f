#include "kaboum/scenarios/stacked_objects.hpp"

#include <fmt/format.h>

#include <array>
#include <limits>

#include "kaboum/core/error.hpp"

namespace kaboum::scenarios {

namespace {

std::string object(int i) {
  return "o" + std::to_string(i);
}

// Table 6.3's objects, initial knowledge and goal for n objects (n >= 2).
struct StackedFacts {
  std::string objects;  // "o1 o2 … on "
  std::string init;     // one fact or fluent per line, indented
  std::string goal;     // the getOneBelow chain
};

// Throws InputError for fewer than 2 objects, or more than `most` (with geometry: the arm reaches
// no higher stack).
void requireObjects(int n, int most = std::numeric_limits<int>::max()) {
  if (n < 2) throw InputError("stacked objects: n must be at least 2, got " + std::to_string(n));
  if (n > most) {
    throw InputError(fmt::format(
        "stacked objects with geometry: n must be at most {} (the arm reaches no higher stack), "
        "got {}",
        most, n));
  }
}

StackedFacts stackedFacts(int n) {
  requireObjects(n);
  StackedFacts facts;
  for (int i = 1; i <= n; ++i) facts.objects += object(i) + " ";
  facts.init = "    (isastack stack1) (isastack stack2) (isastack stack3)\n";
  facts.init += "    (ishighest " + object(n) + ") (ishighest o1) (ishighest stack3)\n";
  facts.init += "    (= (getonebelow o2) stack1) (= (getonebelow o1) stack2)\n";
  for (int i = 3; i <= n; ++i) {
    facts.init += "    (= (getonebelow " + object(i) + ") " + object(i - 1) + ")\n";
  }
  facts.goal = "(= (getonebelow o1) stack1)";
  for (int i = 2; i <= n; ++i) {
    facts.goal += " (= (getonebelow " + object(i) + ") " + object(i - 1) + ")";
  }
  return facts;
}

// The geometric scene's dimensions (metres). The arm's base axis stands at x 0.1 on the robot's
// base (radius 0.23); the stands are outside it, within the arm's reach of a block from above.
constexpr double kStandTop = 0.10;
constexpr double kStandSize = 0.06;
constexpr double kBlockSize = 0.04;
constexpr double kBlockHeight = 0.012;
// Per block of a location's height: the block and the resting gaps the World leaves under it.
constexpr double kLevelHeight = 0.014;
struct Stand {
  const char* location;
  double x, y;
};
constexpr std::array<Stand, 3> kStands{
    {{"stack1", 0.22, 0.25}, {"stack2", 0.30, 0.0}, {"stack3", 0.22, -0.25}}};

}  // namespace

std::string stackedObjectsDomain() {
  // Table 6.3, with one addition: moving an object onto the object it already stands on is
  // excluded (the thesis's effects would otherwise mark that object as highest).
  return R"((define (domain stacked-objects)
  (:requirements :typing :negative-preconditions :equality :conditional-effects
                 :universal-preconditions :object-fluents)
  (:types object)
  (:predicates (isastack ?o - object) (ishighest ?o - object))
  (:functions (getonebelow ?o - object) - object)
  (:action move
    :parameters (?this - object ?other - object)
    :precondition (and (ishighest ?this) (ishighest ?other) (not (isastack ?this))
                       (not (= ?this ?other)) (not (= (getonebelow ?this) ?other)))
    :effect (and (not (ishighest ?other))
                 (forall (?o - object) (when (= (getonebelow ?this) ?o) (ishighest ?o)))
                 (assign (getonebelow ?this) ?other))))
)";
}

std::string stackedObjectsProblem(int n) {
  const StackedFacts facts = stackedFacts(n);
  return "(define (problem stacked-" + std::to_string(n) + ")\n  (:domain stacked-objects)\n" +
         "  (:objects " + facts.objects + "stack1 stack2 stack3 - object)\n  (:init\n" +
         facts.init + "  )\n  (:goal (and " + facts.goal + ")))\n";
}

std::string stackedObjectsGeometryDomain() {
  // Table 6.3's move(this, other) is a pick and a place: pickup makes the object below the highest
  // (the forall of Table 6.3) and putdown puts the object on `other`, geometrically into the stack
  // location `other` is in. No symbolic fact says where a block lies: putDown finds the top of
  // the stack in the location (docs/placement.md).
  return R"((define (domain stacked-objects-geometry)
  (:requirements :typing :negative-preconditions :equality :conditional-effects
                 :object-fluents :numeric-fluents :semantic-attachments)
  (:types object robot)
  (:predicates (isastack ?o - object) (ishighest ?o - object) (instack ?o - object ?s - object)
               (handempty ?r - robot) (holding ?r - robot ?o - object))
  (:functions (getonebelow ?o - object) - object (geometry))
  (:modules
    (grasp ?r - robot ?o - object (geometry) effect pickUp :reads ((geometry)))
    (place ?r - robot ?o - object ?s - object (geometry) effect putDown :reads ((geometry))))
  (:action pickup
    :parameters (?r - robot ?this - object ?s - object)
    :precondition (and (handempty ?r) (ishighest ?this) (not (isastack ?this)) (instack ?this ?s))
    :effect (and (not (handempty ?r)) (holding ?r ?this) (not (ishighest ?this))
                 (not (instack ?this ?s))
                 (forall (?o - object) (when (= (getonebelow ?this) ?o) (ishighest ?o)))
                 [grasp ?r ?this]))
  (:action putdown
    :parameters (?r - robot ?this - object ?other - object ?s - object)
    :precondition (and (holding ?r ?this) (ishighest ?other) (instack ?other ?s) (isastack ?s))
    :effect (and (handempty ?r) (not (holding ?r ?this)) (ishighest ?this)
                 (not (ishighest ?other)) (assign (getonebelow ?this) ?other) (instack ?this ?s)
                 [place ?r ?this ?s])))
)";
}

std::string stackedObjectsGeometryProblem(int n) {
  requireObjects(n, kStackedGeometryMaxObjects);
  const StackedFacts facts = stackedFacts(n);
  std::string init = facts.init;
  init += "    (instack stack1 stack1) (instack stack2 stack2) (instack stack3 stack3)\n";
  init += "    (instack o1 stack2)";
  for (int i = 2; i <= n; ++i) init += " (instack " + object(i) + " stack1)";
  init += "\n    (handempty mobile) (= (geometry) 0)\n";
  return "(define (problem stacked-geometry-" + std::to_string(n) + ")\n" +
         "  (:domain stacked-objects-geometry)\n" + "  (:objects " + facts.objects +
         "stack1 stack2 stack3 - object mobile - robot)\n  (:init\n" + init +
         "  )\n  (:goal (and " + facts.goal + " (handempty mobile))))\n";
}

std::string stackedObjectsScene(int n, const std::string& urdf) {
  requireObjects(n, kStackedGeometryMaxObjects);
  std::string text = fmt::format(
      R"(# The Stacked n Objects scenario (thesis §6.2.2, Figure 6.4) for n = {n}, written by
# `kaboum stacked {n} --scene`: a five-axis arm on an omnidirectional base (Katana-like on a
# Robotino-like base) at three stands; o2..o{n} stacked on stack1, o1 on stack2, stack3 free.
# Format: docs/scene-format.md.
settings:
  epsilon: 0.002        # metres
  sweep_epsilon: 0.005  # metres
  seed: 1

robots:
  - name: mobile
    urdf: "{urdf}"
    home: {{shoulder: 0.3, elbow: 1.2, wrist_pitch: 1.0}}
    tools:
      - name: gripper
        link: gripper
        base_link: arm_base               # the five-axis arm: closed-form IK
        tcp: {{position: [0, 0, 0.1]}}     # between the fingertips

objects:
)",
      fmt::arg("n", n), fmt::arg("urdf", urdf));
  for (const Stand& stand : kStands) {
    text += fmt::format(
        "  - {{name: {}-stand, geometry: {{box: {{size: [{}, {}, {}]}}}}, "
        "pose: {{position: [{}, {}, {}]}}}}\n",
        stand.location, kStandSize, kStandSize, kStandTop, stand.x, stand.y, kStandTop / 2);
  }
  const auto block = [&](int i, const Stand& stand, int level) {
    text += fmt::format(
        "  - name: {}\n"
        "    geometry: {{box: {{size: [{}, {}, {}]}}}}\n"
        "    pose: {{position: [{}, {}, {:.4f}]}}\n"
        "    movable: true\n"
        "    grasps:\n"
        "      - {{name: from-above, pose: {{position: [0, 0, {}], "
        "orientation: {{rpy: [180deg, 0, 90deg]}}}}}}\n",
        object(i), kBlockSize, kBlockSize, kBlockHeight, stand.x, stand.y,
        kStandTop + kBlockHeight * (level + 0.5), kBlockHeight / 2);
  };
  block(1, kStands[1], 0);
  for (int i = 2; i <= n; ++i) block(i, kStands[0], i - 2);
  text += "\nlocations:                # above the stands, as high as n blocks\n";
  for (const Stand& stand : kStands) {
    text += fmt::format(
        "  - {{name: {}, region: {{box: {{min: [{:.3f}, {:.3f}, {:.3f}], "
        "max: [{:.3f}, {:.3f}, {:.3f}]}}}}}}\n",
        stand.location, stand.x - kStandSize / 2, stand.y - kStandSize / 2, kStandTop,
        stand.x + kStandSize / 2, stand.y + kStandSize / 2,
        kStandTop + kLevelHeight * (n + 1) + 0.01);
  }
  return text;
}

}  // namespace kaboum::scenarios
