#include "ompl_fcl_baseline.hpp"

#include <ompl/base/DiscreteMotionValidator.h>
#include <ompl/base/PlannerTerminationCondition.h>
#include <ompl/base/ProblemDefinition.h>
#include <ompl/base/ScopedState.h>
#include <ompl/base/SpaceInformation.h>
#include <ompl/base/StateValidityChecker.h>
#include <ompl/base/spaces/RealVectorStateSpace.h>
#include <ompl/geometric/PathGeometric.h>
#include <ompl/geometric/PathSimplifier.h>
#include <ompl/geometric/planners/rrt/RRTConnect.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <optional>

#include "kaboum/motion/motion_planner.hpp"

namespace kaboum::cli {

namespace ob = ompl::base;
namespace og = ompl::geometric;

using collision::RobotCollisionModel;

namespace {

// The collision part of `link` of a robot, as the verifier maps them (path_verifier.cpp).
std::optional<std::size_t> partOf(const RobotCollisionModel& collision, std::size_t link) {
  for (std::size_t part = 0; part < collision.partCount(); ++part) {
    if (static_cast<std::size_t>(collision.part(part).link) == link) return part;
  }
  return std::nullopt;
}

// World poses of every link of `robot` at configuration q.
void worldLinkPoses(const world::WorldRobot& robot, std::span<const double> q,
                    std::vector<Pose>& poses) {
  robot.collision.model().linkPoses(q, poses);
  const Pose& base = robot.collision.basePose();
  for (Pose& pose : poses) pose = base * pose;
}

}  // namespace

FclStateChecker::FclStateChecker(const verify::ReferenceGeometry& geometry,
                                 const motion::MotionGroup& group)
    : geometry_(geometry), group_(group) {
  const world::World& world = geometry.world();
  const world::GeometricState& context = group.context();
  const std::vector<std::size_t>& moving = group.robots();
  for (std::size_t k = 0; k < moving.size(); ++k) {
    const RobotCollisionModel& collision = world.robots()[moving[k]].collision;
    for (std::size_t link = 0; link < collision.model().links().size(); ++link) {
      if (const auto body = geometry.linkBody(moving[k], link)) links_.push_back({k, link, *body});
    }
    linkPoses_.emplace_back(collision.model().links().size());
  }
  for (std::size_t object = 0; object < world.scene().size(); ++object) {
    if (world.scene().present(object, context.placements)) {
      obstacles_.emplace_back(geometry.objectBody(object),
                              world.scene().pose(object, context.placements));
    }
  }
  std::vector<Pose> poses;
  for (std::size_t robot = 0; robot < world.robots().size(); ++robot) {
    if (std::find(moving.begin(), moving.end(), robot) != moving.end()) continue;
    worldLinkPoses(world.robots()[robot], context.robots[robot].configuration, poses);
    for (std::size_t link = 0; link < poses.size(); ++link) {
      if (const auto body = geometry.linkBody(robot, link))
        obstacles_.emplace_back(*body, poses[link]);
    }
  }
  for (std::size_t i = 0; i < links_.size(); ++i) {
    for (std::size_t j = i + 1; j < links_.size(); ++j) {
      if (links_[i].robot != links_[j].robot) {
        pairs_.emplace_back(i, j);
        continue;
      }
      const RobotCollisionModel& collision = world.robots()[moving[links_[i].robot]].collision;
      const auto a = partOf(collision, links_[i].link), b = partOf(collision, links_[j].link);
      if (!a || !b || !collision.filter().allowed(*a, *b)) pairs_.emplace_back(i, j);
    }
  }
}

bool FclStateChecker::isValid(std::span<const double> q) {
  ++checks_;
  for (std::size_t k = 0; k < linkPoses_.size(); ++k) {
    worldLinkPoses(geometry_.world().robots()[group_.robots()[k]], group_.robotPart(q, k),
                   linkPoses_[k]);
  }
  const auto poseOf = [&](const MovingLink& link) -> const Pose& {
    return linkPoses_[link.robot][link.link];
  };
  // A pure collision test: no distance is wanted (-infinity of interest).
  constexpr double kNoDistance = -std::numeric_limits<double>::infinity();
  for (const MovingLink& link : links_) {
    for (const auto& [body, pose] : obstacles_) {
      if (geometry_.proximity(link.body, poseOf(link), body, pose, kNoDistance).collides) {
        return false;
      }
    }
  }
  for (const auto& [i, j] : pairs_) {
    if (geometry_
            .proximity(links_[i].body, poseOf(links_[i]), links_[j].body, poseOf(links_[j]),
                       kNoDistance)
            .collides) {
      return false;
    }
  }
  return true;
}

namespace {

using RealState = ob::RealVectorStateSpace::StateType;

// OMPL's joint space with motions cut by the largest joint motion (the L∞ distance) instead of
// the Euclidean distance: with the longest valid segment at 1°, no joint moves more than 1°
// between two checked states, and no motion is checked more densely than that needs. The
// planner's metric (nearest neighbours, range) stays OMPL's Euclidean one.
class JointStepSpace final : public ob::RealVectorStateSpace {
 public:
  using ob::RealVectorStateSpace::RealVectorStateSpace;
  unsigned int validSegmentCount(const ob::State* a, const ob::State* b) const override {
    const double* p = a->as<RealState>()->values;
    const double* r = b->as<RealState>()->values;
    double largest = 0;
    for (unsigned int i = 0; i < getDimension(); ++i)
      largest = std::max(largest, std::abs(p[i] - r[i]));
    const auto segments =
        static_cast<unsigned int>(std::ceil(largest / getLongestValidSegmentLength()));
    return longestValidSegmentCountFactor_ * std::max(1U, segments);
  }
};

class FclValidity final : public ob::StateValidityChecker {
 public:
  FclValidity(const ob::SpaceInformationPtr& si, FclStateChecker& checker, std::size_t dimension)
      : ob::StateValidityChecker(si), checker_(checker), dimension_(dimension) {}
  bool isValid(const ob::State* state) const override {
    return checker_.isValid({state->as<RealState>()->values, dimension_});
  }

