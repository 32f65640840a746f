// `kaboum fk`: forward kinematics of a URDF chain — the tool pose for given joint values.
#include <Eigen/Geometry>
#include <iostream>

#include "kaboum/core/error.hpp"
#include "kaboum/io/json_kinematics.hpp"
#include "kaboum/io/urdf_loader.hpp"
#include "kaboum/kinematics/kinematic_chain.hpp"
#include "verb.hpp"

namespace kaboum::cli {

using namespace kaboum::kinematics;
using namespace kaboum::io;

namespace {

struct FkOptions {
  std::string urdf;
  std::string tip;
  std::string base;
  std::vector<double> q;
  bool json = false;
};

int runFk(const FkOptions& options) {
  const RobotModel model = loadUrdf(options.urdf);
  const KinematicChain chain(model, options.tip, options.base);
  if (static_cast<int>(options.q.size()) != chain.dof()) {
    throw InputError(locate(options.urdf, "chain to '" + chain.tipName() + "' has " +
                                              std::to_string(chain.dof()) + " joints, got " +
                                              std::to_string(options.q.size()) + " values"));
  }
  const Pose pose = chain.toolPose(options.q);
  if (options.json) {
    nlohmann::json out = toJson(pose);
    out["tip"] = chain.tipName();
    std::cout << out.dump(2) << "\n";
  } else {
    const Eigen::Vector3d p = pose.translation();
    const Eigen::Quaterniond r(pose.linear());
    std::cout.precision(9);
    std::cout << "tip " << chain.tipName() << "\nposition " << p.x() << " " << p.y() << " " << p.z()
              << "\nquaternion " << r.w() << " " << r.x() << " " << r.y() << " " << r.z() << "\n";
  }
  return 0;
}

VerbRunner setupFk(CLI::App& command) {
  auto options = std::make_shared<FkOptions>();
  command.add_option("urdf", options->urdf, "Robot description (URDF)")->required();
  command.add_option("q", options->q, "Joint values of the chain, root to tip (rad, m)");
  command.add_option("--tip", options->tip, "Tip link of the chain (default: end of the trunk)");
  command.add_option("--base", options->base,
                     "Base link of the chain; poses are in its frame (default: root)");
  command.add_flag("--json", options->json, "Print the pose as JSON");
  return [options] { return runFk(*options); };
}

const VerbRegistration registration{
    "fk", "Forward kinematics: tool pose (position, quaternion w x y z) of a URDF chain", setupFk};

}  // namespace
}  // namespace kaboum::cli
