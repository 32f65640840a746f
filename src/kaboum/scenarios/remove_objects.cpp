#include "kaboum/scenarios/remove_objects.hpp"

#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "kaboum/core/error.hpp"

namespace kaboum::scenarios {
namespace {

// The table (top face at z -0.10, x 0.25..0.65, y -0.35..0.45) in front of the arm's base; the
// bin (its floor 5 cm lower, x -0.1..0.45, y -0.65..-0.38) beside it, room for 20 objects.
constexpr double kTableTop = -0.10;
// Line layout: thin plates (8 mm along the line, 2.5 cm across, 22 cm tall) 8 mm apart along x,
// centred at x 0.47 (20 plates span the arm's reach of a level grasp 20 cm above the table), at
// y 0.15 so that the level grasp keeps the wrist bent, away from its singularity. The side grasp
// approaches along +x with the plate 1 cm in front of the palm, so the plate behind it (towards the
// base) would overlap the palm: only the nearest plate can be grasped.
constexpr double kLineCentreX = 0.47;
constexpr double kLineY = 0.15;
constexpr double kPlateHeight = 0.22;
constexpr double kBlockHeight = 0.05;
constexpr double kLinePitch = 0.016;
// Random layout: blocks (2.5 x 2.5 x 5 cm) grasped from above, on the table where the arm reaches
// down to them (0.30 to 0.50 m from its base axis), centres at least 6 cm apart.
constexpr double kRandomMinX = 0.30, kRandomMaxX = 0.50, kRandomMinY = -0.30, kRandomMaxY = 0.40;
constexpr double kRandomMinReach = 0.30, kRandomMaxReach = 0.50;
constexpr double kRandomMinDistance = 0.06;
constexpr int kPlacementAttempts = 100000;

const char* const kDomain =
    R"(; Remove n Objects (seed 003 §IV-A, Table II): pickup and putdown whose geometric effects are
; kaboum's attachments pickUp and putDown on the geometric state fluent (geometry) (docs/tamp.md);
; an action whose grasp, placement or certified path is not found is not applicable.
(define (domain remove-objects)
  (:requirements :strips :typing :negative-preconditions :numeric-fluents :semantic-attachments)
  (:types robot object location)
  (:predicates (handempty ?r - robot) (holding ?r - robot ?o - object)
               (at ?o - object ?l - location))
  (:functions (geometry))
  (:modules
    (grasp ?r - robot ?o - object (geometry) effect pickUp :reads ((geometry)))
    (place ?r - robot ?o - object ?l - location (geometry) effect putDown :reads ((geometry))))
  (:action pickup
    :parameters (?r - robot ?o - object ?l - location)
    :precondition (and (handempty ?r) (at ?o ?l))
    :effect (and (not (handempty ?r)) (holding ?r ?o) (not (at ?o ?l)) [grasp ?r ?o]))
  (:action putdown
    :parameters (?r - robot ?o - object ?l - location)
    :precondition (holding ?r ?o)
    :effect (and (handempty ?r) (not (holding ?r ?o)) (at ?o ?l) [place ?r ?o ?l])))
)";

const char* const kRobotAndTable = R"(settings:
  epsilon: 0.005        # metres
  sweep_epsilon: 0.005  # metres
  seed: 1

robots:
  - name: kr5
    urdf: "/usr/share/doc/dart/data/urdf/KR5/KR5 sixx R650.urdf"
    base_pose: {orientation: {rpy: [90deg, 0, 0]}}   # the URDF's y axis up
    home: {elbow_pitch: -30deg, wrist_pitch: 45deg}   # the hand high above the table
    tools:
      - name: gripper
        link: palm                     # x: the flange's axis
        tcp: {position: [0.10, 0, 0], orientation: {rpy: [0, 90deg, 0]}}   # z: the approach
        hand:
          shapes:
            - {box: {size: [0.012, 0.1, 0.04]}, pose: {position: [0.034, 0, 0]}}     # palm
            - {box: {size: [0.08, 0.01, 0.02]}, pose: {position: [0.08, 0.03, 0]}}    # fingers:
            - {box: {size: [0.08, 0.01, 0.02]}, pose: {position: [0.08, -0.03, 0]}}   # 5 cm apart

objects:
  - name: table
    geometry: {box: {size: [0.4, 0.8, 0.04]}}
    pose: {position: [0.45, 0.05, -0.12]}    # top face at z -0.10
)";

const char* const kLocations = R"(
locations:
  - name: table-top
    region: {box: {min: [0.25, -0.35, -0.1], max: [0.65, 0.45, 0.2]}}
  - name: bin                          # beside the table, its floor 5 cm lower
    region: {box: {min: [-0.1, -0.65, -0.15], max: [0.45, -0.38, 0.2]}}
    support_surface: true
)";

std::string number(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.4f", value);
  std::string result(text);
  while (result.back() == '0') result.pop_back();
  if (result.back() == '.') result.pop_back();
  return result == "-0" ? "0" : result;
}

std::string objectName(int i) {
  return "o" + std::to_string(i);
}

struct Position {
  double x, y;
};

// Line layout: o1 at the far end, on nearest the base, where the grasp approaches from.
std::vector<Position> linePositions(int n) {
  std::vector<Position> positions;
  for (int i = 0; i < n; ++i) {
    positions.push_back({kLineCentreX + ((n - 1) / 2.0 - i) * kLinePitch, kLineY});
  }
  return positions;
}