 private:
  FclStateChecker& checker_;
  std::size_t dimension_;
};

std::vector<std::vector<double>> waypointsOf(og::PathGeometric& path, std::size_t dimension) {
  std::vector<std::vector<double>> waypoints;
  for (const ob::State* state : path.getStates()) {
    const double* q = state->as<RealState>()->values;
    waypoints.emplace_back(q, q + dimension);
  }
  return waypoints;
}

double secondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

OmplFclResult planWithOmplFcl(const motion::MotionGroup& group, FclStateChecker& checker,
                              std::span<const double> start, std::span<const double> goal,
                              const OmplFclOptions& options) {
  const std::size_t dimension = group.dimension();
  auto space = std::make_shared<JointStepSpace>(static_cast<unsigned int>(dimension));
  ob::RealVectorBounds bounds(static_cast<unsigned int>(dimension));
  bounds.low = group.lower();
  bounds.high = group.upper();
  space->setBounds(bounds);
  space->setLongestValidSegmentFraction(options.resolution / space->getMaximumExtent());
  auto si = std::make_shared<ob::SpaceInformation>(space);
  si->setStateValidityChecker(std::make_shared<FclValidity>(si, checker, dimension));
  si->setMotionValidator(std::make_shared<ob::DiscreteMotionValidator>(si));
  si->setup();

  ob::ScopedState<ob::RealVectorStateSpace> startState(space), goalState(space);
  for (std::size_t i = 0; i < dimension; ++i) {
    startState[static_cast<unsigned int>(i)] = start[i];
    goalState[static_cast<unsigned int>(i)] = goal[i];
  }
  auto problem = std::make_shared<ob::ProblemDefinition>(si);
  problem->setStartAndGoalStates(startState, goalState);
  auto planner = std::make_shared<og::RRTConnect>(si);
  planner->setProblemDefinition(problem);
  planner->setup();

  OmplFclResult result;
  const std::size_t checksBefore = checker.checks();
  const auto planning = std::chrono::steady_clock::now();
  const ob::PlannerStatus status =
      planner->solve(ob::timedPlannerTerminationCondition(options.timeLimit));
  result.planningSeconds = secondsSince(planning);
  result.status = status.asString();
  result.solved = status == ob::PlannerStatus::EXACT_SOLUTION;
  if (result.solved) {
    og::PathGeometric& path = *problem->getSolutionPath()->as<og::PathGeometric>();
    result.plannedWaypoints = path.getStateCount();
    result.plannedLength = motion::pathLength(waypointsOf(path, dimension));
    const auto simplifying = std::chrono::steady_clock::now();
    og::PathSimplifier simplifier(si);
    simplifier.simplifyMax(path);
    result.simplifySeconds = secondsSince(simplifying);
    result.path = waypointsOf(path, dimension);
    result.length = motion::pathLength(result.path);
  }
  result.stateChecks = checker.checks() - checksBefore;
  return result;
}

}  // namespace kaboum::cli
