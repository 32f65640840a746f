// Grasps for pickUp (thesis §5.2, Algorithm 3, Table 5.1; §6.1.2): robot configurations whose tool
// grasps an object at a given pose — by constraint projection of the object's grasp constraints
// (the scene file's `constraints`) over the arm's joints, or by sampling the free motions of an
// explicit grasp pose and solving IK.
#pragma once

#include <cstddef>
#include <optional>
#include <random>
#include <span>
#include <vector>

#include "kaboum/motion/tool_kinematics.hpp"

namespace kaboum::tamp {

using namespace kaboum::world;

// A grasp of an object at a pose: the robot's configuration with the tool at it, and where the
// tool centre point is in the object frame.
struct GraspCandidate {
  std::vector<double> configuration;
  Pose tcpInObject = Pose::Identity();
  std::size_t grasp = 0;  // index into the object's grasps
};

class GraspSampler {
 public:
  // Samples grasps for `tool`'s robot; both must outlive the sampler.
  GraspSampler(const World& world, motion::ToolKinematics& tool);

  // One sample: a grasp of scene object `object` at `objectPose` chosen at random among its
  // grasps, its free parameters random, and the configurations that reach it (the other joints of
  // the robot keep their values from `near`): every IK solution of an explicit grasp pose nearest
  // `near` first, or the one projection of a constrained grasp; empty when the sample has no
  // solution within the joint limits. Deterministic for the generator's state. Collisions are the
  // caller's.
  std::vector<GraspCandidate> sample(std::size_t object, const Pose& objectPose,
                                     std::span<const double> near, std::mt19937_64& rng);

 private:
  std::vector<GraspCandidate> sampleConstraints(const std::vector<GraspConstraint>& constraints,
                                                const Pose& objectPose,
                                                std::span<const double> near, std::mt19937_64& rng);
  std::vector<GraspCandidate> samplePose(const GraspPose& grasp, const Pose& objectPose,
                                         std::span<const double> near, std::mt19937_64& rng);

  const World* world_;
  motion::ToolKinematics* tool_;
};

}  // namespace kaboum::tamp
