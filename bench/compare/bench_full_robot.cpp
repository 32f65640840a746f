#include "bench_full_robot.hpp"

#include <fcl/broadphase/broadphase_dynamic_AABB_tree.h>
#include <fcl/broadphase/default_broadphase_callbacks.h>
#include <fcl/geometry/bvh/BVH_model.h>
#include <fcl/geometry/shape/convex.h>
#include <fcl/math/bv/OBBRSS.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <iomanip>
#include <iostream>
#include <memory>
#include <random>

#include "bench_statistics.hpp"
#include "fcl_shapes.hpp"
#include "kaboum/collision/robot_collision.hpp"
#include "kaboum/core/error.hpp"
#include "kaboum/geometry/convex_hull.hpp"
#include "kaboum/io/mesh_io.hpp"
#include "kaboum/io/urdf_loader.hpp"
#include "kaboum/kinematics/random_configuration.hpp"
#include "kaboum/testing/robot_collision_models.hpp"
#include "kaboum/testing/scene_generator.hpp"
#include "pair_decisions.hpp"

namespace kaboum::cli {

using namespace kaboum::geometry;
using namespace kaboum::kinematics;
using namespace kaboum::io;
using namespace kaboum::collision;
using namespace kaboum::testing;

namespace {

using Clock = std::chrono::steady_clock;

nlohmann::json stats(std::vector<double> ns) {
  std::sort(ns.begin(), ns.end());
  double sum = 0;
  for (double t : ns) sum += t;
  const auto at = [&](double fraction) {
    return ns[std::min(ns.size() - 1,
                       static_cast<std::size_t>(fraction * static_cast<double>(ns.size())))];
  };
  return {{"min", ns.front()},
          {"mean", sum / static_cast<double>(ns.size())},
          {"median", at(0.5)},
          {"p99", at(0.99)},
          {"max", ns.back()}};
}

std::shared_ptr<fcl::BVHModel<fcl::OBBRSSd>> fclMesh(const TriangleMesh& mesh) {
  auto model = std::make_shared<fcl::BVHModel<fcl::OBBRSSd>>();
  std::vector<fcl::Vector3d> points(mesh.vertices.begin(), mesh.vertices.end());
  std::vector<fcl::Triangle> triangles;
  for (const Triangle& t : mesh.triangles) triangles.emplace_back(t[0], t[1], t[2]);
  model->beginModel();
  model->addSubModel(points, triangles);
  model->endModel();
  return model;
}

// The scene's obstacles in an FCL DynamicAABBTree manager, as convexes or as hull meshes.
struct FclObstacles {
  std::vector<std::unique_ptr<fcl::CollisionObjectd>> objects;
  fcl::DynamicAABBTreeCollisionManagerd manager;

  FclObstacles(const CollisionScene& scene, bool asMeshes) {
    for (std::size_t o = 0; o < scene.size(); ++o) {
      for (std::size_t p = 0; p < scene.body(o).pieceCount(); ++p) {
        const auto& vertices = scene.body(o).piece(p).vertices();
        std::shared_ptr<fcl::CollisionGeometryd> geometry;
        if (asMeshes) {
          geometry = fclMesh(convexHull(vertices).mesh);
        } else {
          geometry = fclConvex(vertices);
        }
        objects.push_back(std::make_unique<fcl::CollisionObjectd>(geometry, scene.pose(o, {})));
        manager.registerObject(objects.back().get());
      }
    }
    manager.setup();
  }
};

// A robot as FCL objects: one per convex piece, or one per original link mesh.
struct FclRobot {
  struct Item {
    std::unique_ptr<fcl::CollisionObjectd> object;
    int link;
  };
  std::vector<Item> items;

  static FclRobot pieces(const RobotCollisionModel& robot) {
    FclRobot result;
    for (std::size_t i = 0; i < robot.partCount(); ++i) {
      const auto& body = *robot.part(i).body;
      for (std::size_t p = 0; p < body.pieceCount(); ++p) {
        result.items.push_back({std::make_unique<fcl::CollisionObjectd>(
                                    fclConvex(body.piece(p).vertices()), Pose::Identity()),
                                robot.part(i).link});
      }
    }
    return result;
  }

