// A robot's tool in the world frame (thesis §5.1, Appendix A.3): the tool centre point of one of
// the scene file's tools, and inverse kinematics for it — the closed form where the arm fits it,
// damped least squares otherwise — on full robot configurations (joints outside the tool's chain,
// such as fingers or a mobile base, keep their values).
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <vector>

#include "kaboum/kinematics/arm_ik.hpp"
#include "kaboum/kinematics/kinematic_chain.hpp"
#include "kaboum/kinematics/numeric_ik.hpp"
#include "kaboum/world/world.hpp"

namespace kaboum::motion {

using namespace kaboum::world;

class ToolKinematics {
 public:
  // Tool `tool` (index into the scene file's tools of the robot) of robot `robot` of `world`.
  // Throws std::invalid_argument for an unknown robot or tool. `world` must outlive it.
  ToolKinematics(const World& world, std::size_t robot, std::size_t tool, std::uint64_t seed = 1);

  [[nodiscard]] std::size_t robot() const { return robot_; }
  [[nodiscard]] const std::string& name() const { return name_; }
  // The tool centre point in the world frame at robot configuration q.
  [[nodiscard]] Pose tcpPose(std::span<const double> q);
  // A configuration reaching `tcp` near `near`: numeric IK started at `near` (continuity along a
  // Cartesian motion, through wrist singularities too) — replaced by the closed form's solution
  // when one lies within 1e-3 of it, so that a pose reached from different starts gives the same
  // configuration (equal geometric states compare equal) —, else the nearest of solutions(),
  // else nullopt.
  [[nodiscard]] std::optional<std::vector<double>> solveNear(const Pose& tcp,
                                                             std::span<const double> near);
  // Every configuration reaching `tcp` the solver finds (the closed form's distinct solutions, or
  // numeric IK from `near` and seeded restarts), nearest `near` first.
  [[nodiscard]] std::vector<std::vector<double>> solutions(const Pose& tcp,
                                                           std::span<const double> near);

  // The chain from the tool's base link to its link, for constraint problems over it (§5.2).
  [[nodiscard]] const KinematicChain& chain() const { return *chain_; }
  // The tool centre point in the tool link frame.
  [[nodiscard]] const Pose& tcp() const { return tcp_; }
  // The world pose of the chain's base link at robot configuration q (its base link may move).
  [[nodiscard]] Pose chainBase(std::span<const double> q);
  // The robot configuration q with the chain's joints set to `chainValues` (chain order).
  [[nodiscard]] std::vector<double> withChainValues(std::span<const double> q,
                                                    std::span<const double> chainValues) const;

 private:
  // The target of the chain's tip in its base frame, at configuration q (its base link may move).
  [[nodiscard]] Pose tipTarget(const Pose& tcp, std::span<const double> q);
  // Replaces chainSolution_ (numeric IK for the chain tip at `tip`) by the closed form's solution
  // within a rounding distance of it, if there is one.
  void snapToClosedForm(const Pose& tip);

  const World* world_;
  std::size_t robot_;
  std::string name_;
  std::unique_ptr<KinematicChain> chain_;  // stable address for the solvers
  std::optional<ArmIk> closedForm_;
  std::unique_ptr<NumericIk> numeric_;   // with seeded random restarts
  std::unique_ptr<NumericIk> tracking_;  // from the given configuration only
  int baseLink_ = 0;
  Pose tcp_ = Pose::Identity();
  std::vector<int> variables_;  // per chain joint: its robot configuration index
  std::vector<Pose> linkPoses_;
  std::vector<double> chainQ_, chainSolution_;
};

}  // namespace kaboum::motion
