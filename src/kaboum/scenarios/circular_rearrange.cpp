#include "kaboum/scenarios/circular_rearrange.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "kaboum/core/error.hpp"

namespace kaboum::scenarios {

namespace {

// The layout, in metres: the table's top and centre, the bottles (their height, and the circle
// they stand on: at least kCircleRadius from the centre, and kLocationSpacing apart along it),
// the half-widths of a location's square (8 cm: besides a bottle, 3 cm wide, standing at its
// centre, a second one fits in a corner only) and of `any`, a strip across the middle that both
// arms reach (robot1 as far as x 0.575, robot2 from x 0.425) and no location overlaps.
constexpr double kTableTop = 0.30;
constexpr double kCentreX = 0.5;
constexpr double kBottleHeight = 0.12;
constexpr double kCircleRadius = 0.18;
constexpr double kLocationSpacing = 0.095;
constexpr double kLocationHalfWidth = 0.04;
constexpr double kAnyHalfWidthX = 0.05;
constexpr double kAnyHalfWidthY = kCircleRadius - kLocationHalfWidth - 0.02;
constexpr double kRegionTop = kTableTop + 0.2;

void checkSize(int n) {
  if (n < 2 || n > kCircularRearrangeMaxObjects) {
    throw InputError(fmt::format("circular rearrange: n must be from 2 to {}, got {}",
                                 kCircularRearrangeMaxObjects, n));
  }
}

// Where bottle i (1-based) of n stands: loc1 on robot1's side (x below the centre), the others
// following clockwise seen from above.
std::pair<double, double> locationCentre(int i, int n) {
  const double radius = std::max(kCircleRadius, n * kLocationSpacing / (2 * std::numbers::pi));
  const double angle = std::numbers::pi - 2 * std::numbers::pi * (i - 1) / n;
  return {kCentreX + radius * std::cos(angle), radius * std::sin(angle)};
}

// A region on the table: the box from the table's top to kRegionTop over a rectangle.
std::string box(double x, double y, double halfWidthX, double halfWidthY) {
  return fmt::format("{{box: {{min: [{:.3f}, {:.3f}, {:.2f}], max: [{:.3f}, {:.3f}, {:.2f}]}}}}",
                     x - halfWidthX, y - halfWidthY, kTableTop, x + halfWidthX, y + halfWidthY,
                     kRegionTop);
}

}  // namespace

std::string circularRearrangeDomain(bool handover) {
  std::string text =
      R"(; The Bimanual Circular Rearrange scenario (thesis §6.2.1, Table 6.1) with geometry: two robots
; move bottles between locations. Which robot reaches which location is not written here: the
; geometric attachments pickUp and putDown (docs/tamp.md) find grasps, placements and certified
; paths, or fail; retract takes a robot home, out of the other's way (the thesis's move samples a
; random configuration instead).)";
  if (handover) {
    text += "\n; This variant adds handover: one robot hands the bottle it holds to the other.";
  }
  text += "\n(define (domain circular-rearrange)\n";
  text +=
      R"(  (:requirements :strips :typing :negative-preconditions :numeric-fluents :semantic-attachments)
  (:types bottle robot location)
  (:predicates (isgrasped ?o - bottle) (isrobotgrasps ?r - robot ?o - bottle)
               (ishandempty ?r - robot) (isatlocation ?o - bottle ?l - location))
  (:functions (geometry))
  (:modules
    (home ?r - robot (geometry) effect moveHome :reads ((geometry)))
    (grasp ?r - robot ?o - bottle (geometry) effect pickUp :reads ((geometry)))
    (place ?r - robot ?o - bottle ?l - location (geometry) effect putDown :reads ((geometry))))";
  if (handover) {
    text +=
        "\n    (give ?r - robot ?o - bottle ?s - robot (geometry) effect handover :reads "
        "((geometry)))";
  }
  text += ")\n";
  text += R"(  (:action pickup
    :parameters (?r - robot ?o - bottle ?l - location)
    :precondition (and (ishandempty ?r) (not (isgrasped ?o)) (isatlocation ?o ?l))
    :effect (and (not (ishandempty ?r)) (isgrasped ?o) (isrobotgrasps ?r ?o)
                 (not (isatlocation ?o ?l)) [grasp ?r ?o]))
  (:action putdown
    :parameters (?r - robot ?o - bottle ?l - location)
    :precondition (and (isrobotgrasps ?r ?o) (isgrasped ?o))
    :effect (and (ishandempty ?r) (not (isgrasped ?o)) (isatlocation ?o ?l)
                 (not (isrobotgrasps ?r ?o)) [place ?r ?o ?l]))
  (:action retract
    :parameters (?r - robot)
    :effect [home ?r]))";
  if (handover) {
    text += R"(
  (:action handover
    :parameters (?r - robot ?o - bottle ?s - robot)
    :precondition (and (isrobotgrasps ?r ?o) (ishandempty ?s))
    :effect (and (not (isrobotgrasps ?r ?o)) (isrobotgrasps ?s ?o) (ishandempty ?r)
                 (not (ishandempty ?s)) [give ?r ?o ?s])))";
  }
  return text + ")\n";
}

