#include "kaboum/world/world.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <numeric>
#include <stdexcept>
#include <thread>
#include <tuple>

#include "kaboum/core/error.hpp"
#include "kaboum/core/text.hpp"
#include "kaboum/core/worker_pool.hpp"
#include "kaboum/io/mesh_io.hpp"
#include "kaboum/io/urdf_loader.hpp"
#include "kaboum/world/placement.hpp"
#include "kaboum/world/state_predicates.hpp"

namespace kaboum::world {

namespace {

using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// The positions an object with place_in may take at most (freeSpaceFound's random strategy), the
// draws when they put it on another movable object, and how far apart the objects' seeds lie.
constexpr std::size_t kRandomPlacementSamples = 2000;
constexpr std::size_t kRandomPlacementDraws = 20;
constexpr std::uint64_t kPlacementSeedStride = 1000003;

// How many times the piece limit of a decomposition is doubled at most while it stops above ε.
constexpr std::size_t kPieceLimitDoublings = 3;

// The pieces of the scene's meshes: decompositions at the scene's ε, the piece limit raised while
// it keeps them above ε (their decomposer: MeshDecompositions::buildOptions).
LinkPieceOptions pieceOptions(const SceneSettings& settings, const WorldOptions& options) {
  LinkPieceOptions pieces;
  pieces.decompose = options.pieces == MeshPieces::Decomposition;
  pieces.pieceLimitDoublings = kPieceLimitDoublings;
  if (settings.epsilonRelative) {
    pieces.decomposition.epsilon = 0;
    pieces.decomposition.epsilonPercent = 100 * settings.epsilon;
  } else {
    pieces.decomposition.epsilon = settings.epsilon;
  }
  pieces.decomposition.seed = settings.seed;
  return pieces;
}

// The robot's URDF with every tool's hand shapes added to the tool link's collision geometry.
RobotModel robotWithHands(const RobotSpec& spec) {
  const RobotModel urdf = loadUrdf(spec.urdf);
  std::vector<Link> links = urdf.links();
  for (const ToolSpec& tool : spec.tools) {
    if (!tool.hand) continue;
    Link& link = links[static_cast<std::size_t>(urdf.findLink(tool.link).value())];
    for (const Geometry& shape : tool.hand->shapes) link.collisions.push_back(shape.shape);
  }
  return {urdf.name(), std::move(links), urdf.joints()};
}

// Exempts the spec's allowed link pairs from self-collision checks (a link without collision
// geometry has no part to exempt). Throws InputError for a link the robot does not have.
void allowLinkPairs(const RobotSpec& spec, RobotCollisionModel& collision) {
  std::map<int, std::size_t> partOfLink;
  for (std::size_t part = 0; part < collision.partCount(); ++part) {
    partOfLink.emplace(collision.part(part).link, part);
  }
  const auto partOf = [&](const std::string& name) {
    const std::optional<int> link = collision.model().findLink(name);
    if (!link) {
      throw InputError(
          spec.source.message("allowed collision pair names unknown link '" + name + "'"));
    }
    return partOfLink.find(*link);
  };
  for (const AllowedPair& pair : spec.allowedCollisions) {
    const auto first = partOf(pair.first);
    const auto second = partOf(pair.second);
    if (first != partOfLink.end() && second != partOfLink.end()) {
      collision.filter().allow(first->second, second->second);
    }
  }
}

// The bytes of a mesh's vertices and triangles: meshes with equal bytes have equal decompositions.
std::string meshBytes(const TriangleMesh& mesh) {
  std::string bytes;
  bytes.reserve(8 + 24 * mesh.vertices.size() + 12 * mesh.triangles.size());
  const auto append = [&](const auto& value) {
    bytes.append(reinterpret_cast<const char*>(&value), sizeof value);
  };
  append(static_cast<std::uint64_t>(mesh.vertices.size()));
  for (const Vec3& v : mesh.vertices) {
    for (int i = 0; i < 3; ++i) append(v[i]);
  }
  for (const Triangle& t : mesh.triangles) append(t);
  return bytes;
}

bool sameOptions(const DecompositionOptions& a, const DecompositionOptions& b) {
  const auto fields = [](const DecompositionOptions& o) {
    return std::tie(o.epsilon, o.epsilonPercent, o.maxPieces, o.concavitySamples, o.bridgeSamples,
                    o.refineRounds, o.seed);
  };
  return fields(a) == fields(b);
}

// The decompositions of a World's distinct meshes (by content: the second arm of a model shares the
// first's), made before any body is built: one task per distinct mesh on a WorkerPool, each trying
// its piece limits in turn as boundingMeshPieces does (through the cache when there is one), the
// decompositions themselves sharing the pool's idle threads. The bodies are then built in scene
// order reading them, so that they equal a sequential build's whatever the thread count.
class MeshDecompositions {
 public:
  MeshDecompositions(LinkPieceOptions pieces, DecompositionCache* cache)
      : pieces_(std::move(pieces)), cache_(cache) {}

