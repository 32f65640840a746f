#include "kaboum/tamp/grasp_sampler.hpp"

#include <variant>

#include "kaboum/core/error.hpp"
#include "kaboum/kinematics/constraint_sampler.hpp"
#include "kaboum/kinematics/random_configuration.hpp"

namespace kaboum::tamp {

namespace {

// Whether Table 5.1 defines `type` with the hand's feature first (else the object's is first:
// every relation is symmetric).
bool handFirst(const GraspConstraint& constraint) {
  try {
    (void)costFunctionFor(constraint.type, constraint.hand.kind, constraint.object.kind);
    return true;
  } catch (const InputError&) {
    return false;
  }
}

Pose freeMotion(const FreeMotion& motion, double value) {
  Pose pose = Pose::Identity();
  const Vec3 axis = Vec3::Unit(motion.axis);
  if (motion.kind == FreeMotion::Kind::Translation) {
    pose.translation() = value * axis;
  } else {
    pose.linear() = Eigen::AngleAxisd(value, axis).toRotationMatrix();
  }
  return pose;
}

}  // namespace

GraspSampler::GraspSampler(const World& world, motion::ToolKinematics& tool)
    : world_(&world), tool_(&tool) {}

std::vector<GraspCandidate> GraspSampler::sample(std::size_t object, const Pose& objectPose,
                                                 std::span<const double> near,
                                                 std::mt19937_64& rng) {
  const std::vector<GraspSpec>& grasps = world_->description().objects.at(object).grasps;
  if (grasps.empty()) return {};
  const std::size_t index = rng() % grasps.size();
  std::vector<GraspCandidate> found = std::visit(
      [&](const auto& definition) -> std::vector<GraspCandidate> {
        if constexpr (std::is_same_v<std::decay_t<decltype(definition)>, GraspPose>) {
          return samplePose(definition, objectPose, near, rng);
        } else {
          return sampleConstraints(definition, objectPose, near, rng);
        }
      },
      grasps[index].definition);
  for (GraspCandidate& candidate : found) candidate.grasp = index;
  return found;
}

// Algorithm 3 over the arm's chain: F(q) stacks the Table 5.1 costs of the hand's features (on
// the tool centre point) against the object's (at its pose); a random start is projected onto
// F(q) = 0 within the joint limits.
std::vector<GraspCandidate> GraspSampler::sampleConstraints(
    const std::vector<GraspConstraint>& constraints, const Pose& objectPose,
    std::span<const double> near, std::mt19937_64& rng) {
  ConstraintProblem problem;
  const int robot = problem.addRobot(tool_->chain(), tool_->chainBase(near));
  for (const GraspConstraint& constraint : constraints) {
    const auto hand = problem.attachToTool(robot, tool_->tcp(), constraint.hand);
    const auto onObject = problem.attachToObject(objectPose, constraint.object);
    if (handFirst(constraint)) {
      problem.addConstraint(constraint.type, hand, onObject, constraint.distance);
    } else {
      problem.addConstraint(constraint.type, onObject, hand, constraint.distance);
    }
  }
  ConstraintSamplerOptions options;
  options.seed = rng();
  options.maxAttempts = 1;
  ConstraintSampler sampler(problem, options);
  std::vector<double> chainValues(static_cast<std::size_t>(problem.dof()));
  if (!sampler.sample(chainValues)) return {};
  GraspCandidate candidate;
  candidate.configuration = tool_->withChainValues(near, chainValues);
  candidate.tcpInObject = objectPose.inverse() * tool_->tcpPose(candidate.configuration);
  return {std::move(candidate)};
}

// The grasp pose moved by each free motion by a uniform value of its range, then IK: every
// solution, nearest `near` first.
std::vector<GraspCandidate> GraspSampler::samplePose(const GraspPose& grasp, const Pose& objectPose,
                                                     std::span<const double> near,
                                                     std::mt19937_64& rng) {
  Pose motion = Pose::Identity();
  for (const FreeMotion& free : grasp.free) {
    motion = motion * freeMotion(free, free.lower + uniformUnit(rng) * (free.upper - free.lower));
  }
  const Pose tcpInObject = motion * grasp.tcp;
  std::vector<GraspCandidate> candidates;
  for (std::vector<double>& solution : tool_->solutions(objectPose * tcpInObject, near)) {
    candidates.push_back({std::move(solution), tcpInObject, 0});
  }
  return candidates;
}

}  // namespace kaboum::tamp
