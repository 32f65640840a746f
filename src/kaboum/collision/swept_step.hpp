// Sampling steps for swept volumes of straight joint-space motions: every vertex of a link stays
// within ε of the chord between consecutive samples (thesis §4.5, Proposition 3, Eq. 4.19–4.21).
#pragma once

#include <span>
#include <vector>

#include "kaboum/kinematics/robot_model.hpp"

namespace kaboum::collision {

using namespace kaboum::kinematics;

// The joints a link's pose depends on, and a configuration-independent bound on the distance
// from the link frame origin to every joint origin (a point on its axis) before it.
struct LinkSweepChain {
  std::vector<int> revoluteVariables;  // revolute and continuous joints on the path to the link
  // Prismatic joints after the first revolute joint (earlier ones only add a straight-line
  // translation, which a chord follows exactly).
  std::vector<int> bentPrismaticVariables;
  // Σ of |joint origin offset| (+ the largest |limit| for prismatic joints) from the first
  // revolute joint to the link: the "sum of link lengths" of Eq. 4.19's r_max, per link.
  double chainReach = 0;
};

// One chain per link of `model`, in link order.
std::vector<LinkSweepChain> linkSweepChains(const RobotModel& model);

// Number n >= 1 of equal sub-steps of the straight motion qa -> qb such that, within each
// sub-step, every point at most `vertexRadius` from the link origin deviates at most `epsilon`
// from its chord. With r = chainReach + vertexRadius and W = Σ|Δq_i| over the revolute joints:
// - revolute joints only: Baginski's bound (Eq. 4.19) in its exact form,
//   r (1 - cos(W/n / 2)) <= ε, i.e. W/n <= 2 acos(1 - ε/r) (and W/n <= π);
//   Eq. 4.20 (ε <= r (W/n)^2 / 8) and the step Eq. 4.21 (Δq = sqrt(8ε/r)) are its quadratic
//   approximation, which this never needs;
// - with bent prismatic joints (D = Σ|Δd_j|): the chord error of a curve is at most max|p''| / 8,
//   and |p''| <= 2 W^2 r + 2 W D per unit parameter, so n^2 >= (W^2 r + W D) / (4ε).
// `epsilon` must be positive.
int sweepSubdivisions(const LinkSweepChain& chain, std::span<const double> qa,
                      std::span<const double> qb, double vertexRadius, double epsilon);

}  // namespace kaboum::collision
