// Time parameterisation (thesis §6.1.3) on the certified paths of a real plan: rest-to-rest
// quintics stay on the straight segments between waypoints and within every joint's limits, and
// reach a limit (the shortest such timing); blended quintics pass through every waypoint with
// continuous velocity and acceleration, within the limits, in less time, and their deviation from
// the path is measured.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "exec_fixtures.hpp"

namespace kaboum::exec {

namespace {

// Every motion of the pick-and-place plan with its robot's limits from the scene and URDF.
struct Motion {
  std::vector<std::vector<double>> waypoints;
  JointLimits limits;
};

std::vector<Motion> planMotions() {
  ExampleRun& run = pickAndPlace();
  const std::vector<JointLimits> limits = jointLimits(run.world(), {});
  std::vector<Motion> motions;
  for (const auto& node : run.plan().geometry) {
    for (const tamp::ActionGeometry& effect : node) {
      for (const tamp::GeometricStep& step : effect.steps) {
        if (!step.path.empty()) motions.push_back({step.path, limits[step.robot]});
      }
    }
  }
  return motions;
}

// Samples `path` every `step` seconds (and at its end) and calls `check(t, q, qd, qdd)`.
template <typename Check>
void sampleDensely(const TimedPath& path, double step, Check check) {
  std::vector<double> q(path.dof()), qd(path.dof()), qdd(path.dof());
  const auto steps = static_cast<std::size_t>(std::floor(path.duration() / step));
  for (std::size_t k = 0; k <= steps + 1; ++k) {
    const double t = std::min(static_cast<double>(k) * step, path.duration());
    path.sample(t, q, qd, qdd);
    check(t, q, qd, qdd);
  }
}

// The largest |qd_j| / v_j and |qdd_j| / a_j over dense samples.
std::pair<double, double> peakRatios(const TimedPath& path, const JointLimits& limits) {
  double velocity = 0;
  double acceleration = 0;
  sampleDensely(path, 1e-4, [&](double, const auto&, const auto& qd, const auto& qdd) {
    for (std::size_t j = 0; j < qd.size(); ++j) {
      velocity = std::max(velocity, std::abs(qd[j]) / limits.velocity[j]);
      acceleration = std::max(acceleration, std::abs(qdd[j]) / limits.acceleration[j]);
    }
  });
  return {velocity, acceleration};
}

}  // namespace

TEST(Trajectory, LimitsComeFromTheSceneAndTheUrdf) {
  const std::vector<JointLimits> limits = jointLimits(pickAndPlace().world(), {});
  ASSERT_EQ(limits.size(), 1U);
  ASSERT_EQ(limits[0].velocity.size(), 6U);
  // The KR5's URDF gives velocities; it gives no accelerations, so the default holds.
  for (std::size_t j = 0; j < 6; ++j) {
    EXPECT_GT(limits[0].velocity[j], 0);
    EXPECT_EQ(limits[0].acceleration[j], TrajectoryOptions{}.defaultAcceleration);
  }
}

TEST(Trajectory, RestToRestSamplesLieOnTheCertifiedPath) {
  const std::vector<Motion> motions = planMotions();
  ASSERT_EQ(motions.size(), 6U) << "transit, approach, retreat; transfer, approach, retreat";
  std::size_t samples = 0;
  for (const Motion& motion : motions) {
    const TimedPath path(motion.waypoints, motion.limits, Profile::RestToRest);
    ASSERT_GT(path.duration(), 0);
    sampleDensely(path, 1e-4, [&](double, const auto& q, const auto&, const auto&) {
      ++samples;
      ASSERT_LE(distanceToPath(q, motion.waypoints), 1e-9);
    });
    EXPECT_LE(pathDeviation(path, 1e-3), 1e-9);
  }
  EXPECT_GT(samples, 10000U);
}

TEST(Trajectory, RestToRestStopsAtEveryWaypointAndIsTheShortestWithinTheLimits) {
  for (const Motion& motion : planMotions()) {
    const TimedPath path(motion.waypoints, motion.limits, Profile::RestToRest);
    const auto [velocity, acceleration] = peakRatios(path, motion.limits);
    EXPECT_LE(velocity, 1 + 1e-9);
    EXPECT_LE(acceleration, 1 + 1e-9);
    // Some joint of the slowest segment reaches a limit (sampling finds the peak within 1e-6).
    EXPECT_GT(std::max(velocity, acceleration), 1 - 1e-6);
    std::vector<double> q(path.dof()), qd(path.dof()), qdd(path.dof());
    double start = 0;
    for (std::size_t i = 0; i < path.durations().size(); ++i) {
      path.sample(start, q, qd, qdd);
      for (std::size_t j = 0; j < q.size(); ++j) {
        EXPECT_NEAR(q[j], path.waypoints()[i][j], 1e-12);
        EXPECT_NEAR(qd[j], 0, 1e-12);
        EXPECT_NEAR(qdd[j], 0, 1e-12);
      }
      start += path.durations()[i];
    }
    path.sample(path.duration(), q, qd, qdd);
    for (std::size_t j = 0; j < q.size(); ++j) {
      EXPECT_NEAR(q[j], path.waypoints().back()[j], 1e-12);
    }
  }
}

TEST(Trajectory, BlendedPassesThroughTheWaypointsSmoothlyWithinTheLimitsInLessTime) {
  double restToRest = 0;
  double blended = 0;
  double deviation = 0;
  for (const Motion& motion : planMotions()) {
    const TimedPath path(motion.waypoints, motion.limits, Profile::Blended);
    const TimedPath stopping(motion.waypoints, motion.limits, Profile::RestToRest);
    restToRest += stopping.duration();
    blended += path.duration();
    const auto [velocity, acceleration] = peakRatios(path, motion.limits);
    EXPECT_LE(velocity, 1 + 1e-6);
    EXPECT_LE(acceleration, 1 + 1e-6);
    EXPECT_GT(std::max(velocity, acceleration), 1 - 1e-3) << "the tightest limit is met";
    // At every via point: the waypoint, with the same velocity and acceleration on both sides.
    std::vector<double> q(path.dof()), qd(path.dof()), qdd(path.dof());
    std::vector<double> q2(path.dof()), qd2(path.dof()), qdd2(path.dof());
    double t = 0;
    for (std::size_t i = 0; i + 1 < path.durations().size(); ++i) {
      t += path.durations()[i];
      path.sample(t - 1e-9, q, qd, qdd);
      path.sample(t, q2, qd2, qdd2);
      for (std::size_t j = 0; j < q.size(); ++j) {
        EXPECT_NEAR(q2[j], path.waypoints()[i + 1][j], 1e-12);
        EXPECT_NEAR(qd[j], qd2[j], 1e-6);
        EXPECT_NEAR(qdd[j], qdd2[j], 1e-4);
      }
    }
    path.sample(path.duration(), q, qd, qdd);
    for (std::size_t j = 0; j < q.size(); ++j) {
      EXPECT_NEAR(q[j], path.waypoints().back()[j], 1e-12);
      EXPECT_NEAR(qd[j], 0, 1e-12);
    }
    deviation = std::max(deviation, pathDeviation(path, 1e-3));
  }
  EXPECT_LT(blended, restToRest);
  // Blending leaves the segments near the via points: measured, small against the path.
  EXPECT_GT(deviation, 1e-9);
  EXPECT_LT(deviation, 0.1);
}

TEST(Trajectory, APathOfOneConfigurationTakesNoTime) {
  const JointLimits limits{{1, 1}, {2, 2}};
  const TimedPath still({{0.5, 1}, {0.5, 1}}, limits, Profile::Blended);
  EXPECT_EQ(still.duration(), 0);
  std::vector<double> q(2), qd(2), qdd(2);
  still.sample(1, q, qd, qdd);
  EXPECT_EQ(q, (std::vector<double>{0.5, 1}));
  EXPECT_EQ(qd, (std::vector<double>{0, 0}));
}

TEST(Trajectory, BadPathsAndLimitsAreRejected) {
  const JointLimits limits{{1, 1}, {2, 2}};
  EXPECT_THROW(TimedPath({}, limits, Profile::RestToRest), std::invalid_argument);
  EXPECT_THROW(TimedPath({{0, 0}, {1}}, limits, Profile::RestToRest), std::invalid_argument);
  EXPECT_THROW(TimedPath({{0, 0}, {1, 1}}, {{1, 0}, {2, 2}}, Profile::RestToRest),
               std::invalid_argument);
  EXPECT_THROW(TimedPath({{0, 0, 0}}, limits, Profile::RestToRest), std::invalid_argument);
  EXPECT_EQ(profileNamed("blended"), Profile::Blended);
  EXPECT_THROW(profileNamed("trapezoid"), std::invalid_argument);
}

}  // namespace kaboum::exec
