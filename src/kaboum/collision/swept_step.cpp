#include "kaboum/collision/swept_step.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace kaboum::collision {

using namespace kaboum::kinematics;

std::vector<LinkSweepChain> linkSweepChains(const RobotModel& model) {
  const auto& links = model.links();
  const auto& joints = model.joints();
  std::vector<LinkSweepChain> chains(links.size());
  // Joints are stored parent-first, so a link's parent chain is complete before the link.
  for (const Joint& joint : joints) {
    const auto child = static_cast<std::size_t>(joint.childLink);
    LinkSweepChain chain = chains[static_cast<std::size_t>(joint.parentLink)];
    const bool bent = !chain.revoluteVariables.empty();
    const bool revolute = joint.type == JointType::Revolute || joint.type == JointType::Continuous;
    if (bent) {
      chain.chainReach += joint.origin.translation().norm();
      if (joint.type == JointType::Prismatic) {
        chain.chainReach += std::max(std::abs(joint.lower), std::abs(joint.upper));
        chain.bentPrismaticVariables.push_back(joint.variable);
      }
    }
    if (revolute) chain.revoluteVariables.push_back(joint.variable);
    chains[child] = std::move(chain);
  }
  return chains;
}

int sweepSubdivisions(const LinkSweepChain& chain, std::span<const double> qa,
                      std::span<const double> qb, double vertexRadius, double epsilon) {
  double turn = 0;  // W
  for (int v : chain.revoluteVariables) {
    turn += std::abs(qb[static_cast<std::size_t>(v)] - qa[static_cast<std::size_t>(v)]);
  }
  if (turn == 0) return 1;
  double shift = 0;  // D
  for (int v : chain.bentPrismaticVariables) {
    shift += std::abs(qb[static_cast<std::size_t>(v)] - qa[static_cast<std::size_t>(v)]);
  }
  const double reach = chain.chainReach + vertexRadius;
  double steps = turn / std::numbers::pi;
  if (shift == 0) {
    if (epsilon < reach) steps = std::max(steps, turn / (2 * std::acos(1 - epsilon / reach)));
  } else {
    steps = std::max(steps, std::sqrt((turn * turn * reach + turn * shift) / (4 * epsilon)));
  }
  return std::max(1, static_cast<int>(std::ceil(steps)));
}

}  // namespace kaboum::collision
