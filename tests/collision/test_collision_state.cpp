// Collision queries evaluate a given state: the robot model and the scene are shared and never
// change, so states evaluated alternately (through one reused sweep workspace) give exactly the
// answers each gives alone.
#include <gtest/gtest.h>

#include <optional>
#include <random>
#include <vector>

#include "collision_test_support.hpp"
#include "kaboum/collision/predicates.hpp"
#include "kaboum/collision/swept.hpp"
#include "kaboum/testing/scene_generator.hpp"

namespace kaboum::collision {

using namespace kaboum::kinematics;
using namespace kaboum::testing;

namespace {

const Aabb kRegion{Vec3(-0.8, -1.2, -0.8), Vec3(0.8, 0.4, 0.8)};
constexpr std::size_t kObjects = 50, kMovable = 15;
constexpr double kEpsilon = 0.005;

// One geometric state of a planner: a configuration (and the end of a motion from it), where the
// movable objects are, and what the robot holds.
struct WorldState {
  std::vector<double> q, motionEnd;
  std::vector<Pose> linkPoses;
  SceneState placements;
  std::vector<Attachment> held;
};

WorldState randomState(const RobotCollisionModel& robot, const CollisionScene& scene,
                       std::mt19937_64& rng) {
  const RobotModel& model = robot.model();
  WorldState state;
  state.q = randomConfiguration(model, rng);
  state.motionEnd = randomConfiguration(model, rng);
  for (std::size_t v = 0; v < state.q.size(); ++v) {
    state.motionEnd[v] = state.q[v] + 0.3 * (state.motionEnd[v] - state.q[v]);
  }
  state.linkPoses.resize(model.links().size());
  model.linkPoses(state.q, state.linkPoses);
  state.placements = scene.initialState();
  for (Placement& placement : state.placements) {
    placement.pose = Pose(uniformRotation(rng));
    const Vec3 unit(uniformUnit(rng), uniformUnit(rng), uniformUnit(rng));
    placement.pose.translation() = kRegion.lo + unit.cwiseProduct(kRegion.hi - kRegion.lo);
    placement.present = uniformUnit(rng) < 0.8;
  }
  // Up to two different objects held, each by a random link with geometry at a random grasp; a
  // held object is not in the scene.
  const std::size_t heldCount = rng() % 3, first = rng() % kMovable;
  for (std::size_t h = 0; h < heldCount; ++h) {
    const std::size_t object = kObjects - kMovable + (first + h * (1 + rng() % 7)) % kMovable;
    state.placements[scene.slot(object)].present = false;
    const int link = robot.part(rng() % robot.partCount()).link;
    state.held.push_back({scene.sharedBody(object), link, test::randomPose(rng, 0.1)});
  }
  return state;
}

// Every query of a state: robot against the scene and itself, each movable object against the
// rest and on a support surface, and the swept volume of the motion from q.
struct Answers {
  std::optional<std::size_t> sceneHit;
  bool selfCollides = false;
  std::vector<std::optional<std::size_t>> objectHits;
  std::vector<bool> supported;
  std::optional<std::size_t> sweptHit;
  bool sweptSelfCollides = false;
  bool operator==(const Answers&) const = default;
};

// The answers of `states`, asked query kind by query kind over all of them in turn (so that a
// list like {a, b, a, b} alternates the states between consecutive queries), through one sweep.
std::vector<Answers> evaluate(const RobotCollisionModel& robot, const CollisionScene& scene,
                              RobotSweep& sweep, const std::vector<const WorldState*>& states) {
  std::vector<Answers> answers(states.size());
  for (std::size_t k = 0; k < states.size(); ++k) {
    const WorldState& s = *states[k];
    answers[k].sceneHit = robot.firstSceneCollision(s.linkPoses, s.held, scene, s.placements, 0.0);
  }
  for (std::size_t k = 0; k < states.size(); ++k) {
    const WorldState& s = *states[k];
    answers[k].selfCollides = robot.selfCollides(s.linkPoses, s.held, 0.0);
  }
  for (std::size_t object = kObjects - kMovable; object < kObjects; ++object) {
    for (std::size_t k = 0; k < states.size(); ++k) {
      const WorldState& s = *states[k];
      answers[k].objectHits.push_back(scene.firstCollision(
          s.placements, scene.body(object), scene.pose(object, s.placements), 0.01, object));
      answers[k].supported.push_back(isOnSupportSurface(scene, s.placements, object, 0.05, 0.01));
    }
  }
  for (std::size_t k = 0; k < states.size(); ++k) {
    const WorldState& s = *states[k];
    answers[k].sweptHit =
        sweep.firstSceneCollision(s.q, s.motionEnd, s.held, scene, s.placements, 0.0, kEpsilon);
  }
  for (std::size_t k = 0; k < states.size(); ++k) {
    const WorldState& s = *states[k];
    answers[k].sweptSelfCollides = sweep.selfCollides(s.q, s.motionEnd, s.held, 0.0, kEpsilon);
  }
  return answers;
}

// Whether some part of the robot in `s` collides with some present object (every pair tested).
bool bruteForceSceneCollision(const RobotCollisionModel& robot, const CollisionScene& scene,
                              const WorldState& s) {
  for (std::size_t i = 0; i < robot.partCount(s.held); ++i) {
    for (std::size_t o = 0; o < scene.size(); ++o) {
      if (scene.present(o, s.placements) &&
          bodiesCollide(*robot.part(i, s.held).body, robot.partPose(i, s.linkPoses, s.held),
                        scene.body(o), scene.pose(o, s.placements), 0.0)) {
        return true;
      }
    }
  }
  return false;
}

TEST(CollisionState, StatesEvaluatedAlternatelyGiveTheAnswersOfEachAlone) {
  const RobotCollisionModel robot = test::kr5AllowingHomeOverlaps();
  const CollisionScene scene = randomObstacleScene(kRegion, static_cast<int>(kObjects), 12, 0.04, 3,
                                                   static_cast<int>(kMovable));
  std::mt19937_64 rng(31);
#if defined(__SANITIZE_ADDRESS__)
  const int count = 30;
#else
  const int count = 200;
#endif
  std::vector<WorldState> states;
  for (int k = 0; k < count; ++k) states.push_back(randomState(robot, scene, rng));

  std::vector<Answers> alone;
  int hits = 0, holding = 0, selfHits = 0;
  for (const WorldState& s : states) {
    RobotSweep fresh(robot);
    alone.push_back(evaluate(robot, scene, fresh, {&s}).front());
    EXPECT_EQ(alone.back().sceneHit.has_value(), bruteForceSceneCollision(robot, scene, s));
    hits += alone.back().sceneHit.has_value();
    selfHits += alone.back().selfCollides;
    holding += !s.held.empty();
  }
  // The states differ in what they report: the comparison below is not vacuous.
  EXPECT_GT(hits, 0);
  EXPECT_LT(hits, count);
  EXPECT_GT(selfHits, 0);
  EXPECT_GT(holding, count / 3);

  RobotSweep shared(robot);
  for (std::size_t a = 0; a < states.size(); ++a) {
    const std::size_t b = (a + 1 + rng() % (states.size() - 1)) % states.size();
    const auto together = evaluate(robot, scene, shared,
                                   {&states[a], &states[b], &states[a], &states[b], &states[a]});
    for (std::size_t k = 0; k < together.size(); ++k) {
      EXPECT_EQ(together[k], alone[k % 2 == 0 ? a : b]) << "states " << a << " and " << b;
    }
  }
}

}  // namespace
}  // namespace kaboum::collision
