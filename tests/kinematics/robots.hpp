// Paths of the robots the kinematics tests run on, and random configurations for them.
#pragma once

#include <random>
#include <string>
#include <vector>

#include "kaboum/kinematics/kinematic_chain.hpp"
#include "kaboum/kinematics/random_configuration.hpp"

namespace kaboum::test {

inline const std::string kKr5 = "/usr/share/doc/dart/data/urdf/KR5/KR5 sixx R650.urdf";
inline const std::string kWam = "/usr/share/doc/dart/data/urdf/wam/wam.urdf";
inline const std::string kComauLeft = std::string(KABOUM_DATA_DIR) + "/robots/comau-left.urdf";
inline const std::string kComauRight = std::string(KABOUM_DATA_DIR) + "/robots/comau-right.urdf";

// Uniform configuration within the chain's limits (the library's seeded sampler).
inline std::vector<double> randomConfiguration(const KinematicChain& chain, std::mt19937_64& rng) {
  std::vector<double> q(static_cast<std::size_t>(chain.dof()));
  kaboum::randomConfiguration(chain, rng, q);
  return q;
}

}  // namespace kaboum::test
