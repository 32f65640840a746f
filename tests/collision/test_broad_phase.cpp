// The AABB tree reports exactly the overlapping boxes; the collision filter keeps its pairs.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <stdexcept>

#include "kaboum/collision/broad_phase.hpp"
#include "kaboum/collision/collision_filter.hpp"
#include "kaboum/kinematics/random_configuration.hpp"

namespace kaboum::collision {

using namespace kaboum::kinematics;

namespace {

Aabb randomBox(std::mt19937_64& rng, double size) {
  const Vec3 lo(uniformUnit(rng), uniformUnit(rng), uniformUnit(rng));
  const Vec3 extent(uniformUnit(rng), uniformUnit(rng), uniformUnit(rng));
  return {lo, lo + size * extent};
}

TEST(AabbTree, FindsExactlyTheOverlappingBoxes) {
  std::mt19937_64 rng(7);
  for (std::size_t count : {0U, 1U, 2U, 3U, 17U, 300U}) {
    std::vector<Aabb> boxes;
    for (std::size_t i = 0; i < count; ++i) boxes.push_back(randomBox(rng, 0.1));
    AabbTree tree;
    tree.build(boxes);
    EXPECT_EQ(tree.empty(), count == 0);
    for (int q = 0; q < 200; ++q) {
      const Aabb query = randomBox(rng, 0.2);
      std::vector<std::uint32_t> found, expected;
      EXPECT_TRUE(tree.forEachOverlapping(query, [&](std::uint32_t id) {
        found.push_back(id);
        return true;
      }));
      for (std::uint32_t i = 0; i < count; ++i) {
        if (boxes[i].overlaps(query)) expected.push_back(i);
      }
      std::sort(found.begin(), found.end());
      EXPECT_EQ(found, expected);
      EXPECT_EQ(tree.anyOverlapping(query), !expected.empty());
    }
  }
}

TEST(AabbTree, StopsWhenTheVisitorSaysSo) {
  std::vector<Aabb> boxes(10, Aabb{Vec3::Zero(), Vec3::Ones()});
  AabbTree tree;
  tree.build(boxes);
  int visits = 0;
  EXPECT_FALSE(tree.forEachOverlapping(boxes[0], [&](std::uint32_t) { return ++visits < 3; }));
  EXPECT_EQ(visits, 3);
}

TEST(AabbTree, TransformedBoxContainsTheRotatedCorners) {
  std::mt19937_64 rng(3);
  const Aabb local{Vec3(-1, -2, 0.5), Vec3(2, 1, 3)};
  for (int i = 0; i < 100; ++i) {
    Eigen::Quaterniond rotation(uniformUnit(rng) - 0.5, uniformUnit(rng) - 0.5,
                                uniformUnit(rng) - 0.5, uniformUnit(rng) - 0.5);
    Eigen::Isometry3d pose(rotation.normalized());
    pose.translation() = Vec3(uniformUnit(rng), uniformUnit(rng), uniformUnit(rng));
    const Aabb box = transformedAabb(local, pose);
    Vec3 lo = Vec3::Constant(1e9), hi = Vec3::Constant(-1e9);
    for (int c = 0; c < 8; ++c) {
      const Vec3 corner((c & 1) ? local.hi.x() : local.lo.x(),
                        (c & 2) ? local.hi.y() : local.lo.y(),
                        (c & 4) ? local.hi.z() : local.lo.z());
      lo = lo.cwiseMin(pose * corner);
      hi = hi.cwiseMax(pose * corner);
    }
    EXPECT_LT((box.lo - lo).norm(), 1e-12);  // tight: exactly the corners' box
    EXPECT_LT((box.hi - hi).norm(), 1e-12);
  }
}

TEST(CollisionFilter, AllowsSymmetricPairs) {
  CollisionFilter filter(5);
  EXPECT_TRUE(filter.allowed(1, 1));
  EXPECT_FALSE(filter.allowed(0, 2));
  filter.allow(2, 0);
  EXPECT_TRUE(filter.allowed(0, 2));
  EXPECT_FALSE(filter.allowed(4, 2));
  filter.allow(0, 2, false);
  EXPECT_FALSE(filter.allowed(2, 0));
  EXPECT_THROW(filter.allow(0, 5), std::out_of_range);
}

}  // namespace
}  // namespace kaboum::collision
