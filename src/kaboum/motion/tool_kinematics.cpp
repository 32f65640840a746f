#include "kaboum/motion/tool_kinematics.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace kaboum::motion {

namespace {

double squaredDistance(std::span<const double> a, std::span<const double> b) {
  double sum = 0;
  for (std::size_t i = 0; i < a.size(); ++i) sum += (a[i] - b[i]) * (a[i] - b[i]);
  return sum;
}

}  // namespace

ToolKinematics::ToolKinematics(const World& world, std::size_t robot, std::size_t tool,
                               std::uint64_t seed)
    : world_(&world), robot_(robot) {
  if (robot >= world.robots().size()) {
    throw std::invalid_argument("no robot " + std::to_string(robot) + " in the world");
  }
  const RobotSpec& spec = world.description().robots[robot];
  if (tool >= spec.tools.size()) {
    throw std::invalid_argument("robot '" + spec.name + "' has no tool " + std::to_string(tool));
  }
  const ToolSpec& toolSpec = spec.tools[tool];
  name_ = toolSpec.name;
  tcp_ = toolSpec.tcp;
  const RobotModel& model = world.robots()[robot].collision.model();
  chain_ = std::make_unique<KinematicChain>(model, toolSpec.link, toolSpec.baseLink);
  baseLink_ = toolSpec.baseLink.empty() ? 0 : model.findLink(toolSpec.baseLink).value();
  if (toolSpec.ik != IkMethod::Numeric) closedForm_ = ArmIk::fit(*chain_);
  if (toolSpec.ik == IkMethod::ClosedForm && !closedForm_) {
    throw std::invalid_argument("tool '" + name_ + "' of robot '" + spec.name +
                                "': no closed-form IK fits its arm");
  }
  NumericIkOptions options;
  options.seed = seed;
  numeric_ = std::make_unique<NumericIk>(*chain_, options);
  options.maxStarts = 1;
  tracking_ = std::make_unique<NumericIk>(*chain_, options);
  for (int i = 0; i < chain_->dof(); ++i) {
    const auto joint =
        std::find_if(model.joints().begin(), model.joints().end(),
                     [&](const Joint& j) { return j.name == chain_->joint(i).name; });
    variables_.push_back(joint->variable);
  }
  linkPoses_.resize(model.links().size());
  chainQ_.resize(variables_.size());
  chainSolution_.resize(variables_.size());
}

Pose ToolKinematics::tcpPose(std::span<const double> q) {
  const RobotCollisionModel& robot = world_->robots()[robot_].collision;
  robot.model().linkPoses(q, linkPoses_);
  for (std::size_t i = 0; i < variables_.size(); ++i) {
    chainQ_[i] = q[static_cast<std::size_t>(variables_[i])];
  }
  return robot.basePose() * linkPoses_[static_cast<std::size_t>(baseLink_)] *
         chain_->toolPose(chainQ_) * tcp_;
}

Pose ToolKinematics::chainBase(std::span<const double> q) {
  const RobotCollisionModel& robot = world_->robots()[robot_].collision;
  robot.model().linkPoses(q, linkPoses_);
  return robot.basePose() * linkPoses_[static_cast<std::size_t>(baseLink_)];
}

Pose ToolKinematics::tipTarget(const Pose& tcp, std::span<const double> q) {
  return chainBase(q).inverse() * tcp * tcp_.inverse();
}

std::vector<double> ToolKinematics::withChainValues(std::span<const double> q,
                                                    std::span<const double> chainValues) const {
  std::vector<double> full(q.begin(), q.end());
  for (std::size_t i = 0; i < variables_.size(); ++i) {
    full[static_cast<std::size_t>(variables_[i])] = chainValues[i];
  }
  return full;
}

void ToolKinematics::snapToClosedForm(const Pose& tip) {
  // Radians (metres for a prismatic joint): above what the numeric solver's pose tolerance leaves
  // in the joints, below the distance between two branches of the closed form away from
  // singularities; a step a Cartesian motion's certification covers like any other.
  constexpr double kSnap = 1e-3;
  ArmIk::Solutions solved;
  closedForm_->solve(tip, solved);
  double nearest = kSnap;
  int chosen = -1;
  for (int s = 0; s < solved.count; ++s) {
    const ArmIk::Solution& q = solved.q[static_cast<std::size_t>(s)];
    double distance = 0;
    for (std::size_t i = 0; i < variables_.size(); ++i) {
      distance = std::max(distance, std::abs(q[i] - chainSolution_[i]));
    }
    if (distance <= nearest) {
      nearest = distance;
      chosen = s;
    }
  }
  if (chosen >= 0) {
    std::copy_n(solved.q[static_cast<std::size_t>(chosen)].begin(), variables_.size(),
                chainSolution_.begin());
  }
}

std::optional<std::vector<double>> ToolKinematics::solveNear(const Pose& tcp,
                                                             std::span<const double> near) {
  // Damped least squares from `near` first: it follows the arm continuously, also through wrist
  // singularities where the closed form's nearest solution may split the wrist angles otherwise.
  const Pose target = tipTarget(tcp, near);
  for (std::size_t i = 0; i < variables_.size(); ++i) {
    chainQ_[i] = near[static_cast<std::size_t>(variables_[i])];
  }
  if (tracking_->solve(target, chainQ_, chainSolution_)) {
    if (closedForm_) snapToClosedForm(target);
    return withChainValues(near, chainSolution_);
  }
  std::vector<std::vector<double>> all = solutions(tcp, near);
  if (all.empty()) return std::nullopt;
  return std::move(all.front());
}

std::vector<std::vector<double>> ToolKinematics::solutions(const Pose& tcp,
                                                           std::span<const double> near) {
  std::vector<std::vector<double>> found;
  const Pose target = tipTarget(tcp, near);
  if (closedForm_) {
    ArmIk::Solutions solved;
    closedForm_->solve(target, solved);
    for (int s = 0; s < solved.count; ++s) {
      found.push_back(withChainValues(
          near, std::span<const double>(solved.q[static_cast<std::size_t>(s)].data(),
                                        variables_.size())));
    }
  } else {
    for (std::size_t i = 0; i < variables_.size(); ++i) {
      chainQ_[i] = near[static_cast<std::size_t>(variables_[i])];
    }
    if (numeric_->solve(target, chainQ_, chainSolution_)) {
      found.push_back(withChainValues(near, chainSolution_));
    }
  }
  std::stable_sort(found.begin(), found.end(), [&](const auto& a, const auto& b) {
    return squaredDistance(a, near) < squaredDistance(b, near);
  });
  return found;
}

}  // namespace kaboum::motion
