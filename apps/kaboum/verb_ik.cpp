// `kaboum ik`: inverse kinematics of a URDF chain — closed form (thesis A.3) when the arm fits a
// five- or six-axis family, numeric otherwise. Unreachable is an answer: exit code 1.
#include <Eigen/Geometry>
#include <cmath>
#include <iostream>

#include "kaboum/core/error.hpp"
#include "kaboum/io/json_kinematics.hpp"
#include "kaboum/io/urdf_loader.hpp"
#include "kaboum/kinematics/arm_ik.hpp"
#include "kaboum/kinematics/numeric_ik.hpp"
#include "verb.hpp"

namespace kaboum::cli {

using namespace kaboum::kinematics;
using namespace kaboum::io;

namespace {

struct IkOptions {
  std::string urdf;
  std::string tip;
  std::string base;
  std::vector<double> pose;
  bool all = false;
  std::uint64_t seed = 1;
  bool json = false;
};

Pose targetPose(const IkOptions& options) {
  const auto& v = options.pose;
  const Eigen::Quaterniond rotation(v[3], v[4], v[5], v[6]);
  if (!std::isfinite(rotation.norm()) || std::abs(rotation.norm() - 1) > 1e-3) {
    throw InputError("--pose: quaternion (w x y z) must have unit length, got norm " +
                     std::to_string(rotation.norm()));
  }
  Pose target = Pose::Identity();
  target.linear() = rotation.normalized().toRotationMatrix();
  target.translation() = Eigen::Vector3d(v[0], v[1], v[2]);
  return target;
}

// Distinct solutions: all closed-form branches, or numeric solutions from several restarts.
std::vector<std::vector<double>> solve(const KinematicChain& chain, const Pose& target,
                                       const IkOptions& options, std::string& method) {
  std::vector<std::vector<double>> found;
  const auto n = static_cast<std::size_t>(chain.dof());
  if (const auto arm = ArmIk::fit(chain)) {
    method = arm->family() == ArmIk::Family::SixAxis ? "closed-form six-axis (A.3)"
                                                     : "closed-form five-axis (A.3)";
    ArmIk::Solutions solutions;
    arm->solve(target, solutions);
    for (int s = 0; s < solutions.count; ++s) {
      const auto& q = solutions.q[static_cast<std::size_t>(s)];
      found.emplace_back(q.begin(), q.begin() + static_cast<std::ptrdiff_t>(n));
    }
  } else {
    method = "numeric (damped least squares)";
    NumericIk ik(chain, {.seed = options.seed});
    std::vector<double> q(n);
    const int rounds = options.all ? 16 : 1;
    for (int round = 0; round < rounds && ik.solve(target, {}, q); ++round) {
      const bool known = std::any_of(found.begin(), found.end(), [&](const auto& other) {
        for (std::size_t i = 0; i < n; ++i) {
          if (std::abs(other[i] - q[i]) > 1e-3) return false;
        }
        return true;
      });
      if (!known) found.push_back(q);
    }
  }
  if (!options.all && found.size() > 1) found.resize(1);
  return found;
}

int runIk(const IkOptions& options) {
  const RobotModel model = loadUrdf(options.urdf);
  const KinematicChain chain(model, options.tip, options.base);
  const Pose target = targetPose(options);
  std::string method;
  const auto solutions = solve(chain, target, options, method);
  if (options.json) {
    nlohmann::json out = ikSolutionsJson(solutions);
    out.update({{"tip", chain.tipName()}, {"method", method}});
    std::cout << out.dump(2) << "\n";
  } else if (solutions.empty()) {
    std::cout << "unreachable\n";
  } else {
    std::cout.precision(9);
    for (const auto& q : solutions) {
      for (std::size_t i = 0; i < q.size(); ++i) std::cout << (i ? " " : "") << q[i];
      std::cout << "\n";
    }
  }
  return solutions.empty() ? 1 : 0;
}

VerbRunner setupIk(CLI::App& command) {
  auto options = std::make_shared<IkOptions>();
  command.add_option("urdf", options->urdf, "Robot description (URDF)")->required();
  command.add_option("--pose", options->pose, "Target tool pose: x y z qw qx qy qz")
      ->expected(7)
      ->required();
  command.add_option("--tip", options->tip, "Tip link of the chain (default: end of the trunk)");
  command.add_option("--base", options->base,
                     "Base link of the chain; poses are in its frame (default: root)");
  command.add_flag("--all", options->all, "Print all solutions (one per line)");
  command.add_option("--seed", options->seed, "Seed of the numeric solver's restarts");
  command.add_flag("--json", options->json, "Print the solutions as JSON");
  command.footer("Exit code 1 with `unreachable` when no solution exists within joint limits.");
  return [options] { return runIk(*options); };
}

const VerbRegistration registration{
    "ik", "Inverse kinematics of a URDF chain (closed form for 5/6-axis arms, else numeric)",
    setupIk};

}  // namespace
}  // namespace kaboum::cli