  static FclRobot originalMeshes(const RobotModel& model) {
    FclRobot result;
    for (std::size_t l = 0; l < model.links().size(); ++l) {
      for (const CollisionShape& shape : model.links()[l].collisions) {
        if (shape.kind != CollisionShape::Kind::Mesh) {
          throw InputError(model.name() + ": original-mesh benchmark needs mesh collision shapes");
        }
        TriangleMesh mesh = readMesh(shape.meshPath);
        for (Vec3& v : mesh.vertices) v = shape.origin * v.cwiseProduct(shape.size);
        result.items.push_back(
            {std::make_unique<fcl::CollisionObjectd>(fclMesh(mesh), Pose::Identity()),
             static_cast<int>(l)});
      }
    }
    return result;
  }

  bool collides(std::span<const Pose> linkPoses, fcl::DynamicAABBTreeCollisionManagerd& scene) {
    fcl::DefaultCollisionData<double> data;
    for (Item& item : items) {
      item.object->setTransform(linkPoses[static_cast<std::size_t>(item.link)]);
      item.object->computeAABB();
      scene.collide(item.object.get(), &data, fcl::DefaultCollisionFunction<double>);
      if (data.result.isCollision()) return true;
    }
    return false;
  }
};

// Per-query medians, in ns, of `checks` (each a callable check(i) -> bool) over `runs` rounds; a
// round makes one timed pass of every check over all queries in turn, so that a drift of the
// machine's speed reaches every check alike, each after an untimed pass of the same check (else
// its first queries ran with the caches of the check before it: cold outliers in every round).
// `answers[k]` gets check k's results.
template <class... Checks>
std::array<std::vector<double>, sizeof...(Checks)> medianTimes(
    std::size_t count, int runs, std::array<std::vector<char>, sizeof...(Checks)>& answers,
    Checks&&... checks) {
  constexpr std::size_t kChecks = sizeof...(Checks);
  std::array<std::vector<std::vector<double>>, kChecks> times;
  for (std::size_t k = 0; k < kChecks; ++k) {
    times[k].resize(count);
    answers[k].assign(count, 0);
  }
  const auto pass = [&](std::size_t k, auto& check) {
    for (std::size_t i = 0; i < count; ++i) answers[k][i] = check(i);
    for (std::size_t i = 0; i < count; ++i) {
      const auto start = Clock::now();
      answers[k][i] = check(i);
      times[k][i].push_back(std::chrono::duration<double, std::nano>(Clock::now() - start).count());
    }
  };
  for (int run = 0; run < runs; ++run) {
    std::size_t k = 0;
    (pass(k++, checks), ...);
  }
  std::array<std::vector<double>, kChecks> medians;
  for (std::size_t k = 0; k < kChecks; ++k) {
    for (const auto& t : times[k]) medians[k].push_back(median(t));
  }
  return medians;
}

// How kaboum's narrow phase decides the robot-piece / obstacle-piece pairs whose world boxes
// overlap, over all `poses` (every such pair, without the early exit of a real check).
nlohmann::json narrowPhaseDecisions(const RobotCollisionModel& robot, const CollisionScene& scene,
                                    const std::vector<std::vector<Pose>>& poses) {
  long boxesOverlap = 0;
  PairDecisionCounts counts;
  std::vector<std::vector<collision::Aabb>> obstacleBoxes(scene.size());
  for (std::size_t o = 0; o < scene.size(); ++o) {
    for (std::size_t q = 0; q < scene.body(o).pieceCount(); ++q) {
      obstacleBoxes[o].push_back(
          collision::transformedAabb(scene.body(o).pieceBounds(q).box, scene.pose(o, {})));
    }
  }
  for (const auto& linkPoses : poses) {
    for (std::size_t i = 0; i < robot.partCount(); ++i) {
      const Pose partPose = robot.partPose(i, linkPoses);
      const collision::CollisionBody& body = *robot.part(i).body;
      for (std::size_t p = 0; p < body.pieceCount(); ++p) {
        const collision::Aabb box = collision::transformedAabb(body.pieceBounds(p).box, partPose);
        for (std::size_t o = 0; o < scene.size(); ++o) {
          for (std::size_t q = 0; q < scene.body(o).pieceCount(); ++q) {
            if (!obstacleBoxes[o][q].overlaps(box)) continue;
            ++boxesOverlap;
            const collision::TransformedSupport obstacle(
                scene.body(o).piece(q), collision::inFrameOf(partPose, scene.pose(o, {})));
            counts.add(body.piece(p), obstacle);
          }
        }
      }
    }
  }
  nlohmann::json decided = counts.toJson();
  decided["boxes_overlap"] = boxesOverlap;
  return decided;
}

// One way of modelling the robot: kaboum on its convex pieces vs FCL on the same pieces.
nlohmann::json sideBySide(const RobotCollisionModel& robot, const CollisionScene& scene,
                          const std::vector<std::vector<Pose>>& poses, int runs) {
  FclObstacles fclScene(scene, false);
  FclRobot fclPieces = FclRobot::pieces(robot);
  std::size_t pieceCount = 0, vertexCount = 0;
  for (std::size_t i = 0; i < robot.partCount(); ++i) {
    const auto& body = *robot.part(i).body;
    pieceCount += body.pieceCount();
    for (std::size_t p = 0; p < body.pieceCount(); ++p) vertexCount += body.piece(p).vertexCount();
  }
  std::array<std::vector<char>, 2> answers;
  const auto [kaboumNs, fclNs] = medianTimes(
      poses.size(), runs, answers,
      [&](std::size_t i) {
        return robot.firstSceneCollision(poses[i], {}, scene, {}, 0.0).has_value();
      },
      [&](std::size_t i) { return fclPieces.collides(poses[i], fclScene.manager); });
  const std::vector<char>& ours = answers[0];
  const std::vector<char>& theirs = answers[1];
  long collisions = 0, disagreements = 0;
  for (std::size_t i = 0; i < poses.size(); ++i) {
    collisions += ours[i];
    disagreements += ours[i] != theirs[i];
  }
  nlohmann::json figures = {
      {"pieces", pieceCount},
      {"vertices", vertexCount},
      {"collision_fraction", static_cast<double>(collisions) / static_cast<double>(poses.size())},
      {"disagreements", disagreements},
      {"kaboum_ns", stats(kaboumNs)},
      {"fcl_dynamic_aabb_tree_ns", stats(fclNs)},
      {"narrow_phase_decided_by", narrowPhaseDecisions(robot, scene, poses)}};
  figures["fcl_over_kaboum_mean"] = figures["fcl_dynamic_aabb_tree_ns"]["mean"].get<double>() /
                                    figures["kaboum_ns"]["mean"].get<double>();
  figures["fcl_over_kaboum_median"] = figures["fcl_dynamic_aabb_tree_ns"]["median"].get<double>() /
                                      figures["kaboum_ns"]["median"].get<double>();
  return figures;
}

// Whether a link moves with some joint (else it is part of the fixed base).
bool linkMoves(const RobotModel& model, int link) {
  for (int joint = model.links()[static_cast<std::size_t>(link)].parentJoint; joint >= 0;
       joint = model
                   .links()[static_cast<std::size_t>(
                       model.joints()[static_cast<std::size_t>(joint)].parentLink)]
                   .parentJoint) {
    if (model.joints()[static_cast<std::size_t>(joint)].movable()) return true;
  }
  return false;
}

// `options.obstacles` random obstacles in `region`, skipping those that touch the fixed base
// (they would make every configuration collide).
CollisionScene obstaclesAwayFromTheBase(const RobotCollisionModel& robot,
                                        const collision::Aabb& region,
                                        const FullRobotBenchOptions& options) {
  std::vector<Pose> home(robot.model().links().size());
  robot.model().linkPoses(std::vector<double>(static_cast<std::size_t>(robot.model().dof()), 0.0),
                          home);
  const CollisionScene candidates =
      testing::randomObstacleScene(region, 4 * options.obstacles, 12, 0.04, options.seed);
  CollisionScene scene;
  for (std::size_t o = 0;
       o < candidates.size() && static_cast<int>(scene.size()) < options.obstacles; ++o) {
    bool touchesBase = false;
    for (std::size_t i = 0; i < robot.partCount(); ++i) {
      touchesBase |= !linkMoves(robot.model(), robot.part(i).link) &&
                     collision::bodiesCollide(*robot.part(i).body, robot.partPose(i, home),
                                              candidates.body(o), candidates.pose(o, {}), 0.0);
    }
    if (!touchesBase) {
      scene.add(candidates.sharedBody(o), candidates.pose(o, {}), candidates.name(o));
    }
  }
  return scene;
}

}  // namespace

nlohmann::json runFullRobotBench(const FullRobotBenchOptions& options) {
  if (options.obstacles <= 0 || options.queries <= 0 || options.motions <= 0 ||
      options.motionSteps <= 0 || options.runs <= 0 || options.decomposePercent <= 0) {
    throw InputError(
        "full-robot bench: obstacles, queries, motions, steps, runs and epsilon must be positive");
  }
  const auto progress = [&](const std::string& message) {
    if (!options.quiet) std::cerr << "robot: " << message << "\n";
  };
  const RobotModel model = loadUrdf(options.urdf);
  progress("convex hulls and bounding convex decomposition of the links...");
  const RobotCollisionModel hulls = testing::robotCollisionModel(model);
  collision::LinkPieceOptions decomposition;
  decomposition.decompose = true;
  decomposition.decomposition.epsilonPercent = options.decomposePercent;
  const auto decomposeStart = Clock::now();
  const RobotCollisionModel bounded = testing::robotCollisionModel(model, decomposition);
  const double decomposeSeconds =
      std::chrono::duration<double>(Clock::now() - decomposeStart).count();

  // Obstacles fill the box swept by the link origins over random configurations.
  std::mt19937_64 rng(options.seed);
  std::vector<Pose> poses(model.links().size());
  collision::Aabb region{Vec3::Constant(1e300), Vec3::Constant(-1e300)};
  for (int i = 0; i < 200; ++i) {
    model.linkPoses(randomConfiguration(model, rng), poses);
    for (const Pose& pose : poses) {
      region = region.merged({pose.translation(), pose.translation()});
    }
  }
  const CollisionScene scene = obstaclesAwayFromTheBase(hulls, region, options);

  std::vector<std::vector<Pose>> queries(static_cast<std::size_t>(options.queries), poses);
  for (auto& query : queries) model.linkPoses(randomConfiguration(model, rng), query);
  progress("side by side on " + std::to_string(options.queries) + " random configurations...");
  nlohmann::json figures = {{"robot", model.name()},
                            {"obstacles", options.obstacles},
                            {"queries", options.queries},
                            {"runs", options.runs},
                            {"decomposition_seconds", decomposeSeconds},
                            {"decomposition_epsilon_percent", options.decomposePercent}};
  figures["bounding_convex_sets"] = sideBySide(bounded, scene, queries, options.runs);
  figures["convex_hulls"] = sideBySide(hulls, scene, queries, options.runs);

  // Figure 4.9: per-check times along random straight motions.
  progress("Figure 4.9 distributions along " + std::to_string(options.motions) + " motions...");
  std::vector<std::vector<Pose>> along;
  std::vector<double> q(static_cast<std::size_t>(model.dof()));
  for (int m = 0; m < options.motions; ++m) {
    const auto qa = randomConfiguration(model, rng), qb = randomConfiguration(model, rng);
    for (int s = 0; s <= options.motionSteps; ++s) {
      for (std::size_t v = 0; v < q.size(); ++v) {
        q[v] = qa[v] + s * (qb[v] - qa[v]) / options.motionSteps;
      }
      model.linkPoses(q, poses);
      along.push_back(poses);
    }
  }
  FclObstacles fclMeshScene(scene, true);
  FclRobot fclOriginal = FclRobot::originalMeshes(model);
  std::array<std::vector<char>, 3> answers;
  const auto check = [&](const RobotCollisionModel& robot) {
    return [&](std::size_t i) {
      return robot.firstSceneCollision(along[i], {}, scene, {}, 0.0).has_value();
    };
  };
  const auto [originalNs, hullNs, boundedNs] = medianTimes(
      along.size(), options.runs, answers,
      [&](std::size_t i) { return fclOriginal.collides(along[i], fclMeshScene.manager); },
      check(hulls), check(bounded));
  figures["motion_checks"] = along.size();
  figures["figure_4_9_ns"] = {{"original_meshes_fcl", stats(originalNs)},
                              {"convex_hulls_kaboum", stats(hullNs)},
                              {"bounding_convex_sets_kaboum", stats(boundedNs)}};
  return figures;
}

void printFullRobotBench(const nlohmann::json& figures, std::ostream& out) {
  const auto header = [&](const std::string& title) {
    out << std::left << std::setw(36) << title << std::right;
    for (const char* key : {"min", "mean", "median", "p99", "max"}) out << std::setw(9) << key;
    out << "\n";
  };
  const auto row = [&](const std::string& name, const nlohmann::json& s) {
    out << std::left << std::setw(36) << name << std::right << std::fixed << std::setprecision(0);
    for (const char* key : {"min", "mean", "median", "p99", "max"}) {
      out << std::setw(9) << s[key].get<double>();
    }
    out << "\n";
  };
  out << "full robot " << figures["robot"].get<std::string>() << " vs "
      << figures["obstacles"].get<int>() << " convex obstacles, " << figures["queries"].get<int>()
      << " random configurations, median of " << figures["runs"].get<int>()
      << " runs per query (ns per check)\n";
  for (const char* variant : {"bounding_convex_sets", "convex_hulls"}) {
    const auto& v = figures[variant];
    out << std::fixed << std::setprecision(1) << variant << ": " << v["pieces"].get<int>()
        << " pieces, " << v["vertices"].get<int>() << " vertices, "
        << 100 * v["collision_fraction"].get<double>() << "% colliding, "
        << v["disagreements"].get<int>() << " disagreements with FCL\n";
    header("");
    row("  kaboum", v["kaboum_ns"]);
    row("  FCL DynamicAABBTree (libccd)", v["fcl_dynamic_aabb_tree_ns"]);
    out << std::setprecision(1) << "  FCL / kaboum: mean "
        << v["fcl_over_kaboum_mean"].get<double>() << "x, median "
        << v["fcl_over_kaboum_median"].get<double>() << "x\n";
    const auto& decided = v["narrow_phase_decided_by"];
    out << "  kaboum narrow phase on " << decided["boxes_overlap"].get<long>()
        << " box-overlapping piece pairs: bounding spheres apart "
        << decided["bounding_spheres_apart"].get<long>() << ", inner balls overlapping "
        << decided["inner_balls_overlap"].get<long>() << ", fan test " << decided["fan"].get<long>()
        << ", portal test " << decided["portal"].get<long>() << ", GJK "
        << decided["gjk"].get<long>() << "\n";
  }
  out << "Figure 4.9, " << figures["motion_checks"].get<int>() << " checks along random motions:\n";
  header("");
  row("  original meshes (FCL OBBRSS)", figures["figure_4_9_ns"]["original_meshes_fcl"]);
  row("  convex hulls (kaboum)", figures["figure_4_9_ns"]["convex_hulls_kaboum"]);
  row("  bounding convex sets (kaboum)", figures["figure_4_9_ns"]["bounding_convex_sets_kaboum"]);
}

}  // namespace kaboum::cli