std::string circularRearrangeProblem(int n) {
  checkSize(n);
  std::string bottles, locations, at, goal;
  for (int i = 1; i <= n; ++i) {
    bottles += fmt::format("o{} ", i);
    locations += fmt::format(" loc{}", i);
    at += fmt::format("\n         (isatlocation o{} loc{})", i, i);
    goal += fmt::format(" (isatlocation o{} loc{})", i, i % n + 1);
  }
  return fmt::format(
      R"(; Bimanual Circular Rearrange with {0} bottles (thesis Table 6.1): bottle oi stands at loci; the goal
; moves each to the next location, the last to loc1. Written by `kaboum circular-rearrange {0}`.
(define (problem circular-rearrange-{0})
  (:domain circular-rearrange)
  (:objects {1}- bottle robot1 robot2 - robot any{2} - location)
  (:init (ishandempty robot1) (ishandempty robot2){3}
         (= (geometry) 0))
  (:goal (and{4})))
)",
      n, bottles, locations, at, goal);
}

std::string circularRearrangeScene(int n) {
  checkSize(n);
  std::string text = fmt::format(
      R"(# The Bimanual Circular Rearrange scenario (thesis §6.2.1, Figure 6.3) with geometry, {0} bottles:
# two KUKA KR5 sixx R650 arms (Debian's dart-doc) with two-finger grippers face each other across a
# table as in examples/bartender; the bottles stand on a circle around the table's centre at
# loc1..loc{0}, loc1 on robot1's side. The half of the circle near robot1's base only robot1
# reaches (robot2 at most the edges of its squares), the other half only robot2; `any`, a strip
# across the middle inside the circle, both. Written by `kaboum circular-rearrange {0}`; format:
# docs/scene-format.md.
settings:
  epsilon: 0.005        # metres
  sweep_epsilon: 0.005  # metres
  seed: 1

robots:
  - name: robot1
    urdf: "/usr/share/doc/dart/data/urdf/KR5/KR5 sixx R650.urdf"
    base_pose: {{position: [0, 0, 0.5], orientation: {{rpy: [90deg, 0, 0]}}}}   # on the floor
    home: &raised {{shoulder_pitch: -45deg, elbow_pitch: -45deg, wrist_pitch: 90deg}}   # out of the middle
    tools:
      - name: gripper1
        link: palm
        tcp: {{position: [0.10, 0, 0], orientation: {{rpy: [0, 90deg, 0]}}}}
        hand: &gripper
          shapes:
            - {{box: {{size: [0.012, 0.1, 0.04]}}, pose: {{position: [0.034, 0, 0]}}}}
            - {{box: {{size: [0.08, 0.01, 0.02]}}, pose: {{position: [0.08, 0.03, 0]}}}}
            - {{box: {{size: [0.08, 0.01, 0.02]}}, pose: {{position: [0.08, -0.03, 0]}}}}

  - name: robot2
    urdf: "/usr/share/doc/dart/data/urdf/KR5/KR5 sixx R650.urdf"
    base_pose: {{position: [1.0, 0, 0.5], orientation: {{rpy: [90deg, 0, 180deg]}}}}
    home: *raised
    tools:
      - name: gripper2
        link: palm
        tcp: {{position: [0.10, 0, 0], orientation: {{rpy: [0, 90deg, 0]}}}}
        hand: *gripper

objects:
  - name: table
    geometry: {{box: {{size: [0.6, 0.8, 0.04]}}}}
    pose: {{position: [0.5, 0, 0.28]}}      # top face at z 0.30, x from 0.20 to 0.80
)",
      n);
  const double centreZ = kTableTop + kBottleHeight / 2;
  for (int i = 1; i <= n; ++i) {
    const auto [x, y] = locationCentre(i, n);
    text += fmt::format("\n  - name: o{}\n", i);
    if (i == 1) {
      text += fmt::format(R"(    geometry: &bottle {{cylinder: {{radius: 0.015, length: {:.2f}}}}}
    pose: {{position: [{:.3f}, {:.3f}, {:.2f}]}}
    movable: true
    grasps: &grasps
      - name: from-above     # the tool point 2 cm below the top, any turn about the axis
        pose: {{position: [0, 0, {:.2f}], orientation: {{rpy: [180deg, 0, 0]}}}}
        free: {{rotate_z: [-180deg, 180deg]}}
      - name: from-side      # the tool point on the axis 2 cm below the middle, the hand level,
        pose: {{position: [0, 0, -0.02], orientation: {{rpy: [0, 90deg, 0]}}}}   # from any side:
        free: {{rotate_z: [-180deg, 180deg]}}                                 # the top stays free
    resting_faces: &upright [[0, 0, -1]]
)",
                          kBottleHeight, x, y, centreZ, kBottleHeight / 2 - 0.02);
    } else {
      text += fmt::format(R"(    geometry: *bottle
    pose: {{position: [{:.3f}, {:.3f}, {:.2f}]}}
    movable: true
    grasps: *grasps
    resting_faces: *upright
)",
                          x, y, centreZ);
    }
  }
  text += fmt::format(
      "\nlocations:\n  - name: any                 # the middle, both arms reach it\n"
      "    region: {}\n",
      box(kCentreX, 0, kAnyHalfWidthX, kAnyHalfWidthY));
  for (int i = 1; i <= n; ++i) {
    const auto [x, y] = locationCentre(i, n);
    text += fmt::format("  - name: loc{}\n    region: {}\n", i,
                        box(x, y, kLocationHalfWidth, kLocationHalfWidth));
  }
  return text;
}

}  // namespace kaboum::scenarios
