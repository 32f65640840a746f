// Paths of the robots the kinematics tests run on, and a seeded configuration sampler.
#pragma once

#include <random>
#include <string>
#include <vector>

#include "kaboum/kinematics/kinematic_chain.hpp"

namespace kaboum::test {

inline const std::string kKr5 = "/usr/share/doc/dart/data/urdf/KR5/KR5 sixx R650.urdf";
inline const std::string kWam = "/usr/share/doc/dart/data/urdf/wam/wam.urdf";
inline const std::string kComauLeft = std::string(KABOUM_DATA_DIR) + "/robots/comau-left.urdf";
inline const std::string kComauRight = std::string(KABOUM_DATA_DIR) + "/robots/comau-right.urdf";

// Uniform configuration within the chain's limits, shrunk by `margin` on each side.
inline std::vector<double> randomConfiguration(const KinematicChain& chain, std::mt19937_64& rng,
                                               double margin = 0.0) {
  std::vector<double> q(static_cast<std::size_t>(chain.dof()));
  for (int i = 0; i < chain.dof(); ++i) {
    std::uniform_real_distribution<double> uniform(chain.lower(i) + margin,
                                                   chain.upper(i) - margin);
    q[static_cast<std::size_t>(i)] = uniform(rng);
  }
  return q;
}

}  // namespace kaboum::test
