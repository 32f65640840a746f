// Per-link sweep steps (Eq. 4.19): sampled vertices never leave the ε band around their chord.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "kaboum/collision/swept_step.hpp"
#include "kaboum/geometry/triangle_mesh.hpp"
#include "kaboum/io/urdf_loader.hpp"
#include "kaboum/kinematics/random_configuration.hpp"
#include "kaboum/testing/data_paths.hpp"

namespace kaboum::collision {

using namespace kaboum::geometry;
using namespace kaboum::kinematics;
using namespace kaboum::io;
using namespace kaboum::testing;

namespace {

const std::string kKr5 = kaboum::testing::kr5Urdf();
const std::string kComauLeft = kaboum::testing::dataFile("robots/comau-left.urdf");

Vec3 randomDirection(std::mt19937_64& rng) {
  std::normal_distribution<double> normal;
  Vec3 d(normal(rng), normal(rng), normal(rng));
  return d.normalized();
}

// Largest distance of points `radius` from each link origin to the chord of their path, over
// each of the n sub-steps that sweepSubdivisions() chose, relative to ε (must stay <= 1).
double worstDeviationRatio(const RobotModel& model, double radius, double epsilon, int motions,
                           std::uint64_t seed) {
  const auto chains = linkSweepChains(model);
  std::mt19937_64 rng(seed);
  std::vector<Pose> a(model.links().size()), b(model.links().size()), mid(model.links().size());
  double worst = 0;
  for (int m = 0; m < motions; ++m) {
    const auto qa = randomConfiguration(model, rng);
    auto qb = qa;  // a short random motion, so that n stays small enough to sample densely
    for (auto& value : qb) value += 0.3 * (2 * uniformUnit(rng) - 1);
    std::vector<Vec3> points(8);
    for (auto& p : points) p = radius * randomDirection(rng);
    for (std::size_t link = 0; link < chains.size(); ++link) {
      const int n = sweepSubdivisions(chains[link], qa, qb, radius, epsilon);
      for (int step = 0; step < n; ++step) {
        std::vector<double> q0(qa.size()), q1(qa.size()), qt(qa.size());
        const double t0 = double(step) / n, t1 = double(step + 1) / n;
        for (std::size_t v = 0; v < qa.size(); ++v) {
          q0[v] = qa[v] + t0 * (qb[v] - qa[v]);
          q1[v] = qa[v] + t1 * (qb[v] - qa[v]);
        }
        model.linkPoses(q0, a);
        model.linkPoses(q1, b);
        for (int k = 1; k < 16; ++k) {
          const double s = k / 16.0;
          for (std::size_t v = 0; v < qa.size(); ++v) qt[v] = q0[v] + s * (q1[v] - q0[v]);
          model.linkPoses(qt, mid);
          for (const Vec3& p : points) {
            const Vec3 chord = (1 - s) * (a[link] * p) + s * (b[link] * p);
            worst = std::max(worst, (mid[link] * p - chord).norm() / epsilon);
          }
        }
      }
    }
  }
  return worst;
}

TEST(SweptStep, Kr5VerticesStayWithinEpsilonOfTheirChords) {
  const RobotModel kr5 = loadUrdf(kKr5);
  const double ratio = worstDeviationRatio(kr5, 0.2, 0.002, 40, 1);
  EXPECT_LE(ratio, 1.0);
  EXPECT_GT(ratio, 0.2) << "the bound should not be wildly loose";
}

TEST(SweptStep, PrismaticFingersStayWithinEpsilonOfTheirChords) {
  const RobotModel comau = loadUrdf(kComauLeft);
  const auto chains = linkSweepChains(comau);
  bool hasBentPrismatic = false;
  for (const auto& chain : chains) hasBentPrismatic |= !chain.bentPrismaticVariables.empty();
  ASSERT_TRUE(hasBentPrismatic);
  EXPECT_LE(worstDeviationRatio(comau, 0.1, 0.002, 20, 2), 1.0);
}

// For one joint and a point in the plane normal to the axis, Eq. 4.19 is exact: one sub-step
// fewer than chosen leaves the ε band.
TEST(SweptStep, SingleJointStepIsTight) {
  const std::string urdf = R"(<robot name="one">
    <link name="base"/><link name="arm"/>
    <joint name="j" type="revolute"><parent link="base"/><child link="arm"/>
      <axis xyz="0 0 1"/><limit lower="-3" upper="3" effort="1" velocity="1"/></joint>
  </robot>)";
  const RobotModel model = parseUrdf(urdf, "one.urdf", ".");
  const auto chains = linkSweepChains(model);
  const double r = 0.5, epsilon = 1e-3;
  const std::vector<double> qa{-1.0}, qb{1.3};
  const int n = sweepSubdivisions(chains[1], qa, qb, r, epsilon);
  ASSERT_GT(n, 1);
  const auto deviation = [&](int steps) { return r * (1 - std::cos(2.3 / steps / 2)); };
  EXPECT_LE(deviation(n), epsilon);
  EXPECT_GT(deviation(n - 1), epsilon);
  EXPECT_EQ(sweepSubdivisions(chains[0], qa, qb, r, epsilon), 1) << "the base does not move";
}

}  // namespace
}  // namespace kaboum::collision
