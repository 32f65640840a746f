#include "kaboum/motion/motion_planner.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <random>
#include <stdexcept>

#include "kaboum/kinematics/random_configuration.hpp"
#include "kaboum/motion/ompl_planner.hpp"
#include "kaboum/motion/world_checkers.hpp"

namespace kaboum::motion {

namespace {

// The smallest sweep ε a query falls back to when an end is close to an obstacle, as a fraction
// of the asked one.
constexpr double kSmallestSweepFraction = 1.0 / 16;

using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

double distance(std::span<const double> a, std::span<const double> b) {
  double sum = 0;
  for (std::size_t i = 0; i < a.size(); ++i) sum += (a[i] - b[i]) * (a[i] - b[i]);
  return std::sqrt(sum);
}

std::vector<double> interpolate(std::span<const double> a, std::span<const double> b, double t) {
  std::vector<double> q(a.size());
  for (std::size_t i = 0; i < a.size(); ++i) q[i] = a[i] + t * (b[i] - a[i]);
  return q;
}

// The verdicts of the last kCapacity distinct segments, wrapped around a validator: pruning and
// shortcutting ask again about segments they or the straight-segment try already decided (the
// start-goal segment, pairs of waypoints the pruning re-tries after shortcutting, the final
// certification). The wrapped validator's verdict does not depend on the direction
// (docs/motion.md), so a segment is remembered in either direction. Allocates nothing once its
// buffer is full.
class RememberedVerdicts final : public MotionValidator {
 public:
  RememberedVerdicts(MotionValidator& motions, std::size_t dimension)
      : motions_(motions), dimension_(dimension) {}

  [[nodiscard]] bool isValid(std::span<const double> from, std::span<const double> to) override {
    const std::size_t count = verdicts_.size();
    for (std::size_t e = 0; e < count; ++e) {
      const std::span<const double> a(ends_.data() + 2 * e * dimension_, dimension_);
      const std::span<const double> b(ends_.data() + (2 * e + 1) * dimension_, dimension_);
      if ((std::ranges::equal(a, from) && std::ranges::equal(b, to)) ||
          (std::ranges::equal(a, to) && std::ranges::equal(b, from))) {
        return verdicts_[e];
      }
    }
    const bool valid = motions_.isValid(from, to);
    if (count < kCapacity) {
      ends_.resize(2 * (count + 1) * dimension_);
      verdicts_.push_back(valid);
    }
    const std::size_t e = count < kCapacity ? count : next_;
    next_ = (e + 1) % kCapacity;
    std::ranges::copy(from, ends_.begin() + static_cast<std::ptrdiff_t>(2 * e * dimension_));
    std::ranges::copy(to, ends_.begin() + static_cast<std::ptrdiff_t>((2 * e + 1) * dimension_));
    verdicts_[e] = valid;
    return valid;
  }