  // A mesh shape (its mesh as boundingShapePieces decomposes it, shapeMesh) of `owner`: robot r
  // is owner r, object o owner robots + o.
  void add(TriangleMesh mesh, const std::string& file, std::size_t owner) {
    const auto [found, added] = index_.try_emplace(meshBytes(mesh), meshes_.size());
    if (added) meshes_.push_back({std::move(mesh), file, owner, 0, {}, 0.0});
    ++meshes_[found->second].shapes;
  }

  // Decomposes every distinct mesh, the largest first. One that fails is left to the build, which
  // throws its error where a sequential build would.
  void decomposeAll(WorkerPool& workers) {
    std::vector<std::size_t> order(meshes_.size());
    std::iota(order.begin(), order.end(), std::size_t{0});
    std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
      return meshes_[a].mesh.triangleCount() > meshes_[b].mesh.triangleCount();
    });
    workers.run(order.size(), [&](std::size_t k) {
      Distinct& distinct = meshes_[order[k]];
      LinkPieceOptions recording = pieces_;
      recording.decomposer = [&](const TriangleMesh& mesh, const DecompositionOptions& options) {
        Decomposition decomposition = compute(mesh, options, &workers);
        distinct.attempts.emplace_back(options, decomposition);
        return decomposition;
      };
      const Clock::time_point start = Clock::now();
      try {
        (void)boundingMeshPieces(distinct.mesh, distinct.file, recording);
      } catch (...) {  // NOLINT(bugprone-empty-catch): the build decomposes it again and throws
      }
      distinct.seconds = secondsSince(start);
    });
  }

  // The options the bodies are built with: decompositions read from here (a missing one computed).
  [[nodiscard]] LinkPieceOptions buildOptions() const {
    LinkPieceOptions options = pieces_;
    options.decomposer = [this](const TriangleMesh& mesh, const DecompositionOptions& asked) {
      const auto found = index_.find(meshBytes(mesh));
      if (found != index_.end()) {
        for (const auto& [attempt, decomposition] : meshes_[found->second].attempts) {
          if (sameOptions(attempt, asked)) return decomposition;
        }
      }
      return compute(mesh, asked, nullptr);
    };
    return options;
  }

  // Seconds of the decomposition tasks of the meshes `owner` names first.
  [[nodiscard]] double secondsOf(std::size_t owner) const {
    double seconds = 0;
    for (const Distinct& distinct : meshes_) {
      if (distinct.owner == owner) seconds += distinct.seconds;
    }
    return seconds;
  }

  [[nodiscard]] std::vector<MeshDecomposition> summary() const {
    std::vector<MeshDecomposition> summary;
    for (const Distinct& distinct : meshes_) {
      summary.push_back({distinct.file, distinct.mesh.triangleCount(), distinct.shapes,
                         distinct.attempts.size(), distinct.seconds});
    }
    return summary;
  }

