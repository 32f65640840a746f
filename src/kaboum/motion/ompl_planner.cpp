#include "kaboum/motion/ompl_planner.hpp"

#include <ompl/base/MotionValidator.h>
#include <ompl/base/PlannerTerminationCondition.h>
#include <ompl/base/ProblemDefinition.h>
#include <ompl/base/ScopedState.h>
#include <ompl/base/SpaceInformation.h>
#include <ompl/base/StateSampler.h>
#include <ompl/base/StateValidityChecker.h>
#include <ompl/base/spaces/RealVectorStateSpace.h>
#include <ompl/geometric/PathGeometric.h>
#include <ompl/geometric/planners/est/BiEST.h>
#include <ompl/geometric/planners/est/EST.h>
#include <ompl/geometric/planners/prm/PRM.h>
#include <ompl/geometric/planners/rrt/RRT.h>
#include <ompl/geometric/planners/rrt/RRTConnect.h>
#include <ompl/geometric/planners/rrt/RRTstar.h>
#include <ompl/util/Console.h>

#include <functional>
#include <map>
#include <random>
#include <stdexcept>

#include "kaboum/kinematics/random_configuration.hpp"

namespace kaboum::motion {

namespace ob = ompl::base;
namespace og = ompl::geometric;

namespace {

using RealState = ob::RealVectorStateSpace::StateType;

std::span<const double> valuesOf(const ob::State* state, std::size_t dimension) {
  return {state->as<RealState>()->values, dimension};
}

// Uniform, near and Gaussian samples from kaboum's seeded generator instead of OMPL's global one.
class SeededSampler final : public ob::StateSampler {
 public:
  SeededSampler(const ob::StateSpace* space, std::uint64_t seed)
      : ob::StateSampler(space),
        bounds_(space->as<ob::RealVectorStateSpace>()->getBounds()),
        rng_(seed) {}

  void sampleUniform(ob::State* state) override {
    double* q = state->as<RealState>()->values;
    for (std::size_t i = 0; i < bounds_.low.size(); ++i) {
      q[i] = bounds_.low[i] + uniformUnit(rng_) * (bounds_.high[i] - bounds_.low[i]);
    }
  }
  void sampleUniformNear(ob::State* state, const ob::State* near, double distance) override {
    double* q = state->as<RealState>()->values;
    const double* centre = near->as<RealState>()->values;
    for (std::size_t i = 0; i < bounds_.low.size(); ++i) {
      const double lo = std::max(bounds_.low[i], centre[i] - distance);
      const double hi = std::min(bounds_.high[i], centre[i] + distance);
      q[i] = lo + uniformUnit(rng_) * (hi - lo);
    }
  }
  void sampleGaussian(ob::State* state, const ob::State* mean, double stdDev) override {
    double* q = state->as<RealState>()->values;
    const double* centre = mean->as<RealState>()->values;
    for (std::size_t i = 0; i < bounds_.low.size(); ++i) {
      // Box–Muller from two uniform draws, so that the sample is platform-independent.
      const double u = std::max(uniformUnit(rng_), 1e-300);
      const double v = uniformUnit(rng_);
      const double normal = std::sqrt(-2 * std::log(u)) * std::cos(2 * std::numbers::pi * v);
      q[i] = std::clamp(centre[i] + stdDev * normal, bounds_.low[i], bounds_.high[i]);
    }
  }

 private:
  ob::RealVectorBounds bounds_;
  std::mt19937_64 rng_;
};

class ValidityAdapter final : public ob::StateValidityChecker {
 public:
  ValidityAdapter(const ob::SpaceInformationPtr& si, motion::StateValidityChecker& checker,
                  std::size_t dimension)
      : ob::StateValidityChecker(si), checker_(checker), dimension_(dimension) {}
  bool isValid(const ob::State* state) const override {
    return checker_.isValid(valuesOf(state, dimension_));
  }

 private:
  motion::StateValidityChecker& checker_;
  std::size_t dimension_;
};

class MotionAdapter final : public ob::MotionValidator {
 public:
  MotionAdapter(const ob::SpaceInformationPtr& si, motion::MotionValidator& validator,
                std::size_t dimension)
      : ob::MotionValidator(si), validator_(validator), dimension_(dimension) {}

  bool checkMotion(const ob::State* s1, const ob::State* s2) const override {
    const bool valid = validator_.isValid(valuesOf(s1, dimension_), valuesOf(s2, dimension_));
    ++(valid ? valid_ : invalid_);
    return valid;
  }
  // The last valid state: the last of kScanSamples evenly spaced states before the first invalid
  // one (cheap state checks), then the longest certified prefix up to it, halving it at most
  // kCertifyTries times (each try one sweep).
  bool checkMotion(const ob::State* s1, const ob::State* s2,
                   std::pair<ob::State*, double>& lastValid) const override {
    if (checkMotion(s1, s2)) return true;
    ob::State* probe = si_->allocState();
    double reach = 0;
    for (int k = 1; k <= kScanSamples; ++k) {
      const double t = static_cast<double>(k) / kScanSamples;
      si_->getStateSpace()->interpolate(s1, s2, t, probe);
      if (!si_->isValid(probe)) break;
      reach = t;
    }
    double good = 0;
    for (int attempt = 0; attempt < kCertifyTries && reach > 0 && good == 0; ++attempt) {
      si_->getStateSpace()->interpolate(s1, s2, reach, probe);
      if (validator_.isValid(valuesOf(s1, dimension_), valuesOf(probe, dimension_))) good = reach;
      reach *= 0.5;
    }
    if (lastValid.first != nullptr) {
      si_->getStateSpace()->interpolate(s1, s2, good, lastValid.first);
    }
    lastValid.second = good;
    si_->freeState(probe);
    return false;
  }