 private:
  static constexpr std::size_t kCapacity = 64;
  MotionValidator& motions_;
  std::size_t dimension_;
  std::vector<double> ends_;  // from and to of each remembered segment
  std::vector<bool> verdicts_;
  std::size_t next_ = 0;  // the entry replaced next once full
};

// Drops waypoints the straight motion can skip: from each kept waypoint, the farthest later one
// it reaches by a certified segment.
void pruneWaypoints(Waypoints& path, MotionValidator& motions) {
  Waypoints kept{path.front()};
  std::size_t from = 0;
  while (from + 1 < path.size()) {
    std::size_t to = path.size() - 1;
    while (to > from + 1 && !motions.isValid(path[from], path[to])) --to;
    kept.push_back(path[to]);
    from = to;
  }
  path = std::move(kept);
}

// Random partial shortcuts: two points on different segments joined by a certified segment
// replace the path between them when that is shorter. Stops after kFruitlessAttempts attempts in a
// row that shorten nothing: the path is then close to what shortcutting reaches.
void shortcut(Waypoints& path, MotionValidator& motions, int attempts, std::uint64_t seed) {
  constexpr int kFruitlessAttempts = 5;
  int fruitless = 0;
  std::mt19937_64 rng(seed);
  const auto randomSegment = [&] {
    return static_cast<std::size_t>(uniformUnit(rng) * static_cast<double>(path.size() - 1));
  };
  for (int attempt = 0; attempt < attempts && path.size() > 2 && fruitless < kFruitlessAttempts;
       ++attempt) {
    ++fruitless;
    std::size_t i = randomSegment(), j = randomSegment();
    if (i > j) std::swap(i, j);
    const std::vector<double> a = interpolate(path[i], path[i + 1], uniformUnit(rng));
    const std::vector<double> b = interpolate(path[j], path[j + 1], uniformUnit(rng));
    if (j == i) continue;
    double along = distance(a, path[i + 1]) + distance(path[j], b);
    for (std::size_t k = i + 1; k < j; ++k) along += distance(path[k], path[k + 1]);
    // The pieces kept of segments i and j are certified on their own: a part of a certified
    // motion is not certified by it (its swept volume is bounded afresh).
    if (distance(a, b) >= along || !motions.isValid(a, b) || !motions.isValid(path[i], a) ||
        !motions.isValid(b, path[j + 1])) {
      continue;
    }
    Waypoints shorter(path.begin(), path.begin() + static_cast<std::ptrdiff_t>(i + 1));
    shorter.push_back(a);
    shorter.push_back(b);
    shorter.insert(shorter.end(), path.begin() + static_cast<std::ptrdiff_t>(j + 1), path.end());
    path = std::move(shorter);
    fruitless = 0;
  }
}

bool certified(const Waypoints& path, MotionValidator& motions) {
  for (std::size_t i = 0; i + 1 < path.size(); ++i) {
    if (!motions.isValid(path[i], path[i + 1])) return false;
  }
  return true;
}

}  // namespace

std::unique_ptr<MotionValidator> motionValidator(const MotionGroup& group, double sweepEpsilon,
                                                 CheckStatistics* statistics) {
  if (group.world().predicates() != nullptr) {
    const SceneSettings& settings = group.world().description().settings;
    return std::make_unique<DiscreteMotionValidator>(group, settings.jointStep, settings.toolStep,
                                                     statistics);
  }
  return std::make_unique<SweptMotionValidator>(group, sweepEpsilon, statistics);
}

double sweepEpsilonOf(const MotionGroup& group, const MotionOptions& options) {
  return options.sweepEpsilon.value_or(group.world().description().settings.sweepEpsilon);
}

std::optional<std::string> configurationProblem(const MotionGroup& group, std::span<const double> q,
                                                double clearance) {
  const std::size_t outside = group.firstOutsideLimits(q);
  if (outside < group.dimension()) {
    return fmt::format("{} is {:g}, outside its limits [{:g}, {:g}]", group.coordinateName(outside),
                       q[outside], group.lower()[outside], group.upper()[outside]);
  }
  const World& world = group.world();
  GeometricState state = group.context();
  group.assign(q, state);
  if (const auto collision = world.firstCollision(state)) return world.describe(*collision);
  WorldStateChecker states(group, clearance);
  if (const auto close = states.firstCollision(q)) {
    return fmt::format("{} and {} are closer than the {:g} m that certified motions keep",
                       world.describe(close->first), world.describe(close->second), clearance);
  }
  return std::nullopt;
}

std::optional<std::vector<double>> randomFreeConfiguration(const MotionGroup& group,
                                                           double clearance, std::mt19937_64& rng,
                                                           int draws) {
  std::vector<double> q(group.dimension());
  for (int draw = 0; draw < draws; ++draw) {
    for (std::size_t i = 0; i < q.size(); ++i) {
      q[i] =
          group.lower()[i] + kinematics::uniformUnit(rng) * (group.upper()[i] - group.lower()[i]);
    }
    if (!configurationProblem(group, q, clearance)) return q;
  }
  return std::nullopt;
}

double pathLength(const Waypoints& path) {
  double length = 0;
  for (std::size_t i = 0; i + 1 < path.size(); ++i) length += distance(path[i], path[i + 1]);
  return length;
}

QueryEpsilon sweepEpsilonForEnds(const MotionGroup& group, std::span<const double> start,
                                 std::span<const double> goal, const MotionOptions& options) {
  if (const auto problem = configurationProblem(group, start, 0.0)) {
    return {0, PlannerStatus::InvalidStart, "start: " + *problem};
  }
  if (const auto problem = configurationProblem(group, goal, 0.0)) {
    return {0, PlannerStatus::InvalidGoal, "goal: " + *problem};
  }
  const double smallest = kSmallestSweepFraction * sweepEpsilonOf(group, options);
  double epsilon = sweepEpsilonOf(group, options);
  for (;;) {
    const auto startProblem = configurationProblem(group, start, epsilon);
    const auto goalProblem = configurationProblem(group, goal, epsilon);
    if (!startProblem && !goalProblem) return {epsilon, PlannerStatus::Solved, {}};
    if (epsilon > smallest) {
      epsilon *= 0.5;
    } else if (startProblem) {
      return {0, PlannerStatus::InvalidStart, "start: " + *startProblem};
    } else {
      return {0, PlannerStatus::InvalidGoal, "goal: " + *goalProblem};
    }
  }
}

MotionResult planMotion(const MotionGroup& group, std::span<const double> start,
                        std::span<const double> goal, const MotionOptions& options) {
  MotionQuery query;
  if (start.size() != group.dimension() || goal.size() != group.dimension()) {
    throw std::invalid_argument("start and goal need " + std::to_string(group.dimension()) +
                                " joint values");
  }
  MotionResult& result = query.result;
  MotionStatistics& statistics = result.statistics;
  const QueryEpsilon ends = sweepEpsilonForEnds(group, start, goal, options);
  if (ends.status != PlannerStatus::Solved) return query.finish(ends.status, ends.problem);
  const double epsilon = ends.epsilon;
  statistics.sweepEpsilon = epsilon;
  WorldStateChecker states(group, epsilon, &statistics.checks);
  const std::unique_ptr<MotionValidator> certifier =
      motionValidator(group, epsilon, &statistics.checks);
  RememberedVerdicts motions(*certifier, group.dimension());
  if (motions.isValid(start, goal)) {
    statistics.straight = true;
    result.path = {{start.begin(), start.end()}, {goal.begin(), goal.end()}};
    statistics.plannedWaypoints = 2;
    statistics.plannedLength = statistics.length = pathLength(result.path);
    return query.finish(PlannerStatus::Solved);
  }
  const Clock::time_point planning = Clock::now();
  SamplingResult sampled = planWithOmpl(group, states, *certifier, start, goal, options,
                                        options.timeLimit - query.elapsedSeconds());
  statistics.planningSeconds = secondsSince(planning);
  if (sampled.status != PlannerStatus::Solved) {
    return query.finish(sampled.status, "no path found by " + options.planner + " within " +
                                            std::to_string(options.timeLimit) + " s");
  }
  result.path = std::move(sampled.path);
  statistics.plannedWaypoints = result.path.size();
  statistics.plannedLength = pathLength(result.path);
  const Clock::time_point shortcutting = Clock::now();
  pruneWaypoints(result.path, motions);
  shortcut(result.path, motions, options.shortcutAttempts, options.seed);
  pruneWaypoints(result.path, motions);
  if (!certified(result.path, motions)) {
    throw std::logic_error("a shortcut path failed its final certification");
  }
  statistics.shortcutSeconds = secondsSince(shortcutting);
  statistics.length = pathLength(result.path);
  return query.finish(PlannerStatus::Solved);
}

}  // namespace kaboum::motion