 private:
  struct Distinct {
    TriangleMesh mesh;
    std::string file;
    std::size_t owner = 0;
    std::size_t shapes = 0;
    std::vector<std::pair<DecompositionOptions, Decomposition>> attempts;
    double seconds = 0;
  };

  Decomposition compute(const TriangleMesh& mesh, const DecompositionOptions& options,
                        WorkerPool* workers) const {
    if (cache_) return cache_->decompose(mesh, options, workers);
    return workers ? decomposeBounding(mesh, options, *workers) : decomposeBounding(mesh, options);
  }

  LinkPieceOptions pieces_;
  DecompositionCache* cache_;
  std::map<std::string, std::size_t> index_;  // by meshBytes
  std::vector<Distinct> meshes_;              // in the order added
};

// The meshes of an object's geometry (none for a primitive).
LinkMeshes objectMeshes(const ObjectSpec& spec) {
  LinkMeshes meshes;
  if (spec.geometry.shape.kind == CollisionShape::Kind::Mesh) {
    meshes.emplace(spec.geometry.shape.meshPath, readMesh(spec.geometry.shape.meshPath));
  }
  return meshes;
}

WorldRobot buildRobot(const RobotSpec& spec, RobotModel model, const LinkMeshes& meshes,
                      const LinkPieceOptions& pieces, double homeMargin) {
  const Clock::time_point start = Clock::now();
  WorldRobot robot{spec.name, RobotCollisionModel(std::move(model), meshes, pieces), {}, 0, {}, {}};
  robot.collision.setBasePose(spec.base);
  allowLinkPairs(spec, robot.collision);
  for (const JointSpec& joint : spec.joints) robot.home.push_back(joint.home);
  std::vector<Pose> poses(robot.collision.model().links().size());
  robot.collision.model().linkPoses(robot.home, poses);
  robot.collision.allowPairsCollidingAt(poses, homeMargin);
  robot.preprocessingSeconds = secondsSince(start);
  return robot;
}

// The bounding error of every tool's hand shapes (by tool, by shape), which robotWithHands
// appended to its tool link's collision shapes in tool order.
std::vector<std::vector<double>> handShapeErrors(const RobotSpec& spec,
                                                 const RobotCollisionModel& collision) {
  const auto linkOf = [&](const ToolSpec& tool) {
    return static_cast<std::size_t>(collision.model().findLink(tool.link).value());
  };
  std::map<std::size_t, std::size_t> nextHandShape;  // by link: hand shapes, then the first's index
  for (const ToolSpec& tool : spec.tools) {
    if (tool.hand) nextHandShape[linkOf(tool)] += tool.hand->shapes.size();
  }
  for (auto& [link, next] : nextHandShape) next = collision.shapeBoundingErrors(link).size() - next;
  std::vector<std::vector<double>> errors;
  for (const ToolSpec& tool : spec.tools) {
    std::vector<double>& shapes = errors.emplace_back();
    if (!tool.hand) continue;
    const std::vector<double>& linkErrors = collision.shapeBoundingErrors(linkOf(tool));
    for (std::size_t s = 0; s < tool.hand->shapes.size(); ++s) {
      shapes.push_back(linkErrors[nextHandShape[linkOf(tool)]++]);
    }
  }
  return errors;
}

double diagonal(const CollisionBody& body) {
  return (body.bounds().box.hi - body.bounds().box.lo).norm();
}

// The bounding error allowed for a body: the larger of what the scene asks and what it reached.
double allowance(const BodyEpsilon& epsilon) {
  return std::max(epsilon.asked, epsilon.reached);
}

