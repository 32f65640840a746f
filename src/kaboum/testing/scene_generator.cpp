#include "kaboum/testing/scene_generator.hpp"

#include <cmath>
#include <memory>
#include <numbers>
#include <string>

#include "kaboum/kinematics/random_configuration.hpp"

namespace kaboum::testing {

using namespace kaboum::geometry;
using namespace kaboum::kinematics;
using namespace kaboum::collision;

Eigen::Quaterniond uniformRotation(std::mt19937_64& rng) {
  const double u1 = uniformUnit(rng), u2 = uniformUnit(rng), u3 = uniformUnit(rng);
  const double a = std::sqrt(1 - u1), b = std::sqrt(u1), tau = 2 * std::numbers::pi;
  return {b * std::cos(tau * u3), a * std::sin(tau * u2), a * std::cos(tau * u2),
          b * std::sin(tau * u3)};
}

CollisionScene randomObstacleScene(const Aabb& region, int count, int vertices, double halfSize,
                                   std::uint64_t seed, int movable) {
  std::mt19937_64 rng(seed);
  CollisionScene scene;
  for (int i = 0; i < count; ++i) {
    std::vector<std::vector<Vec3>> sets(1);
    for (int v = 0; v < vertices; ++v) {
      sets[0].emplace_back(halfSize * (2 * uniformUnit(rng) - 1),
                           halfSize * (2 * uniformUnit(rng) - 1),
                           halfSize * (2 * uniformUnit(rng) - 1));
    }
    Pose pose(uniformRotation(rng));
    const Vec3 unit(uniformUnit(rng), uniformUnit(rng), uniformUnit(rng));
    pose.translation() = region.lo + unit.cwiseProduct(region.hi - region.lo);
    const std::string name = "obstacle " + std::to_string(i);
    auto body = std::make_shared<const CollisionBody>(sets, name);
    if (i < count - movable) {
      scene.add(std::move(body), pose, name);
    } else {
      scene.addMovable(std::move(body), pose, name);
    }
  }
  return scene;
}

}  // namespace kaboum::testing
