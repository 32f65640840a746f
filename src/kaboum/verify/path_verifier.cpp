#include "kaboum/verify/path_verifier.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include "kaboum/core/error.hpp"

namespace kaboum::verify {

namespace {

// How far a waypoint may lie outside a joint's limits (radians or metres), for values written
// with rounding.
constexpr double kLimitTolerance = 1e-9;

// The robot moved by each stretch of a concatenated configuration: robot index and first value.
struct RobotSlice {
  std::size_t robot = 0;
  std::size_t offset = 0;
};

std::vector<RobotSlice> slicesOf(const World& world, const ScenePath& path) {
  std::vector<RobotSlice> slices;
  std::size_t offset = 0;
  for (std::size_t robot : path.robots) {
    slices.push_back({robot, offset});
    offset += static_cast<std::size_t>(world.robots()[robot].collision.model().dof());
  }
  return slices;
}

std::vector<double> configurationAt(const ScenePath& path, const PathPlace& place) {
  const std::vector<double>& a = path.waypoints[place.segment];
  if (place.segment + 1 == path.waypoints.size()) return a;
  const std::vector<double>& b = path.waypoints[place.segment + 1];
  std::vector<double> q(a.size());
  for (std::size_t j = 0; j < a.size(); ++j) q[j] = std::lerp(a[j], b[j], place.fraction);
  return q;
}

// The points whose motion between two samples is bounded by toolStep: every link origin, tool
// centre point and held object frame of the moving robots, in the robots' model frames.
class TrackedPoints {
 public:
  TrackedPoints(const World& world, const ScenePath& path) : slices_(slicesOf(world, path)) {
    for (const RobotSlice& slice : slices_) {
      const RobotModel& model = world.robots()[slice.robot].collision.model();
      models_.push_back(&model);
      poses_.emplace_back(model.links().size());
      std::vector<std::pair<std::size_t, Vec3>>& points = points_.emplace_back();
      for (std::size_t link = 0; link < model.links().size(); ++link) {
        points.emplace_back(link, Vec3::Zero());
      }
      for (const ToolSpec& tool : world.description().robots[slice.robot].tools) {
        points.emplace_back(static_cast<std::size_t>(model.findLink(tool.link).value()),
                            tool.tcp.translation());
      }
      for (const ResolvedHeld& held : path.held) {
        if (held.robot == slice.robot) {
          points.emplace_back(held.link, held.objectInLink.translation());
        }
      }
    }
  }

  std::vector<Vec3> at(const std::vector<double>& configuration) {
    std::vector<Vec3> positions;
    for (std::size_t k = 0; k < slices_.size(); ++k) {
      const std::span<const double> q(configuration.data() + slices_[k].offset,
                                      static_cast<std::size_t>(models_[k]->dof()));
      models_[k]->linkPoses(q, poses_[k]);
      for (const auto& [link, point] : points_[k]) positions.push_back(poses_[k][link] * point);
    }
    return positions;
  }