// How far body a at poseA must be raised to be free of body b at poseB (bisection to 0.1 mm): the
// depth of a collision as a user can act on it.
double verticalOverlap(const CollisionBody& a, const Pose& poseA, const CollisionBody& b,
                       const Pose& poseB) {
  double free = (a.bounds().box.hi - a.bounds().box.lo).norm() +
                (b.bounds().box.hi - b.bounds().box.lo).norm();
  double colliding = 0;
  const auto raised = [&](double lift) {
    Pose pose = poseA;
    pose.translation().z() += lift;
    return pose;
  };
  while (free - colliding > 1e-4) {
    const double middle = 0.5 * (free + colliding);
    (bodiesCollide(a, raised(middle), b, poseB, 0.0) ? colliding : free) = middle;
  }
  return free;
}

// The smallest lift tried when a movable object rests on another (metres); lifts double from here.
constexpr double kFirstLift = 1e-4;

// The movable objects of `scene` by the lowest world z of their bounds at `placements` (ties in
// object order).
std::vector<std::size_t> movableBottomUp(const CollisionScene& scene,
                                         std::span<const Placement> placements) {
  std::vector<std::pair<double, std::size_t>> bottoms;
  for (std::size_t o = 0; o < scene.size(); ++o) {
    if (!scene.movable(o)) continue;
    bottoms.emplace_back(
        transformedAabb(scene.body(o).bounds().box, scene.pose(o, placements)).lo.z(), o);
  }
  std::sort(bottoms.begin(), bottoms.end());
  std::vector<std::size_t> order;
  for (const auto& entry : bottoms) order.push_back(entry.second);
  return order;
}

}  // namespace

