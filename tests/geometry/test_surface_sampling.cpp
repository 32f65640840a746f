#include <gtest/gtest.h>

#include "kaboum/geometry/surface_sampling.hpp"
#include "kaboum/geometry/triangle_bvh.hpp"
#include "kaboum/testing/test_shapes.hpp"

namespace kaboum::geometry {

using namespace kaboum::testing;

namespace {

TEST(SampleSurface, VerticesThenEdgeMidpointsThenRandomPoints) {
  const TriangleMesh sphere = makeIcosphere(2);  // 162 vertices, 480 edges, 320 triangles
  const std::vector<Vec3> samples = sampleSurface(sphere, 1000, 1);
  ASSERT_EQ(samples.size(), 162u + 480u + 1000u);
  for (std::size_t i = 0; i < 162; ++i) EXPECT_EQ(samples[i], sphere.vertices[i]);
  EXPECT_EQ(sampleSurface(makeBox(Vec3::Zero(), Vec3::Ones()), 0, 1).size(), 8u + 18u);
}

TEST(SampleSurface, SkipsUnusedVertices) {
  TriangleMesh box = makeBox(Vec3::Zero(), Vec3::Ones());
  box.vertices.emplace_back(50, 50, 50);
  const std::vector<Vec3> samples = sampleSurface(box, 10, 1);
  EXPECT_EQ(samples.size(), 8u + 18u + 10u);
  for (const Vec3& s : samples) EXPECT_LE(s.maxCoeff(), 1.0);
}

TEST(SampleSurface, EverySampleLiesOnTheSurface) {
  const TriangleMesh torus = makeTorus(1.0, 0.3, 30, 15);
  const TriangleBvh bvh(torus);
  for (const Vec3& s : sampleSurface(torus, 2000, 4)) EXPECT_LT(bvh.closest(s).distance, 1e-12);
}

TEST(SampleSurface, IsDeterministicForASeed) {
  const TriangleMesh prism = makeLPrism();
  const std::vector<Vec3> first = sampleSurface(prism, 500, 42);
  EXPECT_EQ(first, sampleSurface(prism, 500, 42));
  const std::vector<Vec3> other = sampleSurface(prism, 500, 43);
  ASSERT_EQ(other.size(), first.size());
  const std::size_t fixed = first.size() - 500;
  EXPECT_TRUE(std::equal(first.begin(), first.begin() + fixed, other.begin()));
  EXPECT_FALSE(std::equal(first.begin() + fixed, first.end(), other.begin() + fixed));
}

TEST(SampleSurface, WeightsTrianglesByArea) {
  // Two disjoint triangles of area 0.5 and 1.5 (at x = 0 and x = 10).
  TriangleMesh mesh;
  mesh.vertices = {Vec3(0, 0, 0),  Vec3(0, 1, 0),  Vec3(0, 0, 1),
                   Vec3(10, 0, 0), Vec3(10, 3, 0), Vec3(10, 0, 1)};
  mesh.triangles = {{0, 1, 2}, {3, 4, 5}};
  constexpr std::size_t kCount = 40000;
  const std::vector<Vec3> samples = sampleSurface(mesh, kCount, 8);
  std::size_t onLarge = 0;
  Vec3 largeSum = Vec3::Zero();
  for (std::size_t i = samples.size() - kCount; i < samples.size(); ++i) {
    if (samples[i].x() > 5) {
      ++onLarge;
      largeSum += samples[i];
    }
  }
  // Binomial standard deviation sqrt(n p (1 - p)) = 87 samples: 5 sigma is about 0.011.
  EXPECT_NEAR(static_cast<double>(onLarge) / kCount, 0.75, 0.011);
  // Uniform inside the triangle: the mean is the centroid.
  EXPECT_LT((largeSum / static_cast<double>(onLarge) - Vec3(10, 1, 1.0 / 3)).norm(), 0.02);
}

TEST(SampleSurface, ZeroAreaTrianglesGetNoRandomPoints) {
  TriangleMesh mesh;
  mesh.vertices = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0),
                   Vec3(5, 5, 5), Vec3(6, 6, 6), Vec3(7, 7, 7)};
  mesh.triangles = {{3, 4, 5}, {0, 1, 2}, {5, 4, 3}};
  const std::vector<Vec3> samples = sampleSurface(mesh, 3000, 2);
  ASSERT_EQ(samples.size(), 6u + 6u + 3000u);
  for (std::size_t i = 12; i < samples.size(); ++i) ASSERT_LT(samples[i].norm(), 1.5);

  TriangleMesh flat;
  flat.vertices = {Vec3(0, 0, 0), Vec3(1, 1, 1), Vec3(2, 2, 2)};
  flat.triangles = {{0, 1, 2}};
  EXPECT_EQ(sampleSurface(flat, 100, 1).size(), 3u + 3u);
}

TEST(SurfaceSampler, MakesTheSamplesOfSampleSurfaceOneAtATime) {
  const TriangleMesh torus = makeTorus(1.0, 0.3, 12, 8);
  const std::vector<Vec3> all = sampleSurface(torus, 700, 9);
  SurfaceSampler sampler(torus, 700, 9);
  std::vector<Vec3> streamed;
  for (Vec3 sample; sampler.next(sample);) {
    streamed.push_back(sample);
    EXPECT_EQ(sampler.produced(), streamed.size());
  }
  EXPECT_EQ(streamed, all);
  Vec3 past = Vec3::Constant(7.0);
  EXPECT_FALSE(sampler.next(past));  // stays exhausted
  EXPECT_EQ(past, Vec3::Constant(7.0));
  EXPECT_EQ(sampler.produced(), all.size());
}

TEST(SurfaceSampler, ResumesWhereItStopped) {
  // A measurement that stops after a few samples of each stage and later goes on sees the same
  // sequence as one that reads them all at once.
  const TriangleMesh prism = makeLPrism();
  const std::vector<Vec3> all = sampleSurface(prism, 50, 3);
  SurfaceSampler sampler(prism, 50, 3);
  std::vector<Vec3> streamed;
  for (const std::size_t stop : {std::size_t{3}, all.size() - 60, all.size() - 20, all.size()}) {
    for (Vec3 sample; streamed.size() < stop && sampler.next(sample);) streamed.push_back(sample);
  }
  EXPECT_EQ(streamed, all);

  TriangleMesh flat;  // no area: vertices and edge midpoints only
  flat.vertices = {Vec3(0, 0, 0), Vec3(1, 1, 1), Vec3(2, 2, 2)};
  flat.triangles = {{0, 1, 2}};
  SurfaceSampler flatSampler(flat, 100, 1);
  std::size_t count = 0;
  for (Vec3 sample; flatSampler.next(sample);) ++count;
  EXPECT_EQ(count, 6u);
  const TriangleMesh nothing;
  SurfaceSampler empty(nothing, 10, 1);
  Vec3 none;
  EXPECT_FALSE(empty.next(none));
  EXPECT_EQ(empty.produced(), 0u);
}

}  // namespace
}  // namespace kaboum::geometry
