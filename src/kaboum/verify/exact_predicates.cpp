#include "kaboum/verify/exact_predicates.hpp"

namespace kaboum::verify {

ExactPredicates::ExactPredicates(const World& world) : reference_(world) {}

std::size_t ExactPredicates::bodyOf(const GeometricState& state, std::size_t robot,
                                    std::size_t part) const {
  const RobotCollisionModel& model = reference_.world().robots()[robot].collision;
  if (part >= model.partCount()) {
    return reference_.objectBody(state.robots[robot].heldObjects[part - model.partCount()]);
  }
  return reference_.linkBody(robot, static_cast<std::size_t>(model.part(part).link)).value();
}

std::optional<Collision> ExactPredicates::firstCollisionOfRobot(
    const GeometricState& state, const QueryScratch& scratch, std::size_t robot,
    std::span<const std::uint8_t> against) const {
  const World& world = reference_.world();
  const CollisionScene& scene = world.scene();
  const RobotCollisionModel& model = world.robots()[robot].collision;
  const std::span<const Attachment> held = state.robots[robot].held;
  const std::span<const Pose> poses = scratch.linkPoses[robot];
  const std::size_t parts = model.partCount(held);
  for (std::size_t i = 0; i < parts; ++i) {
    const Pose pose = model.partPose(i, poses, held);
    for (std::size_t j = i + 1; j < parts; ++j) {
      if (model.checksPair(i, j, held) &&
          reference_.collides(bodyOf(state, robot, i), pose, bodyOf(state, robot, j),
                              model.partPose(j, poses, held))) {
        return Collision{world.partyOf(state, robot, i), world.partyOf(state, robot, j)};
      }
    }
  }
  for (std::size_t i = 0; i < parts; ++i) {
    const Pose pose = model.partPose(i, poses, held);
    for (std::size_t object = 0; object < scene.size(); ++object) {
      if (scene.present(object, state.placements) &&
          reference_.collides(bodyOf(state, robot, i), pose, reference_.objectBody(object),
                              scene.pose(object, state.placements))) {
        return Collision{world.partyOf(state, robot, i), {Party::Kind::Object, object}};
      }
    }
  }
  for (std::size_t other = 0; other < world.robots().size(); ++other) {
    if (other == robot || against[other] == 0) continue;
    const RobotCollisionModel& otherModel = world.robots()[other].collision;
    const std::span<const Attachment> otherHeld = state.robots[other].held;
    for (std::size_t i = 0; i < parts; ++i) {
      const Pose pose = model.partPose(i, poses, held);
      for (std::size_t j = 0; j < otherModel.partCount(otherHeld); ++j) {
        if (reference_.collides(bodyOf(state, robot, i), pose, bodyOf(state, other, j),
                                otherModel.partPose(j, scratch.linkPoses[other], otherHeld))) {
          return Collision{world.partyOf(state, robot, i), world.partyOf(state, other, j)};
        }
      }
    }
  }
  return std::nullopt;
}

std::optional<Party> ExactPredicates::firstCollisionOfObject(const GeometricState& state,
                                                             const QueryScratch& scratch,
                                                             std::size_t object, const Pose& pose,
                                                             bool withRobots) const {
  const World& world = reference_.world();
  const CollisionScene& scene = world.scene();
  const std::size_t body = reference_.objectBody(object);
  for (std::size_t other = 0; other < scene.size(); ++other) {
    if (other != object && !state.areJoined(object, other) &&
        scene.present(other, state.placements) &&
        reference_.collides(body, pose, reference_.objectBody(other),
                            scene.pose(other, state.placements))) {
      return Party{Party::Kind::Object, other};
    }
  }
  if (!withRobots) return std::nullopt;
  for (std::size_t r = 0; r < world.robots().size(); ++r) {
    const RobotCollisionModel& model = world.robots()[r].collision;
    const RobotState& robot = state.robots[r];
    for (std::size_t i = 0; i < model.partCount(robot.held); ++i) {
      if (i >= model.partCount() && robot.heldObjects[i - model.partCount()] == object) continue;
      if (reference_.collides(body, pose, bodyOf(state, r, i),
                              model.partPose(i, scratch.linkPoses[r], robot.held))) {
        return world.partyOf(state, r, i);
      }
    }
  }
  return std::nullopt;
}

}  // namespace kaboum::verify
