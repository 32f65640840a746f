// Seeded, platform-independent uniform sampling of joint configurations (the standard library's
// distributions differ between implementations; the engine's output does not).
#pragma once

#include <cstdint>
#include <random>
#include <span>
#include <vector>

#include "kaboum/kinematics/kinematic_chain.hpp"
#include "kaboum/kinematics/robot_model.hpp"

namespace kaboum::kinematics {

// Uniform double in [0, 1) from the top 53 bits of one engine output.
inline double uniformUnit(std::mt19937_64& rng) {
  return static_cast<double>(rng() >> 11) * 0x1.0p-53;
}

// Fills q[offset, offset + chain.dof()) uniformly within the chain's joint limits.
inline void randomConfiguration(const KinematicChain& chain, std::mt19937_64& rng,
                                std::span<double> q) {
  for (int i = 0; i < chain.dof(); ++i) {
    q[static_cast<std::size_t>(i)] =
        chain.lower(i) + uniformUnit(rng) * (chain.upper(i) - chain.lower(i));
  }
}

// A configuration of every variable joint of `model`, uniform within the joint limits.
inline std::vector<double> randomConfiguration(const RobotModel& model, std::mt19937_64& rng) {
  std::vector<double> q(static_cast<std::size_t>(model.dof()));
  for (int v = 0; v < model.dof(); ++v) {
    const Joint& joint = model.variableJoint(v);
    q[static_cast<std::size_t>(v)] = joint.lower + uniformUnit(rng) * (joint.upper - joint.lower);
  }
  return q;
}

}  // namespace kaboum::kinematics
