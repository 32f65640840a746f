// `kaboum-compare collision`: side-by-side benchmarks against the reference libraries on identical
// queries. It runs its sections (the convex pair narrow phase, the full robot; see
// kCollisionSections) and prints ns per query, ratios and wrong answers vs an exact reference.
#include <BulletCollision/NarrowPhaseCollision/btGjkEpa2.h>
#include <BulletCollision/NarrowPhaseCollision/btGjkEpaPenetrationDepthSolver.h>
#include <BulletCollision/NarrowPhaseCollision/btGjkPairDetector.h>
#include <BulletCollision/NarrowPhaseCollision/btPointCollector.h>
#include <BulletCollision/NarrowPhaseCollision/btVoronoiSimplexSolver.h>
#include <btBulletCollisionCommon.h>
#include <ccd/ccd.h>
#include <fcl/geometry/shape/convex.h>
#include <fcl/narrowphase/detail/gjk_solver_indep.h>
#include <fcl/narrowphase/detail/gjk_solver_libccd.h>

#include <algorithm>
#include <ctime>
#include <functional>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>

#include "bench_full_robot.hpp"
#include "bench_statistics.hpp"
#include "fcl_shapes.hpp"
#include "kaboum/collision/convex_polytope.hpp"
#include "kaboum/collision/gjk.hpp"
#include "kaboum/core/error.hpp"
#include "kaboum/testing/minkowski_reference.hpp"
#include "kaboum/testing/polytope_pairs.hpp"
#include "pair_decisions.hpp"
#include "verb.hpp"

