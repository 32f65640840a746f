// kaboum's state validity checker and motion validator for a motion group in a World (thesis
// §6.1.2): configurations checked by the bounded predicates, straight motions certified by the
// robots' bounding swept volumes (§4.5, Definition 1), so that a certified motion cannot pass
// through a collision between its ends. Both allocate nothing per call once built.
#pragma once

#include <array>
#include <memory>
#include <optional>
#include <vector>

#include "kaboum/collision/swept.hpp"
#include "kaboum/motion/motion_group.hpp"
#include "kaboum/motion/validity.hpp"

namespace kaboum::motion {

// Checks only what the moving robots change: each moving robot (with what it holds) against
// itself, the scene's objects and every other robot. The fixed parts of the context (other robots
// against objects, objects against each other) are the caller's to check once (World::
// firstCollision on the start state).
class WorldStateChecker final : public StateValidityChecker {
 public:
  // Holds a reference: `group` must outlive the checker. A configuration is valid when the moving
  // robots keep `clearance` from the scene's objects and 2 × `clearance` from robots (themselves
  // included): the margins at which the swept volumes of motions bounded within `clearance` are
  // checked, so that every valid configuration can start a certified motion. Counts into
  // `statistics` when given.
  WorldStateChecker(const MotionGroup& group, double clearance,
                    CheckStatistics* statistics = nullptr);

  [[nodiscard]] bool isValid(std::span<const double> q) override;
  // The first collision at q, naming both parties.
  [[nodiscard]] std::optional<Collision> firstCollision(std::span<const double> q);

 private:
  const MotionGroup& group_;
  double clearance_;
  CheckStatistics* statistics_;
  GeometricState state_;
  QueryScratch scratch_;
  std::vector<std::vector<std::uint8_t>>
      against_;  // per moving robot: the robots it is checked against
};

// Certifies the straight motion of every moving robot at once: each robot's swept volume against
// itself (swept self-collision), the scene's objects, and the other robots' swept volumes over the
// same interval (a fixed robot's is its pose). Swept volumes are bounded within `sweepEpsilon`
// metres, so a motion is rejected only when it comes within that of a collision. The verdict does
// not depend on the direction of the motion.
class SweptMotionValidator final : public MotionValidator {
 public:
  // Holds a reference: `group` must outlive the validator. Counts into `statistics` when given.
  SweptMotionValidator(const MotionGroup& group, double sweepEpsilon,
                       CheckStatistics* statistics = nullptr);

  [[nodiscard]] bool isValid(std::span<const double> from, std::span<const double> to) override;
  [[nodiscard]] double sweepEpsilon() const { return epsilon_; }

 private:
  [[nodiscard]] bool certify(std::span<const double> from, std::span<const double> to);

  // Configurations checked for a plain collision before the sweep (fractions of the motion).
  static constexpr std::array<double, 4> kPrefilterSamples{1.0, 0.5, 0.25, 0.75};

  const MotionGroup& group_;
  double epsilon_;
  CheckStatistics* statistics_;
  WorldStateChecker samples_;  // at clearance 0
  std::vector<double> sample_;
  // One sweep per robot of the world (fixed robots sweep their constant configuration).
  std::vector<std::unique_ptr<RobotSweep>> sweeps_;
  std::vector<int> movingIndex_;  // per world robot: its index among the moving robots, or -1
};

// Checks the straight motion of every moving robot at discrete samples, for a World whose state
// queries use exact predicates (World::usePredicates; thesis §6.2.3, Proposition 4): swept volumes
// exist only for convex pieces. Between consecutive samples no revolute or continuous coordinate
// moves more than `jointStep` radians and no prismatic one more than `prismaticStep` metres; a
// motion is valid when every sample between its ends is collision-free — what happens between
// samples is not checked. The verdict does not depend on the direction of the motion.
class DiscreteMotionValidator final : public MotionValidator {
 public:
  // Holds a reference: `group` must outlive the validator. Counts into `statistics` when given.
  // Throws std::invalid_argument for a step that is not positive.
  DiscreteMotionValidator(const MotionGroup& group, double jointStep, double prismaticStep,
                          CheckStatistics* statistics = nullptr);

  [[nodiscard]] bool isValid(std::span<const double> from, std::span<const double> to) override;

 private:
  CheckStatistics* statistics_;
  WorldStateChecker samples_;  // at clearance 0
  std::vector<double> sample_;
  std::vector<double> steps_;  // per coordinate: the largest motion between samples
};

}  // namespace kaboum::motion
