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

FclStateChecker::FclStateChecker(const verify::ReferenceGeometry& geometry, std::size_t robot)
    : geometry_(geometry), robot_(geometry.world().robots().at(robot)) {
  const world::World& world = geometry.world();
  const RobotCollisionModel& collision = robot_.collision;
  for (std::size_t link = 0; link < collision.model().links().size(); ++link) {
    if (const auto body = geometry.linkBody(robot, link)) links_.emplace_back(link, *body);
  }
  const world::GeometricState initial = world.initialState();
  for (std::size_t object = 0; object < world.scene().size(); ++object) {
    objects_.emplace_back(geometry.objectBody(object),
                          world.scene().pose(object, initial.placements));
  }
  // The link part of each link, as the verifier maps them (path_verifier.cpp).
  const auto partOf = [&](std::size_t link) -> std::optional<std::size_t> {
    for (std::size_t part = 0; part < collision.partCount(); ++part) {
      if (static_cast<std::size_t>(collision.part(part).link) == link) return part;
    }
    return std::nullopt;
  };
  for (std::size_t i = 0; i < links_.size(); ++i) {
    for (std::size_t j = i + 1; j < links_.size(); ++j) {
      const auto a = partOf(links_[i].first), b = partOf(links_[j].first);
      if (!a || !b || !collision.filter().allowed(*a, *b)) selfPairs_.emplace_back(i, j);
    }
  }
  linkPoses_.resize(collision.model().links().size());
}

bool FclStateChecker::isValid(std::span<const double> q) {
  ++checks_;
  robot_.collision.model().linkPoses(q, linkPoses_);
  const Pose& base = robot_.collision.basePose();
  for (Pose& pose : linkPoses_) pose = base * pose;
  // A pure collision test: no distance is wanted (-infinity of interest).
  constexpr double kNoDistance = -std::numeric_limits<double>::infinity();
  for (const auto& [link, body] : links_) {
    for (const auto& [object, pose] : objects_) {
      if (geometry_.proximity(body, linkPoses_[link], object, pose, kNoDistance).collides) {
        return false;
      }
    }
  }
  for (const auto& [i, j] : selfPairs_) {
    const auto& [linkA, bodyA] = links_[i];
    const auto& [linkB, bodyB] = links_[j];
    if (geometry_.proximity(bodyA, linkPoses_[linkA], bodyB, linkPoses_[linkB], kNoDistance)
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