namespace kaboum::cli {

using namespace kaboum::geometry;
using namespace kaboum::collision;
using namespace kaboum::testing;

namespace {

struct CollisionBenchOptions {
  std::size_t pairs = 2000;
  std::vector<int> vertexCounts = {8, 16, 32, 64};
  int runs = 5;
  std::uint64_t seed = 1;
  std::vector<std::string> sections;
  bool json = false;
  bool quiet = false;
};

// One timed sweep of `query(i)` over every pair i, in CPU ns per query.
template <class Query>
double sweepNanoseconds(std::size_t count, Query& query) {
  volatile std::size_t sink = 0;
  const double start = threadNanoseconds();
  std::size_t hits = 0;
  for (std::size_t i = 0; i < count; ++i) hits += query(i) ? 1 : 0;
  const double stop = threadNanoseconds();
  sink = sink + hits;
  return (stop - start) / static_cast<double>(count);
}

// One library's answers on the workload: speed and wrong answers against the reference.
struct MethodReport {
  std::string name;
  std::vector<double> booleanRounds;   // ns per query in each round (timeInterleaved)
  std::vector<double> distanceRounds;  // empty when the library has no distance query
  int missedOverlaps = 0;              // "free" although the true distance is <= 0
  double deepestMissed = 0.0;          // largest penetration depth among them
  int falseAlarms = 0;                 // "colliding" although the true distance is > 1e-6
  int overestimates = 0;               // distance above the true distance by more than 1e-9
  double largestOverestimate = 0.0;
};

// A library checked against the reference, with its timed sweeps (each one pass over all pairs),
// run later round by round together with the other libraries' (timeInterleaved).
struct Method {
  MethodReport report;
  std::function<double()> booleanSweep;
  std::function<double()> distanceSweep;  // empty when the library has no distance query
};

// Correctness tolerances of the counts (units of the unit-size workload).
constexpr double kFalseAlarmDistance = 1e-6;
constexpr double kOverestimateTolerance = 1e-9;

template <class Intersects, class Distance>
Method measure(const std::string& name, const std::vector<double>& truth, Intersects intersects,
               Distance distance) {
  Method method;
  MethodReport& report = method.report;
  report.name = name;
  const std::size_t count = truth.size();
  for (std::size_t i = 0; i < count; ++i) {
    const bool hit = intersects(i);
    if (!hit && truth[i] <= 0.0) {
      ++report.missedOverlaps;
      report.deepestMissed = std::max(report.deepestMissed, -truth[i]);
    }
    if (hit && truth[i] > kFalseAlarmDistance) ++report.falseAlarms;
  }
  method.booleanSweep = [count, intersects]() mutable {
    return sweepNanoseconds(count, intersects);
  };
  if constexpr (!std::is_same_v<Distance, std::nullptr_t>) {
    for (std::size_t i = 0; i < count; ++i) {
      const double excess = distance(i) - std::max(truth[i], 0.0);
      if (excess > kOverestimateTolerance) {
        ++report.overestimates;
        report.largestOverestimate = std::max(report.largestOverestimate, excess);
      }
    }
    method.distanceSweep = [count, distance]() mutable {
      auto positive = [&](std::size_t i) { return distance(i) > 0.0; };
      return sweepNanoseconds(count, positive);
    };
  }
  return method;
}

// Times every method `runs` times, round by round (in each round a boolean sweep of every method,
// then a distance sweep of every method), so that a drift of the machine's speed reaches all
// libraries alike (ratios are then taken round by round: sameRoundRatio). Each timed sweep follows
// an untimed one of the same method, so that its shapes are in the caches as in a run of that
// method alone (a cold sweep after the other libraries' took kaboum about twice as long: memory
// latency, not the query).
std::vector<MethodReport> timeInterleaved(std::vector<Method>& methods, int runs) {
  std::vector<MethodReport> reports;
  for (const Method& method : methods) reports.push_back(method.report);
  for (int run = 0; run < runs; ++run) {
    for (std::size_t k = 0; k < methods.size(); ++k) {
      methods[k].booleanSweep();
      reports[k].booleanRounds.push_back(methods[k].booleanSweep());
    }
    for (std::size_t k = 0; k < methods.size(); ++k) {
      if (!methods[k].distanceSweep) continue;
      methods[k].distanceSweep();
      reports[k].distanceRounds.push_back(methods[k].distanceSweep());
    }
  }
  return reports;
}

// The ratio of two methods' times as the median of their same-round ratios.
double sameRoundRatio(const std::vector<double>& theirs, const std::vector<double>& ours) {
  std::vector<double> perRound;
  for (std::size_t run = 0; run < theirs.size(); ++run) perRound.push_back(theirs[run] / ours[run]);
  return median(perRound);
}

// libccd's view of a placed polytope: brute-force support over the local vertices.
struct CcdPolytope {
  const std::vector<Vec3>* local;
  Eigen::Matrix3d rotation;
  Vec3 translation;
  Vec3 center;
};

void ccdSupport(const void* object, const ccd_vec3_t* direction, ccd_vec3_t* out) {
  const auto& shape = *static_cast<const CcdPolytope*>(object);
  const Vec3 d =
      shape.rotation.transpose() * Vec3(direction->v[0], direction->v[1], direction->v[2]);
  const Vec3* best = &shape.local->front();
  double bestDot = d.dot(*best);
  for (const Vec3& p : *shape.local) {
    if (d.dot(p) > bestDot) {
      bestDot = d.dot(p);
      best = &p;
    }
  }
  const Vec3 world = shape.rotation * *best + shape.translation;
  ccdVec3Set(out, world.x(), world.y(), world.z());
}

void ccdCenter(const void* object, ccd_vec3_t* out) {
  const Vec3& c = static_cast<const CcdPolytope*>(object)->center;
  ccdVec3Set(out, c.x(), c.y(), c.z());
}

btTransform bulletTransform(const Eigen::Isometry3d& pose) {
  const Eigen::Matrix3d& r = pose.linear();
  const Vec3& t = pose.translation();
  return btTransform(
      btMatrix3x3(r(0, 0), r(0, 1), r(0, 2), r(1, 0), r(1, 1), r(1, 2), r(2, 0), r(2, 1), r(2, 2)),
      btVector3(t.x(), t.y(), t.z()));
}

// Every library's shapes for the same pairs, built once outside the timed loops.
struct PairShapes {
  std::vector<collision::ConvexPolytope> kaboumA, kaboumB;
  std::vector<std::shared_ptr<fcl::Convexd>> fclA, fclB;
  std::vector<std::unique_ptr<btConvexHullShape>> bulletA, bulletB;
  std::vector<btTransform> bulletPoseA, bulletPoseB;
  std::vector<CcdPolytope> ccdA, ccdB;
};

std::unique_ptr<btConvexHullShape> bulletHull(const std::vector<Vec3>& points) {
  auto shape = std::make_unique<btConvexHullShape>();
  for (const Vec3& p : points) shape->addPoint(btVector3(p.x(), p.y(), p.z()), false);
  shape->recalcLocalAabb();
  shape->setMargin(0.0);  // exact shapes, as for every other library
  return shape;
}

PairShapes buildShapes(const std::vector<PolytopePair>& pairs) {
  PairShapes shapes;
  for (const PolytopePair& pair : pairs) {
    shapes.kaboumA.emplace_back(pair.localA);
    shapes.kaboumB.emplace_back(pair.localB);
    shapes.fclA.push_back(fclConvex(pair.localA));
    shapes.fclB.push_back(fclConvex(pair.localB));
    shapes.bulletA.push_back(bulletHull(pair.localA));
    shapes.bulletB.push_back(bulletHull(pair.localB));
    shapes.bulletPoseA.push_back(bulletTransform(pair.poseA));
    shapes.bulletPoseB.push_back(bulletTransform(pair.poseB));
    shapes.ccdA.push_back({&pair.localA, pair.poseA.linear(), pair.poseA.translation(),
                           pair.poseA * shapes.kaboumA.back().center()});
    shapes.ccdB.push_back({&pair.localB, pair.poseB.linear(), pair.poseB.translation(),
                           pair.poseB * shapes.kaboumB.back().center()});
  }
  return shapes;
}

std::vector<MethodReport> measureAll(const std::vector<PolytopePair>& pairs,
                                     const std::vector<double>& truth, int runs) {
  using collision::TransformedSupport;
  PairShapes s = buildShapes(pairs);
  std::vector<Method> methods;

  methods.push_back(measure(
      "kaboum", truth,
      [&](std::size_t i) {
        return collision::intersects(TransformedSupport(s.kaboumA[i], pairs[i].poseA),
                                     TransformedSupport(s.kaboumB[i], pairs[i].poseB));
      },
      [&](std::size_t i) {
        return collision::distance(TransformedSupport(s.kaboumA[i], pairs[i].poseA),
                                   TransformedSupport(s.kaboumB[i], pairs[i].poseB))
            .distance;
      }));

  const fcl::detail::GJKSolver_libccd<double> fclCcd;
  methods.push_back(measure(
      "fcl_libccd", truth,
      [&](std::size_t i) {
        return fclCcd.shapeIntersect(*s.fclA[i], pairs[i].poseA, *s.fclB[i], pairs[i].poseB,
                                     nullptr);
      },
      [&](std::size_t i) {
        double d = 0.0;
        fclCcd.shapeDistance(*s.fclA[i], pairs[i].poseA, *s.fclB[i], pairs[i].poseB, &d);
        return std::max(d, 0.0);
      }));

  const fcl::detail::GJKSolver_indep<double> fclIndep;
  methods.push_back(measure(
      "fcl_indep", truth,
      [&](std::size_t i) {
        return fclIndep.shapeIntersect(*s.fclA[i], pairs[i].poseA, *s.fclB[i], pairs[i].poseB,
                                       nullptr);
      },
      [&](std::size_t i) {
        double d = 0.0;
        fclIndep.shapeDistance(*s.fclA[i], pairs[i].poseA, *s.fclB[i], pairs[i].poseB, &d);
        return std::max(d, 0.0);
      }));

  btVoronoiSimplexSolver simplexSolver;
  btGjkEpaPenetrationDepthSolver penetrationSolver;
  auto pairDetector = [&](std::size_t i) {
    btGjkPairDetector detector(s.bulletA[i].get(), s.bulletB[i].get(), &simplexSolver,
                               &penetrationSolver);
    btDiscreteCollisionDetectorInterface::ClosestPointInput input;
    input.m_transformA = s.bulletPoseA[i];
    input.m_transformB = s.bulletPoseB[i];
    btPointCollector output;
    detector.getClosestPoints(input, output, nullptr);
    return output.m_hasResult ? output.m_distance : 0.0;
  };
  methods.push_back(measure(
      "bullet_gjk_pair_detector", truth, [&](std::size_t i) { return pairDetector(i) <= 0.0; },
      [&](std::size_t i) { return std::max(pairDetector(i), 0.0); }));

  auto gjkEpa2 = [&](std::size_t i) {
    btGjkEpaSolver2::sResults result;
    const bool separated =
        btGjkEpaSolver2::Distance(s.bulletA[i].get(), s.bulletPoseA[i], s.bulletB[i].get(),
                                  s.bulletPoseB[i], btVector3(1, 0, 0), result);
    return separated ? result.distance : 0.0;
  };
  methods.push_back(measure(
      "bullet_gjk_epa2", truth, [&](std::size_t i) { return gjkEpa2(i) <= 0.0; },
      [&](std::size_t i) { return gjkEpa2(i); }));

  ccd_t ccd;
  CCD_INIT(&ccd);
  ccd.support1 = ccdSupport;
  ccd.support2 = ccdSupport;
  ccd.center1 = ccdCenter;
  ccd.center2 = ccdCenter;
  ccd.max_iterations = 500;
  methods.push_back(measure(
      "libccd_gjk", truth,
      [&](std::size_t i) { return ccdGJKIntersect(&s.ccdA[i], &s.ccdB[i], &ccd) != 0; }, nullptr));
  methods.push_back(measure(
      "libccd_mpr", truth,
      [&](std::size_t i) { return ccdMPRIntersect(&s.ccdA[i], &s.ccdB[i], &ccd) != 0; }, nullptr));
  return timeInterleaved(methods, runs);
}

// How kaboum's cold boolean query decides the pairs.
nlohmann::json kaboumDecisions(const std::vector<PolytopePair>& pairs) {
  PairDecisionCounts counts;
  for (const PolytopePair& pair : pairs) {
    const collision::ConvexPolytope a(pair.localA), b(pair.localB);
    counts.add(a, collision::TransformedSupport(b, pair.poseA.inverse() * pair.poseB));
  }
  return counts.toJson();
}

// Section "pairs": random convex polytope pairs per vertex count, every library side by side.
nlohmann::json runPairSection(const CollisionBenchOptions& options) {
  nlohmann::json section;
  for (const int n : options.vertexCounts) {
    if (n < 4) throw InputError(locate("--vertices", "a polytope needs at least 4 vertices"));
    if (!options.quiet) std::cerr << "pairs N=" << n << ": exact reference...\n";
    const std::vector<PolytopePair> pairs =
        testing::randomPolytopePairs(options.pairs, n, options.seed);
    std::vector<double> truth;
    int overlapping = 0;
    for (const PolytopePair& pair : pairs) {
      truth.push_back(testing::minkowskiReference(pair.worldA(), pair.worldB()).signedDistance);
      overlapping += truth.back() <= 0.0 ? 1 : 0;
    }
    if (!options.quiet) std::cerr << "pairs N=" << n << ": timing...\n";
    const std::vector<MethodReport> reports = measureAll(pairs, truth, options.runs);
    const MethodReport& ours = reports.front();

    nlohmann::json methods;
    for (const MethodReport& r : reports) {
      nlohmann::json entry = {
          {"boolean_ns", median(r.booleanRounds)},
          {"boolean_ratio_to_kaboum", sameRoundRatio(r.booleanRounds, ours.booleanRounds)},
          {"boolean_rounds_ns", r.booleanRounds},
          {"missed_overlaps", r.missedOverlaps},
          {"deepest_missed_overlap", r.deepestMissed},
          {"false_alarms", r.falseAlarms}};
      if (!r.distanceRounds.empty()) {
        entry["distance_ns"] = median(r.distanceRounds);
        entry["distance_ratio_to_kaboum"] = sameRoundRatio(r.distanceRounds, ours.distanceRounds);
        entry["distance_rounds_ns"] = r.distanceRounds;
        entry["distance_overestimates"] = r.overestimates;
        entry["largest_overestimate"] = r.largestOverestimate;
      }
      methods[r.name] = entry;
    }
    const nlohmann::json decisions = kaboumDecisions(pairs);
    section[std::to_string(n)] = {{"pairs", options.pairs},
                                  {"overlapping", overlapping},
                                  {"kaboum_boolean_decided_by", decisions},
                                  {"methods", methods}};

    if (!options.json) {
      std::printf(
          "\nconvex pairs, N=%d vertices: %zu pairs (%d overlapping), seed %llu, medians of "
          "%d interleaved rounds (ratio: median of the same-round ratios to kaboum)\n",
          n, options.pairs, overlapping, static_cast<unsigned long long>(options.seed),
          options.runs);
      std::printf(
          "kaboum boolean decided by: bounding spheres apart %d, inner balls overlapping %d, "
          "fan test %d, portal test %d, GJK %d\n",
          decisions["bounding_spheres_apart"].get<int>(),
          decisions["inner_balls_overlap"].get<int>(), decisions["fan"].get<int>(),
          decisions["portal"].get<int>(), decisions["gjk"].get<int>());
      std::printf("%-25s %10s %8s %11s %8s %7s %10s %7s %9s %10s\n", "method", "bool ns", "ratio",
                  "dist ns", "ratio", "missed", "deepest", "alarms", "dist>true", "largest");
      for (const MethodReport& r : reports) {
        std::printf("%-25s %10.1f %8.2f", r.name.c_str(), median(r.booleanRounds),
                    sameRoundRatio(r.booleanRounds, ours.booleanRounds));
        if (!r.distanceRounds.empty()) {
          std::printf(" %11.1f %8.2f", median(r.distanceRounds),
                      sameRoundRatio(r.distanceRounds, ours.distanceRounds));
        } else {
          std::printf(" %11s %8s", "-", "-");
        }
        std::printf(" %7d %10.2e %7d", r.missedOverlaps, r.deepestMissed, r.falseAlarms);
        if (!r.distanceRounds.empty()) {
          std::printf(" %9d %10.2e\n", r.overestimates, r.largestOverestimate);
        } else {
          std::printf(" %9s %10s\n", "-", "-");
        }
      }
    }
  }
  return section;
}

struct CollisionSection {
  const char* name;
  const char* description;
  nlohmann::json (*run)(const CollisionBenchOptions&);
};

// The full-robot section (bench_full_robot.hpp) with this verb's seed, runs and verbosity.
nlohmann::json runRobotSection(const CollisionBenchOptions& options) {
  FullRobotBenchOptions robot;
  robot.seed = options.seed;
  robot.runs = options.runs;
  robot.quiet = options.quiet;
  nlohmann::json section = runFullRobotBench(robot);
  if (!options.json) printFullRobotBench(section, std::cout);
  return section;
}

const CollisionSection kCollisionSections[] = {
    {"pairs", "convex polytope pairs: boolean and distance, per vertex count", runPairSection},
    {"robot",
     "full robot (KR5 hulls and bounding convex sets) vs 50 convex obstacles, FCL DynamicAABBTree "
     "side by side, Figure 4.9 distributions",
     runRobotSection},
};

int runCollisionBench(const CollisionBenchOptions& options) {
  if (options.pairs == 0) throw InputError(locate("--pairs", "must be at least 1"));
  if (options.runs < 1) throw InputError(locate("--runs", "must be at least 1"));
  for (const std::string& name : options.sections) {
    const bool known = std::any_of(std::begin(kCollisionSections), std::end(kCollisionSections),
                                   [&](const CollisionSection& s) { return name == s.name; });
    if (!known) throw InputError(locate("--section", "unknown section '" + name + "'"));
  }
  nlohmann::json out;
  for (const CollisionSection& section : kCollisionSections) {
    const bool selected =
        options.sections.empty() || std::find(options.sections.begin(), options.sections.end(),
                                              section.name) != options.sections.end();
    if (selected) out[section.name] = section.run(options);
  }
  if (options.json) std::cout << out.dump(2) << "\n";
  return 0;
}

VerbRunner setupCollision(CLI::App& command) {
  auto options = std::make_shared<CollisionBenchOptions>();
  CLI::App* collision = &command;
  collision->add_option("--pairs", options->pairs, "Random pairs per vertex count")
      ->capture_default_str();
  collision->add_option("--vertices", options->vertexCounts, "Vertex counts of the polytopes")
      ->capture_default_str();
  collision
      ->add_option("--runs", options->runs,
                   "Timed rounds (every library once per round, interleaved); medians are reported")
      ->capture_default_str();
  collision->add_option("--seed", options->seed, "Seed of the random workload")
      ->capture_default_str();
  std::string sectionHelp = "Sections to run (default: all):";
  for (const CollisionSection& s : kCollisionSections) {
    sectionHelp += std::string(" ") + s.name + " (" + s.description + ")";
  }
  collision->add_option("--section", options->sections, sectionHelp);
  collision->add_flag("--json", options->json, "Print the results as JSON");
  collision->add_flag("--quiet", options->quiet, "No progress messages on stderr");
  return [options] { return runCollisionBench(*options); };
}

const VerbRegistration registration{
    "collision",
    "Collision queries side by side: kaboum vs FCL 0.7, Bullet 3.24 and libccd on identical "
    "convex pairs and full-robot checks",
    setupCollision};

}  // namespace
}  // namespace kaboum::cli
