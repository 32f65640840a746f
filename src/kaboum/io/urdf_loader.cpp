#include "kaboum/io/urdf_loader.hpp"

#include <console_bridge/console.h>
#include <urdf_model/model.h>
#include <urdf_parser/urdf_parser.h>
#include <urdf_world/types.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <mutex>
#include <numbers>
#include <sstream>

#include "kaboum/core/error.hpp"
#include "kaboum/io/mesh_io.hpp"

namespace kaboum::io {

using namespace kaboum::geometry;
using namespace kaboum::kinematics;

namespace {

namespace fs = std::filesystem;

// urdfdom reports problems through console_bridge; this collects its error messages for one parse
// (console_bridge's handler is global, hence the lock).
urdf::ModelInterfaceSharedPtr parseWithUrdfdom(const std::string& xml, std::string& errors) {
  struct MessageCollector : console_bridge::OutputHandler {
    std::string messages;
    void log(const std::string& text, console_bridge::LogLevel level, const char*, int) override {
      if (level >= console_bridge::CONSOLE_BRIDGE_LOG_ERROR) messages += text + "; ";
    }
  };
  static std::mutex mutex;
  const std::lock_guard lock(mutex);
  MessageCollector collector;
  console_bridge::useOutputHandler(&collector);
  urdf::ModelInterfaceSharedPtr model;
  try {
    model = urdf::parseURDF(xml);
  } catch (const std::exception& e) {
    collector.messages += std::string(e.what()) + "; ";
  }
  console_bridge::restorePreviousOutputHandler();
  errors = collector.messages;
  return model;
}

Pose toPose(const urdf::Pose& pose) {
  double x = 0, y = 0, z = 0, w = 1;
  pose.rotation.getQuaternion(x, y, z, w);
  Pose result = Pose::Identity();
  result.linear() = Eigen::Quaterniond(w, x, y, z).normalized().toRotationMatrix();
  result.translation() = Eigen::Vector3d(pose.position.x, pose.position.y, pose.position.z);
  return result;
}

// Resolves a URDF mesh reference: relative paths and file:// against the URDF's folder;
// package://NAME/REST against that folder and its ancestors (as REST or NAME/REST).
std::string resolveMesh(const std::string& uri, const fs::path& baseDir, const std::string& file,
                        const std::string& linkName) {
  const auto fail = [&](const std::string& what) {
    throw InputError(locate(file, "link '" + linkName + "': mesh '" + uri + "' " + what));
  };
  std::vector<fs::path> candidates;
  const std::string package = "package://";
  const std::string fileScheme = "file://";
  if (uri.rfind(package, 0) == 0) {
    const std::string rest = uri.substr(package.size());
    const auto slash = rest.find('/');
    if (slash == std::string::npos) fail("names no file inside its package");
    const fs::path name = rest.substr(0, slash);
    const fs::path inside = rest.substr(slash + 1);
    for (fs::path dir = fs::absolute(baseDir);; dir = dir.parent_path()) {
      candidates.push_back(dir / inside);
      candidates.push_back(dir / name / inside);
      if (dir == dir.parent_path()) break;
    }
  } else if (uri.rfind(fileScheme, 0) == 0) {
    candidates.emplace_back(uri.substr(fileScheme.size()));
  } else if (uri.find("://") != std::string::npos) {
    fail("uses an unsupported URI scheme");
  } else {
    const fs::path path(uri);
    candidates.push_back(path.is_absolute() ? path : baseDir / path);
  }
  for (const auto& candidate : candidates) {
    std::error_code error;
    if (fs::is_regular_file(candidate, error)) return candidate.lexically_normal().string();
  }
  fail("not found");
  return {};
}

CollisionShape toShape(const urdf::Collision& collision, const fs::path& baseDir,
                       const std::string& file, const std::string& linkName) {
  CollisionShape shape;
  shape.origin = toPose(collision.origin);
  if (!collision.geometry) {
    throw InputError(locate(file, "link '" + linkName + "': collision without geometry"));
  }
  const urdf::Geometry& geometry = *collision.geometry;
  switch (geometry.type) {
    case urdf::Geometry::BOX: {
      const auto& box = static_cast<const urdf::Box&>(geometry);
      shape.kind = CollisionShape::Kind::Box;
      shape.size = {box.dim.x, box.dim.y, box.dim.z};
      break;
    }
    case urdf::Geometry::CYLINDER: {
      const auto& cylinder = static_cast<const urdf::Cylinder&>(geometry);
      shape.kind = CollisionShape::Kind::Cylinder;
      shape.radius = cylinder.radius;
      shape.length = cylinder.length;
      break;
    }
    case urdf::Geometry::SPHERE:
      shape.kind = CollisionShape::Kind::Sphere;
      shape.radius = static_cast<const urdf::Sphere&>(geometry).radius;
      break;
    case urdf::Geometry::MESH: {
      const auto& mesh = static_cast<const urdf::Mesh&>(geometry);
      shape.kind = CollisionShape::Kind::Mesh;
      shape.size = {mesh.scale.x, mesh.scale.y, mesh.scale.z};
      shape.meshPath = resolveMesh(mesh.filename, baseDir, file, linkName);
      break;
    }
  }
  return shape;
}

Eigen::Vector3d unitAxis(const urdf::Joint& joint, const std::string& file) {
  const Eigen::Vector3d axis(joint.axis.x, joint.axis.y, joint.axis.z);
  if (!(axis.norm() > 1e-9) || !axis.allFinite()) {
    throw InputError(locate(file, "joint '" + joint.name + "': axis must be a non-zero vector"));
  }
  return axis.normalized();
}

// Adds the joints a URDF joint stands for (three for planar) and any intermediate links.
void addJoints(const urdf::Joint& source, int parent, int child, const std::string& file,
               std::vector<Link>& links, std::vector<Joint>& joints) {
  Joint joint;
  joint.name = source.name;
  joint.parentLink = parent;
  joint.childLink = child;
  joint.origin = toPose(source.parent_to_joint_origin_transform);
  const auto requireLimits = [&] {
    if (!source.limits) {
      throw InputError(locate(file, "joint '" + source.name + "': <limit> is required"));
    }
    if (!(source.limits->lower <= source.limits->upper)) {
      throw InputError(locate(file, "joint '" + source.name + "': lower limit exceeds upper"));
    }
    joint.lower = source.limits->lower;
    joint.upper = source.limits->upper;
    joint.maxVelocity = source.limits->velocity;
  };
  switch (source.type) {
    case urdf::Joint::FIXED:
      joint.type = JointType::Fixed;
      break;
    case urdf::Joint::REVOLUTE:
      joint.type = JointType::Revolute;
      joint.axis = unitAxis(source, file);
      requireLimits();
      break;
    case urdf::Joint::CONTINUOUS:
      joint.type = JointType::Continuous;
      joint.axis = unitAxis(source, file);
      joint.lower = -std::numbers::pi;
      joint.upper = std::numbers::pi;
      if (source.limits) joint.maxVelocity = source.limits->velocity;
      break;
    case urdf::Joint::PRISMATIC:
      joint.type = JointType::Prismatic;
      joint.axis = unitAxis(source, file);
      requireLimits();
      break;
    case urdf::Joint::PLANAR: {
      // Mobile base: translate along two in-plane directions, then turn about the normal.
      const Eigen::Vector3d normal = unitAxis(source, file);
      const Eigen::Vector3d u = normal.unitOrthogonal();
      const Eigen::Vector3d v = normal.cross(u);
      const double reach = source.limits && source.limits->upper > source.limits->lower
                               ? std::max(std::abs(source.limits->lower), source.limits->upper)
                               : 10.0;
      const int xLink = static_cast<int>(links.size());
      links.push_back({source.name + "/x", -1, {}});
      const int yLink = static_cast<int>(links.size());
      links.push_back({source.name + "/y", -1, {}});
      Joint x = joint;
      x.name = source.name + "/x";
      x.type = JointType::Prismatic;
      x.axis = u;
      x.lower = -reach;
      x.upper = reach;
      x.childLink = xLink;
      Joint y = x;
      y.name = source.name + "/y";
      y.origin = Pose::Identity();
      y.axis = v;
      y.parentLink = xLink;
      y.childLink = yLink;
      Joint theta = y;
      theta.name = source.name + "/theta";
      theta.type = JointType::Continuous;
      theta.axis = normal;
      theta.lower = -std::numbers::pi;
      theta.upper = std::numbers::pi;
      theta.parentLink = yLink;
      theta.childLink = child;
      joints.push_back(x);
      joints.push_back(y);
      joints.push_back(theta);
      return;
    }
    case urdf::Joint::FLOATING:
      throw InputError(locate(file, "joint '" + source.name +
                                        "': floating joints are not supported (use planar "
                                        "for a mobile base or a separate robot base pose)"));
    default:
      throw InputError(locate(file, "joint '" + source.name + "': unknown joint type"));
  }
  joints.push_back(joint);
}

}  // namespace

RobotModel parseUrdf(const std::string& xml, const std::string& sourceName,
                     const std::string& baseDir) {
  std::string errors;
  const urdf::ModelInterfaceSharedPtr model = parseWithUrdfdom(xml, errors);
  if (!model) {
    if (errors.size() >= 2) errors.resize(errors.size() - 2);
    throw InputError(
        locate(sourceName, "invalid URDF: " + (errors.empty() ? "parse failed" : errors)));
  }
  std::vector<Link> links;
  std::map<std::string, int> linkIndex;
  for (const auto& [name, link] : model->links_) {
    Link converted;
    converted.name = name;
    const auto& collisions = link->collision_array;
    for (const auto& collision : collisions) {
      if (collision) converted.collisions.push_back(toShape(*collision, baseDir, sourceName, name));
    }
    if (collisions.empty() && link->collision) {
      converted.collisions.push_back(toShape(*link->collision, baseDir, sourceName, name));
    }
    linkIndex[name] = static_cast<int>(links.size());
    links.push_back(std::move(converted));
  }
  std::vector<Joint> joints;
  std::map<std::string, std::string> parentJointOf;
  for (const auto& [name, joint] : model->joints_) {
    const auto parent = linkIndex.find(joint->parent_link_name);
    const auto child = linkIndex.find(joint->child_link_name);
    if (parent == linkIndex.end() || child == linkIndex.end()) {
      throw InputError(locate(sourceName, "joint '" + name + "': parent or child link missing"));
    }
    const auto [previous, inserted] = parentJointOf.emplace(joint->child_link_name, name);
    if (!inserted) {
      throw InputError(locate(sourceName, "joints '" + previous->second + "' and '" + name +
                                              "' both move link '" + joint->child_link_name +
                                              "' (kinematic loop)"));
    }
    addJoints(*joint, parent->second, child->second, sourceName, links, joints);
  }
  try {
    return RobotModel(model->getName(), std::move(links), std::move(joints));
  } catch (const std::invalid_argument& e) {
    throw InputError(locate(sourceName, e.what()));
  }
}

RobotModel loadUrdf(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(locate(path, "cannot open file"));
  std::ostringstream text;
  text << in.rdbuf();
  return parseUrdf(text.str(), path, fs::path(path).parent_path().string());
}

std::map<std::string, TriangleMesh> readCollisionMeshes(const RobotModel& model) {
  std::map<std::string, TriangleMesh> meshes;
  for (const Link& link : model.links()) {
    for (const CollisionShape& shape : link.collisions) {
      if (shape.kind == CollisionShape::Kind::Mesh && !meshes.contains(shape.meshPath)) {
        meshes.emplace(shape.meshPath, readMesh(shape.meshPath));
      }
    }
  }
  return meshes;
}

}  // namespace kaboum::io
