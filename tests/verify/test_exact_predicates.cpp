// The exact predicates (verify::ExactPredicates; thesis §6.2.3, Proposition 4) against the bounded
// ones on a real robot scene (examples/pick-and-place: the KR5's original link meshes, decomposed
// at the scene's ε = 5 mm): on random configurations the bounded predicates never call free a
// state the exact ones call colliding (the bounding pieces contain the meshes), and just outside
// the exact contact the bounded ones still reject states the exact ones call free — within ε of
// a collision. With exact predicates installed, motions are checked at samples 1° apart.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <memory>
#include <random>

#include "../support/test_support.hpp"
#include "kaboum/io/scene_file.hpp"
#include "kaboum/kinematics/random_configuration.hpp"
#include "kaboum/motion/motion_planner.hpp"
#include "kaboum/motion/world_checkers.hpp"
#include "kaboum/testing/data_paths.hpp"
#include "kaboum/verify/exact_predicates.hpp"

namespace kaboum::verify {

using namespace kaboum::testing;

namespace {

// The pick-and-place scene with its bounding convex decomposition (cached beside the CLI tests').
World& pickAndPlaceWorld() {
  static World world(readSceneFile(exampleFile("pick-and-place/scene.yaml")),
                     {MeshPieces::Decomposition, std::filesystem::path(KABOUM_CLI).parent_path() /
                                                     "test-decomposition-cache"});
  return world;
}

// The robot at q, everything else as in the initial state.
GeometricState stateAt(const World& world, const std::vector<double>& q) {
  GeometricState state = world.initialState();
  state.robots[0].configuration = q;
  return state;
}

// Whether `state` collides by the World's predicates: `exact` installed, or the bounded ones.
bool collides(World& world, const ExactPredicates* exact, const GeometricState& state) {
  world.usePredicates(exact);
  const bool colliding = world.firstCollision(state).has_value();
  world.usePredicates(nullptr);
  return colliding;
}

std::vector<double> lerp(const std::vector<double>& a, const std::vector<double>& b, double t) {
  std::vector<double> q(a.size());
  for (std::size_t i = 0; i < a.size(); ++i) q[i] = a[i] + t * (b[i] - a[i]);
  return q;
}

}  // namespace

TEST(ExactPredicates, BoundedNeverCallsFreeWhatExactCallsColliding) {
  World& world = pickAndPlaceWorld();
  const ExactPredicates exact(world);
  std::mt19937_64 rng(1);
  std::size_t exactColliding = 0;
  constexpr int kConfigurations = 400;
  for (int i = 0; i < kConfigurations; ++i) {
    const GeometricState state =
        stateAt(world, kinematics::randomConfiguration(world.robots()[0].collision.model(), rng));
    const bool byExact = collides(world, &exact, state);
    const bool byBounded = collides(world, nullptr, state);
    EXPECT_TRUE(byBounded || !byExact) << "configuration " << i;
    exactColliding += byExact ? 1 : 0;
  }
  // Both verdicts occur: the property is tested on colliding and free states.
  EXPECT_GT(exactColliding, 0U);
  EXPECT_LT(exactColliding, static_cast<std::size_t>(kConfigurations));
}

TEST(ExactPredicates, NearAnExactContactTheBoundedPredicatesRejectAFreeState) {
  World& world = pickAndPlaceWorld();
  const ExactPredicates exact(world);
  std::mt19937_64 rng(2);
  const RobotModel& model = world.robots()[0].collision.model();
  const std::vector<double> home = world.initialState().robots[0].configuration;
  ASSERT_FALSE(collides(world, nullptr, stateAt(world, home)));
  // From home towards random colliding configurations: bisect the exact predicates' boundary and
  // look just on its free side.
  int found = 0;
  for (int segment = 0; segment < 20 && found == 0; ++segment) {
    const std::vector<double> target = kinematics::randomConfiguration(model, rng);
    if (!collides(world, &exact, stateAt(world, target))) continue;
    double free = 0, colliding = 1;
    for (int step = 0; step < 30; ++step) {
      const double middle = 0.5 * (free + colliding);
      (collides(world, &exact, stateAt(world, lerp(home, target, middle))) ? colliding : free) =
          middle;
    }
    const GeometricState nearContact = stateAt(world, lerp(home, target, free));
    ASSERT_FALSE(collides(world, &exact, nearContact));
    if (collides(world, nullptr, nearContact)) ++found;
  }
  EXPECT_GT(found, 0);
}

TEST(ExactPredicates, MotionsAreCheckedAtSamplesOneDegreeApartInEitherDirection) {
  World& world = pickAndPlaceWorld();
  const ExactPredicates exact(world);
  world.usePredicates(&exact);
  const motion::MotionGroup group(world, world.initialState(), {0});
  motion::CheckStatistics statistics;
  const std::unique_ptr<motion::MotionValidator> motions =
      motion::motionValidator(group, 0.005, &statistics);
  ASSERT_NE(dynamic_cast<motion::DiscreteMotionValidator*>(motions.get()), nullptr);
  std::mt19937_64 rng(3);
  std::size_t rejected = 0;
  constexpr int kPairs = 30;
  for (int pair = 0; pair < kPairs; ++pair) {
    const auto a = motion::randomFreeConfiguration(group, 0.0, rng);
    const auto b = motion::randomFreeConfiguration(group, 0.0, rng);
    ASSERT_TRUE(a && b);
    const bool valid = motions->isValid(*a, *b);
    EXPECT_EQ(motions->isValid(*b, *a), valid) << "pair " << pair;
    // The samples of the check: at most 1° (the scene's joint_step) apart in every joint.
    double largest = 0;
    for (std::size_t i = 0; i < a->size(); ++i)
      largest = std::max(largest, std::abs((*b)[i] - (*a)[i]));
    const int intervals =
        static_cast<int>(std::ceil(largest / world.description().settings.jointStep));
    bool sampleCollides = false;
    for (int k = 1; k < intervals && !sampleCollides; ++k) {
      sampleCollides =
          world.firstCollision(stateAt(world, lerp(*a, *b, double(k) / intervals))).has_value();
    }
    EXPECT_EQ(valid, !sampleCollides) << "pair " << pair;
    rejected += valid ? 0 : 1;
  }
  world.usePredicates(nullptr);
  EXPECT_GT(rejected, 0U);
  EXPECT_EQ(statistics.motionChecks, 2U * kPairs);
  EXPECT_EQ(statistics.motionPositives, 2 * rejected);
}

}  // namespace kaboum::verify