World::World(SceneDescription scene, const WorldOptions& options) : description_(std::move(scene)) {
  const Clock::time_point start = Clock::now();
  std::optional<DecompositionCache> cache;
  if (options.cacheDirectory) cache.emplace(*options.cacheDirectory);
  const auto& robotSpecs = description_.robots;
  const auto& objects = description_.objects;
  const std::size_t robotCount = robotSpecs.size();
  WorkerPool workers(options.threads > 0 ? options.threads : std::thread::hardware_concurrency());
  decompositions_.threads = workers.threads();
  // Three rounds on the pool, each task writing only its own outputs (a failure: the error of the
  // first robot, then object, in scene order): every file read (robots with their hands, objects),
  // the distinct meshes decomposed, the bodies built from those decompositions.
  std::vector<std::optional<RobotModel>> models(robotCount);
  std::vector<LinkMeshes> robotMeshes(robotCount), bodyMeshes(objects.size());
  std::vector<double> loadSeconds(robotCount);
  workers.run(robotCount + objects.size(), [&](std::size_t i) {
    if (i >= robotCount) {
      bodyMeshes[i - robotCount] = objectMeshes(objects[i - robotCount]);
      return;
    }
    const Clock::time_point robotStart = Clock::now();
    models[i].emplace(robotWithHands(robotSpecs[i]));
    robotMeshes[i] = readCollisionMeshes(*models[i]);
    loadSeconds[i] = secondsSince(robotStart);
  });
  MeshDecompositions decompositions(pieceOptions(description_.settings, options),
                                    cache ? &*cache : nullptr);
  if (options.pieces == MeshPieces::Decomposition) {
    for (std::size_t r = 0; r < models.size(); ++r) {
      for (const Link& link : models[r]->links()) {
        for (const CollisionShape& shape : link.collisions) {
          if (shape.kind != CollisionShape::Kind::Mesh) continue;
          decompositions.add(shapeMesh(shape, robotMeshes[r]), shape.meshPath, r);
        }
      }
    }
    for (std::size_t o = 0; o < objects.size(); ++o) {
      const CollisionShape& shape = objects[o].geometry.shape;
      if (shape.kind != CollisionShape::Kind::Mesh) continue;
      decompositions.add(shapeMesh(shape, bodyMeshes[o]), shape.meshPath, robotCount + o);
    }
    decompositions.decomposeAll(workers);
    decompositions_.meshes = decompositions.summary();
  }
  const LinkPieceOptions pieces = decompositions.buildOptions();
  std::vector<std::optional<WorldRobot>> built(robotCount);
  std::vector<BoundingPieces> objectBounding(objects.size());
  std::vector<BodyPtr> objectBodies(objects.size());
  objectSeconds_.assign(objects.size(), 0.0);
  workers.run(robotCount + objects.size(), [&](std::size_t i) {
    const Clock::time_point buildStart = Clock::now();
    if (i < robotCount) {
      built[i].emplace(buildRobot(robotSpecs[i], std::move(*models[i]), robotMeshes[i], pieces,
                                  2 * description_.settings.sweepEpsilon));
      built[i]->preprocessingSeconds += loadSeconds[i] + decompositions.secondsOf(i);
      return;
    }
    const std::size_t o = i - robotCount;
    objectBounding[o] = boundingShapePieces(objects[o].geometry.shape, bodyMeshes[o], pieces);
    objectBodies[o] = std::make_shared<const CollisionBody>(objectBounding[o].pieces,
                                                            "object " + objects[o].name);
    objectSeconds_[o] = secondsSince(buildStart) + decompositions.secondsOf(i);
  });
  for (std::size_t r = 0; r < robotCount; ++r) {
    WorldRobot& robot = robots_.emplace_back(std::move(*built[r]));
    for (std::size_t i = 0; i < robot.collision.partCount(); ++i) {
      const Attachment& part = robot.collision.part(i);
      const std::vector<double>& errors =
          robot.collision.shapeBoundingErrors(static_cast<std::size_t>(part.link));
      robot.partEpsilon.push_back(
          {epsilonFor(diagonal(*part.body)), *std::max_element(errors.begin(), errors.end())});
    }
    robot.handShapeEpsilon = handShapeErrors(description_.robots[r], robot.collision);
    names_[lowerCase(description_.robots[r].name)] = {NamedEntity::Kind::Robot, r};
  }

  for (std::size_t o = 0; o < objects.size(); ++o) {
    BodyPtr body = std::move(objectBodies[o]);
    objectEpsilon_.push_back({epsilonFor(diagonal(*body)), objectBounding[o].boundingError});
    if (objects[o].movable) {
      scene_.addMovable(std::move(body), objects[o].pose, objects[o].name);
    } else {
      scene_.add(std::move(body), objects[o].pose, objects[o].name);
    }
    names_[lowerCase(objects[o].name)] = {NamedEntity::Kind::Object, o};
  }

  // Movable objects start free, raised off what they rest on when touching is all that collides,
  // and further up to the resting gap (restingGap()), so that certified motions can leave them.
  // Lowest first, each against the fixed obstacles and the objects placed before it, so that an
  // object stacked on another is raised off it once that one has moved (a collision between two
  // objects is found when the higher one is placed).
  initialPlacements_ = scene_.initialState();
  restingLift_.assign(objects.size(), 0.0);
  const double gap = restingGap();
  const std::vector<std::size_t> bottomUp = movableBottomUp(scene_, initialPlacements_);
  for (const std::size_t o : bottomUp) initialPlacements_[scene_.slot(o)].present = false;
  for (const std::size_t o : bottomUp) {
    if (objects[o].placeIn) continue;  // placed at random below, once the others stand
    initialPlacements_[scene_.slot(o)].present = true;
    Pose& pose = initialPlacements_[scene_.slot(o)].pose;
    const std::optional<std::size_t> near =
        scene_.firstCollision(initialPlacements_, scene_.body(o), pose, gap, o);
    if (!near) continue;
    const std::optional<std::size_t> hit =
        scene_.firstCollision(initialPlacements_, scene_.body(o), pose, 0.0, o);
    const double largestLift =
        allowance(objectEpsilon_[o]) + allowance(objectEpsilon_[*near]) + 2 * gap + kFirstLift;
    // On a movable object already raised: that object's lift first (a stack rises as a whole).
    const double below = objects[*near].movable ? restingLift_[*near] : 0.0;
    const Pose written = pose;
    for (double lift = kFirstLift; lift <= largestLift && restingLift_[o] == 0; lift *= 2) {
      Pose raised = written;
      raised.translation().z() += below + lift;
      if (!scene_.firstCollision(initialPlacements_, scene_.body(o), raised, gap, o)) {
        pose = raised;
        restingLift_[o] = below + lift;
      }
    }
    if (!hit) continue;  // near but free: raised when that frees it, else left where it is
    if (restingLift_[o] == 0) {
      const double depth = verticalOverlap(scene_.body(o), written, scene_.body(*hit),
                                           scene_.pose(*hit, initialPlacements_));
      throw InputError(objects[o].poseSource.message(
          "object '" + objects[o].name + "' starts in collision with object '" +
          objects[*hit].name + "' (" + fmt::format("{:.1f}", 1000 * depth) +
          " mm deep: raised by that much it would be free)"));
    }
  }
  for (std::size_t l = 0; l < description_.locations.size(); ++l) {
    names_[lowerCase(description_.locations[l].name)] = {NamedEntity::Kind::Location, l};
  }
  placeAtRandom();
  if (cache) cacheReport_ = cache->report();
  validateInitialState();
  preprocessingSeconds_ = secondsSince(start);
}