// Random layout: rejection sampling from a seeded generator; the uniform numbers are taken from the
// generator's bits directly, so the scene is the same on every standard library.
std::vector<Position> randomPositions(int n, std::uint64_t seed) {
  std::mt19937_64 generator(seed);
  const auto uniform = [&generator](double low, double high) {
    return low + (high - low) * static_cast<double>(generator() >> 11) * 0x1.0p-53;
  };
  std::vector<Position> positions;
  for (int attempt = 0; attempt < kPlacementAttempts && static_cast<int>(positions.size()) < n;
       ++attempt) {
    const Position candidate{uniform(kRandomMinX, kRandomMaxX), uniform(kRandomMinY, kRandomMaxY)};
    const double reach = std::hypot(candidate.x, candidate.y);
    bool apart = reach >= kRandomMinReach && reach <= kRandomMaxReach;
    for (const Position& other : positions) {
      apart =
          apart && std::hypot(candidate.x - other.x, candidate.y - other.y) >= kRandomMinDistance;
    }
    if (apart) positions.push_back(candidate);
  }
  if (static_cast<int>(positions.size()) < n) {
    throw InputError("remove objects: no room for " + std::to_string(n) + " objects with seed " +
                     std::to_string(seed));
  }
  return positions;
}

std::string objectsYaml(const std::vector<Position>& positions, RemoveObjectsLayout layout) {
  const bool line = layout == RemoveObjectsLayout::Line;
  const double height = line ? kPlateHeight : kBlockHeight;
  std::string yaml;
  for (std::size_t i = 0; i < positions.size(); ++i) {
    yaml += "\n  - name: " + objectName(static_cast<int>(i) + 1) + "\n    geometry: ";
    if (i == 0) {
      yaml += line ? "&plate {box: {size: [0.008, 0.025, 0.22]}}   # 8 mm along the line"
                   : "&block {box: {size: [0.025, 0.025, 0.05]}}";
    } else {
      yaml += line ? "*plate" : "*block";
    }
    yaml += "\n    pose: {position: [" + number(positions[i].x) + ", " + number(positions[i].y) +
            ", " + number(kTableTop + height / 2) + "]}\n    movable: true\n    grasps: ";
    if (i > 0) {
      yaml += "*grasps\n";
    } else if (line) {
      yaml += R"(&grasps
      - name: side                     # approach along +x, the plate 1 cm in front of the palm
        pose: {position: [0.046, 0, 0.09], orientation: {rpy: [0, 90deg, 0]}}
)";
    } else {
      yaml += R"(&grasps
      - name: from-above               # the tool point 1 cm above the centre, any turn about z
        pose: {position: [0, 0, 0.01], orientation: {rpy: [180deg, 0, 0]}}
        free: {rotate_z: [-180deg, 180deg]}
)";
    }
  }
  return yaml;
}

std::string sceneYaml(int n, RemoveObjectsLayout layout, std::uint64_t seed) {
  const bool line = layout == RemoveObjectsLayout::Line;
  std::string header = "# Remove " + std::to_string(n) +
                       " Objects (seed 003 §IV-A, Table II): a KUKA KR5 " +
                       "sixx R650 (Debian's dart-doc)\n";
  header += line ? "# removes plates standing in a line into the bin; the side grasp approaches "
                   "along the line,\n# so only the nearest plate can be grasped.\n"
                 : "# removes blocks at random places on the table (seed " + std::to_string(seed) +
                       ") into the bin.\n";
  header += "# Written by `kaboum remove-objects`; format: docs/scene-format.md.\n";
  const std::vector<Position> positions = line ? linePositions(n) : randomPositions(n, seed);
  return header + kRobotAndTable + objectsYaml(positions, layout) + kLocations;
}

std::string problemPddl(int n, RemoveObjectsLayout layout) {
  std::string objects, init, goal;
  for (int i = 1; i <= n; ++i) {
    objects += objectName(i) + " ";
    init += " (at " + objectName(i) + " table-top)";
    goal += " (at " + objectName(i) + " bin)";
  }
  const std::string name = "remove-" + layoutName(layout) + "-" + std::to_string(n);
  return "; Remove " + std::to_string(n) + " objects from the table into the bin, the hand empty " +
         "at the end.\n(define (problem " + name + ")\n  (:domain remove-objects)\n" +
         "  (:objects kr5 - robot " + objects + "- object table-top bin - location)\n" +
         "  (:init (handempty kr5)" + init + " (= (geometry) 0))\n" + "  (:goal (and" + goal +
         " (handempty kr5))))\n";
}

}  // namespace

RemoveObjectsLayout parseRemoveObjectsLayout(const std::string& word) {
  if (word == "random") return RemoveObjectsLayout::Random;
  if (word == "line") return RemoveObjectsLayout::Line;
  throw InputError("remove objects: --layout must be random or line, got '" + word + "'");
}

std::string layoutName(RemoveObjectsLayout layout) {
  return layout == RemoveObjectsLayout::Line ? "line" : "random";
}

RemoveObjectsScenario removeObjects(int n, RemoveObjectsLayout layout, std::uint64_t seed) {
  if (n < 1 || n > kMaxRemovedObjects) {
    throw InputError("remove objects: n must be between 1 and " +
                     std::to_string(kMaxRemovedObjects) + ", got " + std::to_string(n));
  }
  return {kDomain, problemPddl(n, layout), sceneYaml(n, layout, seed)};
}

}  // namespace kaboum::scenarios