 private:
  std::vector<RobotSlice> slices_;
  std::vector<const RobotModel*> models_;
  std::vector<std::vector<Pose>> poses_;
  std::vector<std::vector<std::pair<std::size_t, Vec3>>> points_;
};

double largestMotion(const std::vector<Vec3>& from, const std::vector<Vec3>& to) {
  double largest = 0;
  for (std::size_t i = 0; i < from.size(); ++i)
    largest = std::max(largest, (to[i] - from[i]).norm());
  return largest;
}

// Interval widths below this are not subdivided further (a guard against unbounded refinement).
constexpr double kSmallestInterval = 1e-12;

// Appends the samples of [t0, t1) of `segment`, subdividing until no tracked point moves more
// than `toolStep` between consecutive samples.
void refine(const ScenePath& path, TrackedPoints& points, std::size_t segment, double t0,
            const std::vector<Vec3>& p0, double t1, const std::vector<Vec3>& p1, double toolStep,
            std::vector<PathPlace>& samples) {
  const double motion = largestMotion(p0, p1);
  if (motion <= toolStep || t1 - t0 < kSmallestInterval) {
    samples.push_back({segment, t0});
    return;
  }
  const double parts = std::max(2.0, std::ceil(motion / toolStep));
  double start = t0;
  std::vector<Vec3> startPoints = p0;
  for (double k = 1; k <= parts; ++k) {
    const double end = k == parts ? t1 : std::lerp(t0, t1, k / parts);
    std::vector<Vec3> endPoints =
        k == parts ? p1 : points.at(configurationAt(path, {segment, end}));
    refine(path, points, segment, start, startPoints, end, endPoints, toolStep, samples);
    start = end;
    startPoints = std::move(endPoints);
  }
}

std::string nameList(const World& world, const std::vector<std::size_t>& robots) {
  std::string list;
  for (std::size_t robot : robots) {
    list += (list.empty() ? "'" : ", '") + world.robots()[robot].name + "'";
  }
  return list;
}

// One party of the checks: a robot link, a held object or a scene object, with its reference body.
struct CheckedParty {
  PartyName name;
  std::size_t body = 0;
  std::optional<std::size_t> robot;  // absent for a scene object
  std::size_t link = 0;
  Pose inLink = Pose::Identity();  // a held object's frame in its link frame
  bool held = false;
  Pose scenePose = Pose::Identity();  // a scene object's world pose
  std::optional<std::size_t> object;  // a held or scene object's id
};

// What the robots hold: the moving robots' objects of the path, the others' of the context.
std::vector<ResolvedHeld> heldObjects(const ScenePath& path) {
  std::vector<ResolvedHeld> held = path.held;
  if (!path.context) return held;
  for (std::size_t r = 0; r < path.context->robots.size(); ++r) {
    if (std::find(path.robots.begin(), path.robots.end(), r) != path.robots.end()) continue;
    const RobotState& robot = path.context->robots[r];
    for (std::size_t i = 0; i < robot.held.size(); ++i) {
      held.push_back({r, robot.heldObjects[i], static_cast<std::size_t>(robot.held[i].link),
                      robot.held[i].inLink});
    }
  }
  return held;
}

std::vector<CheckedParty> partiesOf(const ReferenceGeometry& geometry, const ScenePath& path) {
  const World& world = geometry.world();
  const std::vector<ResolvedHeld> allHeld = heldObjects(path);
  std::vector<CheckedParty> parties;
  for (std::size_t r = 0; r < world.robots().size(); ++r) {
    const WorldRobot& robot = world.robots()[r];
    const std::vector<Link>& links = robot.collision.model().links();
    for (std::size_t link = 0; link < links.size(); ++link) {
      if (const std::optional<std::size_t> body = geometry.linkBody(r, link)) {
        CheckedParty party;
        party.name = {robot.name, links[link].name, ""};
        party.body = *body;
        party.robot = r;
        party.link = link;
        parties.push_back(std::move(party));
      }
    }
    for (const ResolvedHeld& held : allHeld) {
      if (held.robot != r) continue;
      parties.push_back({{robot.name, links[held.link].name, world.scene().name(held.object)},
                         geometry.objectBody(held.object),
                         r,
                         held.link,
                         held.objectInLink,
                         true,
                         Pose::Identity(),
                         held.object});
    }
  }
  const GeometricState state = path.context ? *path.context : world.initialState();
  for (std::size_t object = 0; object < world.scene().size(); ++object) {
    if (std::any_of(allHeld.begin(), allHeld.end(),
                    [&](const ResolvedHeld& held) { return held.object == object; })) {
      continue;
    }
    CheckedParty party;
    party.name.object = world.scene().name(object);
    party.body = geometry.objectBody(object);
    party.scenePose = world.scene().pose(object, state.placements);
    party.object = object;
    parties.push_back(std::move(party));
  }
  return parties;
}

// Whether the World checks two parties of the same robot against each other: link pairs unless
// its collision filter allows them, a held object against parts of other links only.
bool worldChecksSelfPair(const RobotCollisionModel& robot, const CheckedParty& a,
                         const CheckedParty& b) {
  if (a.held || b.held) return a.link != b.link;
  std::optional<std::size_t> partA, partB;
  for (std::size_t part = 0; part < robot.partCount(); ++part) {
    const auto link = static_cast<std::size_t>(robot.part(part).link);
    if (link == a.link) partA = part;
    if (link == b.link) partB = part;
  }
  return !partA || !partB || !robot.filter().allowed(*partA, *partB);
}

// The pairs of parties checked at each sample: those with a party on a moving robot, but for two
// objects joined in the path's context (GeometricState::joined).
std::vector<std::pair<std::size_t, std::size_t>> checkedPairs(
    const World& world, const ScenePath& path, const std::vector<CheckedParty>& parties) {
  const auto moving = [&](const CheckedParty& party) {
    return party.robot &&
           std::find(path.robots.begin(), path.robots.end(), *party.robot) != path.robots.end();
  };
  std::vector<std::pair<std::size_t, std::size_t>> pairs;
  for (std::size_t i = 0; i < parties.size(); ++i) {
    for (std::size_t j = i + 1; j < parties.size(); ++j) {
      const CheckedParty &a = parties[i], &b = parties[j];
      if (!moving(a) && !moving(b)) continue;
      if (path.context && a.object && b.object && path.context->areJoined(*a.object, *b.object)) {
        continue;
      }
      if (a.robot && b.robot && *a.robot == *b.robot &&
          !worldChecksSelfPair(world.robots()[*a.robot].collision, a, b)) {
        continue;
      }
      pairs.emplace_back(i, j);
    }
  }
  return pairs;
}

nlohmann::json partyJson(const PartyName& party) {
  const auto orNull = [](const std::string& text) {
    return text.empty() ? nlohmann::json(nullptr) : nlohmann::json(text);
  };
  return {{"robot", orNull(party.robot)},
          {"link", orNull(party.link)},
          {"object", orNull(party.object)},
          {"description", describe(party)}};
}

nlohmann::json placeJson(const PathPlace& place) {
  return {{"segment", place.segment}, {"fraction", place.fraction}};
}

}  // namespace

std::string waypointError(const World& world, std::span<const std::size_t> robots,
                          std::span<const double> waypoint) {
  ScenePath path;
  path.robots.assign(robots.begin(), robots.end());
  std::size_t dof = 0;
  for (std::size_t robot : robots) {
    dof += static_cast<std::size_t>(world.robots()[robot].collision.model().dof());
  }
  if (waypoint.size() != dof) {
    return fmt::format(": {} values, but robots {} have {} joints", waypoint.size(),
                       nameList(world, path.robots), dof);
  }
  for (const RobotSlice& slice : slicesOf(world, path)) {
    const WorldRobot& robot = world.robots()[slice.robot];
    for (int v = 0; v < robot.collision.model().dof(); ++v) {
      const Joint& joint = robot.collision.model().variableJoint(v);
      const std::size_t index = slice.offset + static_cast<std::size_t>(v);
      const double value = waypoint[index];
      if (!std::isfinite(value)) return fmt::format("[{}]: not finite", index);
      if (joint.type != JointType::Continuous &&
          (value < joint.lower - kLimitTolerance || value > joint.upper + kLimitTolerance)) {
        return fmt::format(
            "[{}]: joint '{}' of robot '{}' at {:g} is outside its limits [{:g}, {:g}]", index,
            joint.name, robot.name, value, joint.lower, joint.upper);
      }
    }
  }
  return "";
}

ScenePath resolvePath(const World& world, const io::PathFile& path, const std::string& fileName) {
  const auto fail = [&](const std::string& key, const std::string& what) {
    throw InputError(locate(fileName, key + ": " + what));
  };
  ScenePath result;
  std::size_t dof = 0;
  for (std::size_t i = 0; i < path.robots.size(); ++i) {
    const std::string key = fmt::format("robots[{}]", i);
    const std::optional<NamedEntity> found = world.find(path.robots[i]);
    if (!found || found->kind != NamedEntity::Kind::Robot) {
      fail(key, "no robot '" + path.robots[i] + "' in the scene");
    }
    const auto earlier = std::find(result.robots.begin(), result.robots.end(), found->index);
    if (earlier != result.robots.end()) {
      fail(key, fmt::format("robot '{}' is already robots[{}]", path.robots[i],
                            earlier - result.robots.begin()));
    }
    result.robots.push_back(found->index);
    dof += static_cast<std::size_t>(world.robots()[found->index].collision.model().dof());
  }
  if (path.waypoints.empty()) fail("waypoints", "no waypoint");
  for (std::size_t w = 0; w < path.waypoints.size(); ++w) {
    const std::string error = waypointError(world, result.robots, path.waypoints[w]);
    if (!error.empty())
      throw InputError(locate(fileName, fmt::format("waypoints[{}]{}", w, error)));
  }
  result.waypoints = path.waypoints;
  for (std::size_t h = 0; h < path.held.size(); ++h) {
    const io::HeldObject& held = path.held[h];
    const std::string key = fmt::format("held[{}]", h);
    const std::optional<NamedEntity> robot = world.find(held.robot);
    if (!robot || robot->kind != NamedEntity::Kind::Robot) {
      fail(key + ".robot", "no robot '" + held.robot + "' in the scene");
    }
    const std::optional<NamedEntity> object = world.find(held.object);
    if (!object || object->kind != NamedEntity::Kind::Object) {
      fail(key + ".object", "no object '" + held.object + "' in the scene");
    }
    if (!world.scene().movable(object->index)) {
      fail(key + ".object", "object '" + held.object + "' is not movable");
    }
    for (std::size_t earlier = 0; earlier < result.held.size(); ++earlier) {
      if (result.held[earlier].object == object->index) {
        fail(key + ".object",
             fmt::format("object '{}' is already held (held[{}])", held.object, earlier));
      }
    }
    const RobotModel& model = world.robots()[robot->index].collision.model();
    const std::optional<int> link = model.findLink(held.link);
    if (!link) {
      fail(key + ".link", "robot '" + held.robot + "' has no link '" + held.link + "'");
    }
    result.held.push_back(
        {robot->index, object->index, static_cast<std::size_t>(*link), held.objectInLink});
  }
  return result;
}

std::vector<PathPlace> densify(const World& world, const ScenePath& path,
                               const VerifyOptions& options) {
  if (!(options.jointStep > 0) || !(options.toolStep > 0)) {
    throw std::invalid_argument("densify: steps must be positive");
  }
  std::vector<double> jointSteps;
  for (const RobotSlice& slice : slicesOf(world, path)) {
    const RobotModel& model = world.robots()[slice.robot].collision.model();
    for (int v = 0; v < model.dof(); ++v) {
      jointSteps.push_back(model.variableJoint(v).type == JointType::Prismatic ? options.toolStep
                                                                               : options.jointStep);
    }
  }
  TrackedPoints points(world, path);
  std::vector<PathPlace> samples;
  for (std::size_t segment = 0; segment + 1 < path.waypoints.size(); ++segment) {
    const std::vector<double>& a = path.waypoints[segment];
    const std::vector<double>& b = path.waypoints[segment + 1];
    double intervals = 1;
    for (std::size_t j = 0; j < a.size(); ++j) {
      intervals = std::max(intervals, std::ceil(std::abs(b[j] - a[j]) / jointSteps[j]));
    }
    double start = 0;
    std::vector<Vec3> startPoints = points.at(a);
    for (double k = 1; k <= intervals; ++k) {
      const double end = k / intervals;
      std::vector<Vec3> endPoints = points.at(configurationAt(path, {segment, end}));
      refine(path, points, segment, start, startPoints, end, endPoints, options.toolStep, samples);
      start = end;
      startPoints = std::move(endPoints);
    }
  }
  if (path.waypoints.size() == 1) {
    samples.push_back({0, 0.0});
  } else {
    samples.push_back({path.waypoints.size() - 2, 1.0});
  }
  return samples;
}

std::string describe(const PartyName& party) {
  if (party.object.empty()) return "robot '" + party.robot + "' link '" + party.link + "'";
  if (party.robot.empty()) return "object '" + party.object + "'";
  return "object '" + party.object + "' held by robot '" + party.robot + "'";
}

PathVerification verifyPath(const ReferenceGeometry& geometry, const ScenePath& path,
                            const VerifyOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  const World& world = geometry.world();
  const std::vector<PathPlace> samples = densify(world, path, options);
  const std::vector<CheckedParty> parties = partiesOf(geometry, path);
  const std::vector<std::pair<std::size_t, std::size_t>> pairs = checkedPairs(world, path, parties);
  const std::vector<RobotSlice> slices = slicesOf(world, path);

  // Link poses of every robot; robots not in the path stay where the context has them.
  std::vector<std::vector<Pose>> linkPoses;
  for (std::size_t r = 0; r < world.robots().size(); ++r) {
    const WorldRobot& robot = world.robots()[r];
    linkPoses.emplace_back(robot.collision.model().links().size());
    robot.collision.model().linkPoses(
        path.context ? path.context->robots[r].configuration : robot.home, linkPoses.back());
  }
  std::vector<Pose> worldPoses(parties.size());

  PathVerification result;
  result.samples = samples.size();
  result.pairs = pairs.size();
  double smallest = std::numeric_limits<double>::infinity();
  // Per pair, the collision it is part of at the previous sample.
  std::vector<std::optional<std::size_t>> runOfPair(pairs.size());
  const std::size_t progressEvery = std::max<std::size_t>(1, samples.size() / 100);
  for (std::size_t s = 0; s < samples.size(); ++s) {
    if (options.progress && s % progressEvery == 0) options.progress(s, samples.size());
    const std::vector<double> q = configurationAt(path, samples[s]);
    for (const RobotSlice& slice : slices) {
      const RobotModel& model = world.robots()[slice.robot].collision.model();
      model.linkPoses(
          std::span<const double>(q.data() + slice.offset, static_cast<std::size_t>(model.dof())),
          linkPoses[slice.robot]);
    }
    for (std::size_t p = 0; p < parties.size(); ++p) {
      const CheckedParty& party = parties[p];
      worldPoses[p] = party.robot ? world.robots()[*party.robot].collision.basePose() *
                                        linkPoses[*party.robot][party.link] * party.inLink
                                  : party.scenePose;
    }
    for (std::size_t i = 0; i < pairs.size(); ++i) {
      const auto [a, b] = pairs[i];
      const Proximity proximity = geometry.proximity(parties[a].body, worldPoses[a],
                                                     parties[b].body, worldPoses[b], smallest);
      if (proximity.collides) {
        if (runOfPair[i]) {  // it collided at the previous sample too
          PathCollision& run = result.collisions[*runOfPair[i]];
          run.to = samples[s];
          ++run.samples;
        } else {
          runOfPair[i] = result.collisions.size();
          result.collisions.push_back(
              {parties[a].name, parties[b].name, samples[s], samples[s], 1});
        }
      } else {
        runOfPair[i].reset();
      }
      if (proximity.distance < smallest) {  // 0 for a collision
        smallest = proximity.distance;
        result.clearance = Clearance{smallest, parties[a].name, parties[b].name, samples[s]};
      }
    }
  }
  if (options.progress) options.progress(samples.size(), samples.size());
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

nlohmann::json toJson(const PathVerification& verification) {
  nlohmann::json clearance = nullptr;
  if (verification.clearance) {
    const Clearance& c = *verification.clearance;
    clearance = {{"distance", c.distance},
                 {"first", partyJson(c.first)},
                 {"second", partyJson(c.second)},
                 {"segment", c.where.segment},
                 {"fraction", c.where.fraction}};
  }
  nlohmann::json collisions = nlohmann::json::array();
  for (const PathCollision& collision : verification.collisions) {
    collisions.push_back({{"first", partyJson(collision.first)},
                          {"second", partyJson(collision.second)},
                          {"from", placeJson(collision.from)},
                          {"to", placeJson(collision.to)},
                          {"samples", collision.samples}});
  }
  return {{"collision_free", verification.collisionFree()},
          {"samples", verification.samples},
          {"pairs", verification.pairs},
          {"clearance", clearance},
          {"collisions", collisions},
          {"seconds", verification.seconds}};
}

}  // namespace kaboum::verify