void World::placeAtRandom() {
  const auto& objects = description_.objects;
  if (std::none_of(objects.begin(), objects.end(), [](const auto& o) { return o.placeIn; })) return;
  const PlacementGeometry placement(*this);
  QueryScratch queries = scratch();
  for (std::size_t o = 0; o < objects.size(); ++o) {
    if (!objects[o].placeIn) continue;
    FreeSpaceOptions options;
    options.strategy = SearchStrategy::Random;
    options.maxSamples = kRandomPlacementSamples;
    options.seed = description_.settings.placementSeed * kPlacementSeedStride + o;
    Placement& placed = initialPlacements_[scene_.slot(o)];
    // A pose on another movable object (a stack) is drawn again, with the next seed.
    FreeSpace found;
    for (std::size_t draw = 0; draw < kRandomPlacementDraws; ++draw, ++options.seed) {
      placed.present = false;
      found = placement.freeSpaceFound(initialState(), o, *objects[o].placeIn, options, queries);
      if (!found.pose) break;
      placed = {*found.pose, true};
      const GeometricState state = initialState();
      bool stacked = false;
      for (std::size_t other = 0; other < objects.size() && !stacked; ++other) {
        stacked = other != o && scene_.movable(other) && placement.objectOnTop(state, other) == o;
      }
      if (!stacked) break;
      found.pose.reset();
    }
    if (!found.pose) {
      placed.present = false;
      throw InputError(objects[o].poseSource.message(fmt::format(
          "no free place for object '{}' in location '{}' ({} random samples)", objects[o].name,
          description_.locations[*objects[o].placeIn].name, found.samples)));
    }
  }
}

void World::validateInitialState() {
  const std::optional<Collision> collision = firstCollision(initialState());
  if (!collision) return;
  // Robots come first in the checks, and movable objects were already freed of each other.
  const Party& party = collision->first;
  const SourceLocation& source = party.kind == Party::Kind::Robot
                                     ? description_.robots[party.index].homeSource
                                     : description_.objects[party.index].poseSource;
  const std::string what = party.kind == Party::Kind::Robot ? " at home" : " at its initial pose";
  throw InputError(
      source.message(describe(party) + what + " collides with " + describe(collision->second)));
}

std::optional<NamedEntity> World::find(const std::string& name) const {
  const auto found = names_.find(lowerCase(name));
  if (found == names_.end()) return std::nullopt;
  return found->second;
}

double World::epsilonFor(double diagonal) const {
  const SceneSettings& settings = description_.settings;
  return settings.epsilonRelative ? settings.epsilon * diagonal : settings.epsilon;
}

GeometricState World::initialState() const {
  GeometricState state;
  for (const WorldRobot& robot : robots_) state.robots.push_back({robot.home, {}, {}});
  state.placements = initialPlacements_;
  return state;
}

