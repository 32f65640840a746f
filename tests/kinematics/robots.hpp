// Paths of the robots the kinematics tests run on, and random configurations for them.
#pragma once

#include <random>
#include <string>
#include <vector>

#include "kaboum/kinematics/kinematic_chain.hpp"
#include "kaboum/kinematics/random_configuration.hpp"
#include "kaboum/testing/data_paths.hpp"

namespace kaboum::test {

using namespace kaboum::kinematics;
using namespace kaboum::testing;

inline const std::string kKr5 = kaboum::testing::kr5Urdf();
inline const std::string kWam = kaboum::testing::wamUrdf();
inline const std::string kComauLeft = kaboum::testing::dataFile("robots/comau-left.urdf");
inline const std::string kComauRight = kaboum::testing::dataFile("robots/comau-right.urdf");

// Uniform configuration within the chain's limits (the library's seeded sampler).
inline std::vector<double> randomConfiguration(const KinematicChain& chain, std::mt19937_64& rng) {
  std::vector<double> q(static_cast<std::size_t>(chain.dof()));
  kaboum::kinematics::randomConfiguration(chain, rng, q);
  return q;
}

}  // namespace kaboum::test
