// `kaboum-compare verify-collision`: differential check of the bounded collision predicate
// (Definition 1 (1)) against FCL on the ORIGINAL triangle meshes, over random relative poses of
// real meshes.
#include <fcl/geometry/bvh/BVH_model.h>
#include <fcl/math/bv/OBBRSS.h>
#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/distance.h>

#include <Eigen/Geometry>
#include <chrono>
#include <filesystem>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <numbers>
#include <random>

#include "kaboum/collision/body.hpp"
#include "kaboum/collision/robot_collision.hpp"
#include "kaboum/core/error.hpp"
#include "kaboum/geometry/mesh_analysis.hpp"
#include "kaboum/geometry/triangle_bvh.hpp"
#include "kaboum/io/mesh_io.hpp"
#include "kaboum/kinematics/random_configuration.hpp"
#include "kaboum/testing/data_paths.hpp"
#include "mesh_cli.hpp"
#include "verb.hpp"

namespace kaboum::cli {

using namespace kaboum::geometry;
using namespace kaboum::kinematics;
using namespace kaboum::io;
using namespace kaboum::collision;
using namespace kaboum::testing;

namespace {

struct VerifyOptions {
  std::vector<std::string> meshes;
  long samples = 100000;
  std::uint64_t seed = 1;
  double reachScale = 1.0;
  std::string decompose;  // empty: one convex hull per mesh
  bool json = false;
};

// The KR5 and WAM link meshes of Debian's dart-doc package.
std::vector<std::string> defaultMeshes() {
  std::vector<std::string> paths;
  for (const char* name : {"base_link", "shoulder", "bicep", "elbow", "forearm", "wrist", "palm"}) {
    paths.push_back((testing::kr5MeshDir() / (std::string(name) + ".STL")).string());
  }
  for (int i = 1; i <= 7; ++i) {
    paths.push_back(
        (testing::dartUrdfDir() / "wam/meshes/wam" / ("wam" + std::to_string(i) + ".STL"))
            .string());
  }
  return paths;
}

struct Subject {
  std::string path;
  TriangleMesh mesh;
  std::unique_ptr<CollisionBody> body;
  std::shared_ptr<fcl::BVHModel<fcl::OBBRSSd>> fclModel;
  std::unique_ptr<TriangleBvh> exact;  // for solid containment of false alarms
  double epsilon = 0;                  // decomposition ε; 0 for a convex hull
};

Subject loadSubject(const std::string& path, const std::string& decompose) {
  Subject s{path, readMesh(path), nullptr, nullptr, nullptr, 0.0};
  collision::LinkPieceOptions pieceOptions;
  if (!decompose.empty()) {
    pieceOptions.decompose = true;
    s.epsilon = parseEpsilon(decompose, boundingBoxDiagonal(s.mesh));
    pieceOptions.decomposition.epsilon = s.epsilon;
  }
  const auto pieces = collision::boundingConvexPieces(s.mesh, path, pieceOptions);
  s.body = std::make_unique<CollisionBody>(pieces, path);
  s.fclModel = std::make_shared<fcl::BVHModel<fcl::OBBRSSd>>();
  std::vector<fcl::Vector3d> points(s.mesh.vertices.begin(), s.mesh.vertices.end());
  std::vector<fcl::Triangle> triangles;
  for (const Triangle& t : s.mesh.triangles) triangles.emplace_back(t[0], t[1], t[2]);
  s.fclModel->beginModel();
  s.fclModel->addSubModel(points, triangles);
  s.fclModel->endModel();
  s.exact = std::make_unique<TriangleBvh>(s.mesh);
  return s;
}

// Uniform rotation (Shoemake) from three uniform numbers: deterministic for a given seed.
Eigen::Quaterniond randomRotation(std::mt19937_64& rng) {
  const double u1 = uniformUnit(rng), u2 = uniformUnit(rng), u3 = uniformUnit(rng);
  const double a = std::sqrt(1 - u1), b = std::sqrt(u1), tau = 2 * std::numbers::pi;
  return {b * std::cos(tau * u3), a * std::sin(tau * u2), a * std::cos(tau * u2),
          b * std::sin(tau * u3)};
}

Vec3 randomDirection(std::mt19937_64& rng) {
  const double z = 2 * uniformUnit(rng) - 1, phi = 2 * std::numbers::pi * uniformUnit(rng);
  const double r = std::sqrt(std::max(0.0, 1 - z * z));
  return {r * std::cos(phi), r * std::sin(phi), z};
}

int runVerify(const VerifyOptions& options) {
  if (options.samples <= 0) throw InputError("--samples must be positive");
  if (options.reachScale <= 0) throw InputError("--reach-scale must be positive");
  const auto paths = options.meshes.empty() ? defaultMeshes() : options.meshes;
  std::vector<Subject> subjects;
  std::size_t pieces = 0;
  for (const auto& path : paths) {
    subjects.push_back(loadSubject(path, options.decompose));
    pieces += subjects.back().body->pieceCount();
  }

  std::mt19937_64 rng(options.seed);
  long fclCollisions = 0, kaboumCollisions = 0, missed = 0, falseAlarms = 0, solidContacts = 0;
  double worstFalseAlarm = 0, worstEpsilonRatio = 0;
  std::string worstPair;
  double kaboumSeconds = 0, fclSeconds = 0;
  using Clock = std::chrono::steady_clock;
  for (long i = 0; i < options.samples; ++i) {
    const Subject& a = subjects[rng() % subjects.size()];
    const Subject& b = subjects[rng() % subjects.size()];
    const double reach = options.reachScale * (a.body->bounds().radius + b.body->bounds().radius);
    // Pose of b relative to a: random rotation, sphere centres a random distance apart.
    Pose pose(randomRotation(rng));
    pose.translation() = a.body->bounds().centre - pose.linear() * b.body->bounds().centre +
                         uniformUnit(rng) * reach * randomDirection(rng);

    const auto t0 = Clock::now();
    const bool ours = collision::bodiesCollide(*a.body, Pose::Identity(), *b.body, pose, 0.0);
    const auto t1 = Clock::now();
    fcl::CollisionObjectd objectA(a.fclModel, fcl::Transform3d::Identity());
    fcl::CollisionObjectd objectB(b.fclModel, pose);
    fcl::CollisionRequestd request;
    fcl::CollisionResultd result;
    fcl::collide(&objectA, &objectB, request, result);
    const auto t2 = Clock::now();
    kaboumSeconds += std::chrono::duration<double>(t1 - t0).count();
    fclSeconds += std::chrono::duration<double>(t2 - t1).count();
    const bool surfacesMeet = result.isCollision();
    fclCollisions += surfacesMeet;
    kaboumCollisions += ours;
    if (surfacesMeet && !ours) ++missed;
    if (!surfacesMeet && ours) {
      // One solid inside the other is a collision the surfaces do not show.
      if (a.exact->contains(pose * b.mesh.vertices[0]) ||
          b.exact->contains(pose.inverse() * a.mesh.vertices[0])) {
        ++solidContacts;
        continue;
      }
      ++falseAlarms;
      fcl::DistanceRequestd distanceRequest;
      fcl::DistanceResultd distanceResult;
      fcl::distance(&objectA, &objectB, distanceRequest, distanceResult);
      if (a.epsilon > 0) {
        worstEpsilonRatio =
            std::max(worstEpsilonRatio, distanceResult.min_distance / (a.epsilon + b.epsilon));
      }
      if (distanceResult.min_distance > worstFalseAlarm) {
        worstFalseAlarm = distanceResult.min_distance;
        worstPair = std::filesystem::path(a.path).filename().string() + " / " +
                    std::filesystem::path(b.path).filename().string();
      }
    }
  }
  const double n = static_cast<double>(options.samples);
  if (options.json) {
    nlohmann::json out = {{"samples", options.samples},
                          {"meshes", paths.size()},
                          {"pieces", pieces},
                          {"decompose", options.decompose.empty() ? "hull" : options.decompose},
                          {"seed", options.seed},
                          {"fcl_collisions", fclCollisions},
                          {"kaboum_collisions", kaboumCollisions},
                          {"missed", missed},
                          {"solid_contacts", solidContacts},
                          {"false_alarms", falseAlarms},
                          {"max_false_alarm_distance", worstFalseAlarm},
                          {"max_false_alarm_pair", worstPair},
                          {"max_false_alarm_over_epsilon_sum", worstEpsilonRatio},
                          {"kaboum_ns_per_query", 1e9 * kaboumSeconds / n},
                          {"fcl_ns_per_query", 1e9 * fclSeconds / n}};
    std::cout << out.dump(2) << "\n";
  } else {
    std::cout << "samples " << options.samples << " over " << paths.size() << " meshes, " << pieces
              << " convex pieces ("
              << (options.decompose.empty() ? "hulls" : "decomposition at " + options.decompose)
              << "), seed " << options.seed << "\n"
              << "FCL (original triangles) collisions " << fclCollisions << "\n"
              << "kaboum (bounding convex pieces) collisions " << kaboumCollisions << "\n"
              << "missed collisions " << missed << "\n"
              << "solid containments (surfaces apart, one inside the other) " << solidContacts
              << "\n"
              << "false alarms " << falseAlarms << ", largest true distance " << worstFalseAlarm
              << (worstPair.empty() ? "" : " (" + worstPair + ")") << "\n"
              << (options.decompose.empty()
                      ? ""
                      : "largest false-alarm distance / (epsilon_a + epsilon_b) " +
                            std::to_string(worstEpsilonRatio) + "\n")
              << "ns per query: kaboum " << 1e9 * kaboumSeconds / n << ", FCL mesh "
              << 1e9 * fclSeconds / n << "\n";
  }
  return missed == 0 ? 0 : 1;
}

VerbRunner setupVerify(CLI::App& command) {
  auto options = std::make_shared<VerifyOptions>();
  command.add_option("--mesh", options->meshes,
                     "Mesh files to pair up (default: the KR5 and WAM links of dart-doc)");
  command.add_option("--samples", options->samples, "Number of random relative poses")
      ->capture_default_str();
  command.add_option("--seed", options->seed, "Random seed")->capture_default_str();
  command
      .add_option("--reach-scale", options->reachScale,
                  "Centre distance up to this times the sum of the bounding radii")
      ->capture_default_str();
  command.add_option("--decompose", options->decompose,
                     "Bounding convex decomposition at this epsilon (a distance, or E% of each "
                     "mesh's diagonal) instead of one convex hull per mesh");
  command.add_flag("--json", options->json, "Print the counts as JSON");
  return [options] { return runVerify(*options); };
}

const VerbRegistration registration{
    "verify-collision",
    "Differential check against FCL on the original meshes: missed collisions (must be 0) and "
    "false alarms of the bounded collision predicate; exit code 1 on a miss",
    setupVerify};

}  // namespace
}  // namespace kaboum::cli