QueryScratch World::scratch() const {
  QueryScratch scratch;
  for (const WorldRobot& robot : robots_) {
    scratch.linkPoses.emplace_back(robot.collision.model().links().size());
  }
  scratch.againstRobots.resize(robots_.size());
  scratch.placements.reserve(scene_.movableCount());
  return scratch;
}

void World::hold(GeometricState& state, std::size_t robot, int link, std::size_t object,
                 const Pose& objectInLink) const {
  checkState(state);
  Placement& placement = state.placements[scene_.slot(object)];
  if (!placement.present) {
    throw std::invalid_argument("object '" + scene_.name(object) + "' is not placed in the state");
  }
  const Attachment attachment{scene_.sharedBody(object), link, objectInLink};
  robots_.at(robot).collision.checkHeld(std::span(&attachment, 1));
  placement.present = false;
  state.robots[robot].held.push_back(attachment);
  state.robots[robot].heldObjects.push_back(object);
}

Pose World::release(GeometricState& state, std::size_t robot, std::size_t object) const {
  checkState(state);
  RobotState& holder = state.robots.at(robot);
  const auto it = std::find(holder.heldObjects.begin(), holder.heldObjects.end(), object);
  if (it == holder.heldObjects.end()) {
    throw std::invalid_argument("robot '" + robots_[robot].name + "' does not hold object '" +
                                scene_.name(object) + "'");
  }
  const auto index = static_cast<std::size_t>(it - holder.heldObjects.begin());
  const RobotCollisionModel& model = robots_[robot].collision;
  std::vector<Pose> linkPoses(model.model().links().size());
  model.model().linkPoses(holder.configuration, linkPoses);
  const Attachment& attachment = holder.held[index];
  const Pose pose =
      model.basePose() * linkPoses[static_cast<std::size_t>(attachment.link)] * attachment.inLink;
  holder.held.erase(holder.held.begin() + static_cast<std::ptrdiff_t>(index));
  holder.heldObjects.erase(it);
  state.placements[scene_.slot(object)] = Placement{pose, true};
  return pose;
}

void World::checkState(const GeometricState& state) const {
  if (state.robots.size() != robots_.size()) {
    throw std::invalid_argument("state of " + std::to_string(state.robots.size()) +
                                " robots for a world of " + std::to_string(robots_.size()));
  }
  for (std::size_t r = 0; r < robots_.size(); ++r) {
    const RobotState& robot = state.robots[r];
    if (robot.configuration.size() !=
            static_cast<std::size_t>(robots_[r].collision.model().dof()) ||
        robot.held.size() != robot.heldObjects.size()) {
      throw std::invalid_argument("state of robot '" + robots_[r].name + "' has the wrong size");
    }
  }
}

void World::computeLinkPoses(const GeometricState& state, QueryScratch& scratch) const {
  for (std::size_t r = 0; r < robots_.size(); ++r) {
    robots_[r].collision.model().linkPoses(state.robots[r].configuration, scratch.linkPoses[r]);
  }
}

std::optional<Collision> World::firstCollisionOfRobot(const GeometricState& state,
                                                      const QueryScratch& scratch,
                                                      std::size_t robot,
                                                      std::span<const std::uint8_t> against,
                                                      double margin) const {
  if (predicates_ != nullptr) {
    return predicates_->firstCollisionOfRobot(state, scratch, robot, against);
  }
  const RobotCollisionModel& model = robots_[robot].collision;
  const std::span<const Attachment> held = state.robots[robot].held;
  const std::span<const Pose> poses = scratch.linkPoses[robot];
  if (const auto parts = model.firstSelfCollision(poses, held, 2 * margin)) {
    return Collision{partyOf(state, robot, parts->first), partyOf(state, robot, parts->second)};
  }
  for (std::size_t i = 0; i < model.partCount(held); ++i) {
    if (const auto hit = scene_.firstCollision(state.placements, *model.part(i, held).body,
                                               model.partPose(i, poses, held), margin)) {
      return Collision{partyOf(state, robot, i), {Party::Kind::Object, *hit}};
    }
  }
  for (std::size_t other = 0; other < robots_.size(); ++other) {
    if (other == robot || against[other] == 0) continue;
    const RobotCollisionModel& otherModel = robots_[other].collision;
    const std::span<const Attachment> otherHeld = state.robots[other].held;
    for (std::size_t i = 0; i < model.partCount(held); ++i) {
      const Pose pose = model.partPose(i, poses, held);
      for (std::size_t j = 0; j < otherModel.partCount(otherHeld); ++j) {
        if (bodiesCollide(*model.part(i, held).body, pose, *otherModel.part(j, otherHeld).body,
                          otherModel.partPose(j, scratch.linkPoses[other], otherHeld),
                          2 * margin)) {
          return Collision{partyOf(state, robot, i), partyOf(state, other, j)};
        }
      }
    }
  }
  return std::nullopt;
}