 private:
  static constexpr int kScanSamples = 16;
  static constexpr int kCertifyTries = 3;
  motion::MotionValidator& validator_;
  std::size_t dimension_;
};

// An OMPL planner whose own generator (goal bias, roadmap choices) is seeded too.
template <class Planner>
class Seeded final : public Planner {
 public:
  Seeded(const ob::SpaceInformationPtr& si, std::uint64_t seed) : Planner(si) {
    this->rng_.setLocalSeed(static_cast<std::uint_fast32_t>(seed));
  }
};

using PlannerFactory = std::function<ob::PlannerPtr(const ob::SpaceInformationPtr&, std::uint64_t)>;

template <class Planner>
PlannerFactory factory() {
  return [](const ob::SpaceInformationPtr& si, std::uint64_t seed) {
    return std::make_shared<Seeded<Planner>>(si, seed);
  };
}

const std::map<std::string, PlannerFactory>& planners() {
  static const std::map<std::string, PlannerFactory> factories = {
      {"rrtconnect", factory<og::RRTConnect>()}, {"rrt", factory<og::RRT>()},
      {"rrtstar", factory<og::RRTstar>()},       {"est", factory<og::EST>()},
      {"biest", factory<og::BiEST>()},           {"prm", factory<og::PRM>()},
  };
  return factories;
}

}  // namespace

const std::vector<std::string>& motionPlannerNames() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> all;
    for (const auto& [name, make] : planners()) all.push_back(name);
    return all;
  }();
  return names;
}

SamplingResult planWithOmpl(const MotionGroup& group, StateValidityChecker& states,
                            MotionValidator& motions, std::span<const double> start,
                            std::span<const double> goal, const MotionOptions& options,
                            double seconds) {
  const auto found = planners().find(options.planner);
  if (found == planners().end()) {
    throw std::invalid_argument("unknown motion planner '" + options.planner + "'");
  }
  ompl::msg::setLogLevel(ompl::msg::LOG_NONE);
  const std::size_t dimension = group.dimension();
  auto space = std::make_shared<ob::RealVectorStateSpace>(static_cast<unsigned>(dimension));
  ob::RealVectorBounds bounds(static_cast<unsigned>(dimension));
  bounds.low = group.lower();
  bounds.high = group.upper();
  space->setBounds(bounds);
  const std::uint64_t seed = options.seed;
  space->setStateSamplerAllocator([seed](const ob::StateSpace* s) -> ob::StateSamplerPtr {
    return std::make_shared<SeededSampler>(s, seed);
  });
  auto si = std::make_shared<ob::SpaceInformation>(space);
  si->setStateValidityChecker(std::make_shared<ValidityAdapter>(si, states, dimension));
  si->setMotionValidator(std::make_shared<MotionAdapter>(si, motions, dimension));
  si->setup();

  ob::ScopedState<ob::RealVectorStateSpace> startState(space), goalState(space);
  for (std::size_t i = 0; i < dimension; ++i) {
    startState[static_cast<unsigned>(i)] = start[i];
    goalState[static_cast<unsigned>(i)] = goal[i];
  }
  auto problem = std::make_shared<ob::ProblemDefinition>(si);
  problem->setStartAndGoalStates(startState, goalState);
  const ob::PlannerPtr planner = found->second(si, seed + 1);
  if (options.range > 0 && planner->params().hasParam("range")) {
    planner->params().setParam("range", std::to_string(options.range));
  }
  planner->setProblemDefinition(problem);
  planner->setup();

  const std::atomic<bool>* cancel = options.cancel;
  const ob::PlannerTerminationCondition stop = ob::plannerOrTerminationCondition(
      ob::timedPlannerTerminationCondition(seconds), ob::PlannerTerminationCondition([cancel] {
        return cancel != nullptr && cancel->load(std::memory_order_relaxed);
      }));
  const ob::PlannerStatus status = planner->solve(stop);
  SamplingResult result;
  if (status != ob::PlannerStatus::EXACT_SOLUTION) {
    const bool cancelled = cancel != nullptr && cancel->load(std::memory_order_relaxed);
    result.status = cancelled ? PlannerStatus::Cancelled : PlannerStatus::TimeLimit;
    return result;
  }
  auto* path = problem->getSolutionPath()->as<og::PathGeometric>();
  for (const ob::State* state : path->getStates()) {
    const std::span<const double> q = valuesOf(state, dimension);
    result.path.emplace_back(q.begin(), q.end());
  }
  result.status = PlannerStatus::Solved;
  return result;
}

}  // namespace kaboum::motion
