// Closed-form IK (thesis Appendix A.3) for a URDF chain: recognises the five- and six-axis arm
// families by their joint axes, derives their parameters, and maps solutions to joint values.
#pragma once

#include <array>
#include <optional>
#include <span>

#include "kaboum/kinematics/closed_form_ik.hpp"
#include "kaboum/kinematics/kinematic_chain.hpp"

namespace kaboum::kinematics {

class ArmIk {
 public:
  enum class Family { FiveAxis, SixAxis };
  static constexpr int kMaxSolutions = 8;
  using Solution = std::array<double, 6>;  // joint values; the first dof() entries are used
  struct Solutions {
    std::array<Solution, kMaxSolutions> q{};
    int count = 0;
  };

  // The closed-form solver for `chain` if its axes fit one of the families (verified by FK on
  // sample configurations), else nullopt. `chain` must outlive the solver.
  static std::optional<ArmIk> fit(const KinematicChain& chain);

  [[nodiscard]] Family family() const { return family_; }
  [[nodiscard]] int dof() const { return family_ == Family::SixAxis ? 6 : 5; }
  [[nodiscard]] const SixAxisArm& sixAxis() const { return six_; }
  [[nodiscard]] const FiveAxisArm& fiveAxis() const { return five_; }

  // All distinct solutions within joint limits for the tip pose (chain root frame); each one
  // reproduces `tip` by FK. Zero solutions means unreachable. Allocates nothing.
  void solve(const Pose& tip, Solutions& out) const;

 private:
  ArmIk(const KinematicChain& chain, Family family) : chain_(&chain), family_(family) {}
  // Family angles at joint values q (θ_i = sign_i q_i + offset_i) and back.
  [[nodiscard]] bool toJoints(std::span<const double> theta, Solution& q) const;
  [[nodiscard]] Pose familyTip(std::span<const double> q) const;
  void addIfNew(const Solution& q, const Pose& tip, Solutions& out) const;

  const KinematicChain* chain_;
  Family family_;
  SixAxisArm six_;
  FiveAxisArm five_;
  Pose base_ = Pose::Identity();  // family base frame in the chain root frame
  Pose tool_ = Pose::Identity();  // chain tip in the family's flange frame
  std::array<double, 6> sign_{1, 1, 1, 1, 1, 1};
  std::array<double, 6> offset_{};
};

}  // namespace kaboum::kinematics