std::optional<Collision> World::firstCollision(const GeometricState& state,
                                               QueryScratch& scratch) const {
  checkState(state);
  computeLinkPoses(state, scratch);
  // Each robot against itself, the scene and the robots after it.
  std::fill(scratch.againstRobots.begin(), scratch.againstRobots.end(), std::uint8_t{1});
  for (std::size_t r = 0; r < robots_.size(); ++r) {
    scratch.againstRobots[r] = 0;
    if (auto collision = firstCollisionOfRobot(state, scratch, r, scratch.againstRobots, 0.0)) {
      return collision;
    }
  }
  for (std::size_t object = 0; object < scene_.size(); ++object) {
    if (!scene_.movable(object) || !scene_.present(object, state.placements)) continue;
    const Pose pose = scene_.pose(object, state.placements);
    if (predicates_ != nullptr) {
      if (const auto hit =
              predicates_->firstCollisionOfObject(state, scratch, object, pose, false)) {
        return Collision{{Party::Kind::Object, object}, *hit};
      }
      continue;
    }
    std::span<const Placement> others = state.placements;
    if (state.isJoined(object)) {
      scratch.placements.assign(state.placements.begin(), state.placements.end());
      for (const auto& [a, b] : state.joined) {
        if (a == object || b == object)
          scratch.placements[scene_.slot(a == object ? b : a)].present = false;
      }
      others = scratch.placements;
    }
    if (const auto hit = scene_.firstCollision(others, scene_.body(object), pose, 0.0, object)) {
      return Collision{{Party::Kind::Object, object}, {Party::Kind::Object, *hit}};
    }
  }
  return std::nullopt;
}

std::optional<Collision> World::firstCollision(const GeometricState& state) const {
  QueryScratch buffers = scratch();
  return firstCollision(state, buffers);
}

Party World::partyOf(const GeometricState& state, std::size_t robot, std::size_t part) const {
  const RobotCollisionModel& model = robots_[robot].collision;
  const std::size_t links = model.partCount();
  return part < links ? Party{Party::Kind::Robot, robot, model.part(part).link}
                      : Party{Party::Kind::Object, state.robots[robot].heldObjects[part - links]};
}

std::string World::linkName(const Party& party) const {
  return robots_[party.index].collision.model().links()[static_cast<std::size_t>(party.link)].name;
}

std::string World::describe(const Party& party) const {
  if (party.kind == Party::Kind::Object) return "object '" + scene_.name(party.index) + "'";
  const std::string robot = "robot '" + robots_[party.index].name + "'";
  return party.link < 0 ? robot : robot + " link '" + linkName(party) + "'";
}

std::string World::describe(const Collision& collision) const {
  const Party& first = collision.first;
  const Party& second = collision.second;
  if (first.kind == Party::Kind::Robot && second.kind == Party::Kind::Robot &&
      first.index == second.index && second.link >= 0) {
    return describe(first) + " collides with its link '" + linkName(second) + "'";
  }
  return describe(first) + " collides with " + describe(second);
}

}  // namespace kaboum::world
