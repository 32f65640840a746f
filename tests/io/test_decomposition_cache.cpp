// The decomposition cache on disk (§6.1.1 pre-processing kept between runs): hits equal to the
// decompositions they replace, keys that change with the mesh and the options, corrupt entries
// rebuilt, concurrent writers, and a directory that cannot be created.
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <thread>

#include "../support/test_support.hpp"
#include "kaboum/core/error.hpp"
#include "kaboum/io/decomposition_cache.hpp"
#include "kaboum/io/mesh_io.hpp"

namespace kaboum::io {
namespace {

using namespace kaboum::testing;

TriangleMesh fingerAdapter() {
  return readMesh(dataFile("meshes/bimanual-assembly/tools/finger-adapter.wrl"));
}

DecompositionOptions fiveMillimetres() {
  DecompositionOptions options;
  options.epsilon = 0.005;
  return options;
}

template <typename T>
bool sameBytes(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0;
}

void expectIdentical(const Decomposition& a, const Decomposition& b) {
  ASSERT_EQ(a.pieces.size(), b.pieces.size());
  for (std::size_t i = 0; i < a.pieces.size(); ++i) {
    EXPECT_TRUE(sameBytes(a.pieces[i].mesh.vertices, b.pieces[i].mesh.vertices)) << "piece " << i;
    EXPECT_TRUE(sameBytes(a.pieces[i].mesh.triangles, b.pieces[i].mesh.triangles)) << "piece " << i;
    ASSERT_EQ(a.pieces[i].planes.size(), b.pieces[i].planes.size());
    for (std::size_t p = 0; p < a.pieces[i].planes.size(); ++p) {
      EXPECT_EQ(a.pieces[i].planes[p].normal, b.pieces[i].planes[p].normal);
      EXPECT_EQ(a.pieces[i].planes[p].offset, b.pieces[i].planes[p].offset);
    }
  }
  EXPECT_TRUE(sameBytes(a.closedInput.vertices, b.closedInput.vertices));
  EXPECT_TRUE(sameBytes(a.closedInput.triangles, b.closedInput.triangles));
  EXPECT_EQ(a.stats.estimatedError, b.stats.estimatedError);
  EXPECT_EQ(a.stats.epsilon, b.stats.epsilon);
  EXPECT_EQ(a.stats.totalVertices, b.stats.totalVertices);
  EXPECT_EQ(a.stats.stopReason, b.stats.stopReason);
}

// The files of `directory` (entries, and temporary files if any were left).
std::vector<std::filesystem::path> filesIn(const std::filesystem::path& directory) {
  std::vector<std::filesystem::path> files;
  for (const auto& entry : std::filesystem::directory_iterator(directory)) {
    files.push_back(entry.path());
  }
  return files;
}

TEST(DecompositionCache, AMissThenAHitGiveTheSamePiecesByteForByte) {
  const test::ScratchDir dir;
  const TriangleMesh mesh = fingerAdapter();
  DecompositionCache cold(dir.file("cache"));
  const Decomposition computed = cold.decompose(mesh, fiveMillimetres());
  EXPECT_EQ(cold.report().misses, 1U);
  EXPECT_EQ(cold.report().hits, 0U);
  EXPECT_TRUE(std::filesystem::exists(cold.entryPath(mesh, fiveMillimetres())));

  DecompositionCache warm(dir.file("cache"));
  const Decomposition read = warm.decompose(mesh, fiveMillimetres());
  EXPECT_EQ(warm.report().hits, 1U);
  EXPECT_EQ(warm.report().misses, 0U);
  EXPECT_TRUE(warm.report().warnings.empty());
  expectIdentical(computed, read);
  expectIdentical(decomposeBounding(mesh, fiveMillimetres()), read);
}

TEST(DecompositionCache, AChangedMeshOrOptionMisses) {
  const test::ScratchDir dir;
  const TriangleMesh mesh = fingerAdapter();
  DecompositionCache cache(dir.file("cache"));
  (void)cache.decompose(mesh, fiveMillimetres());

  TriangleMesh moved = mesh;
  moved.vertices[0].x() += 1e-6;
  DecompositionOptions coarser = fiveMillimetres();
  coarser.epsilon = 0.006;
  DecompositionOptions reseeded = fiveMillimetres();
  reseeded.seed = 2;
  DecompositionOptions fewerPieces = fiveMillimetres();
  fewerPieces.maxPieces = 4;
  EXPECT_NE(cache.entryPath(moved, fiveMillimetres()), cache.entryPath(mesh, fiveMillimetres()));
  (void)cache.decompose(moved, fiveMillimetres());
  for (const DecompositionOptions& options : {coarser, reseeded, fewerPieces}) {
    EXPECT_NE(cache.entryPath(mesh, options), cache.entryPath(mesh, fiveMillimetres()));
    (void)cache.decompose(mesh, options);
  }
  EXPECT_EQ(cache.report().misses, 5U);
  EXPECT_EQ(cache.report().hits, 0U);
  EXPECT_EQ(filesIn(dir.file("cache")).size(), 5U);
}

TEST(DecompositionCache, CorruptEntriesAreDetectedAndRebuilt) {
  const test::ScratchDir dir;
  const TriangleMesh mesh = fingerAdapter();
  DecompositionCache first(dir.file("cache"));
  const Decomposition computed = first.decompose(mesh, fiveMillimetres());
  const std::filesystem::path entry = first.entryPath(mesh, fiveMillimetres());
  const std::string valid = test::slurp(entry.string());

  const auto flipped = [&](std::size_t at) {
    std::string bytes = valid;
    bytes[at] = static_cast<char>(bytes[at] ^ 0x10);
    return bytes;
  };
  const std::vector<std::pair<std::string, std::string>> corruptions = {
      {"truncated", valid.substr(0, valid.size() / 2)},
      {"truncated", valid.substr(0, 10)},
      {"truncated", ""},
      {"bad magic", flipped(0)},
      {"format version", flipped(8)},
      {"key does not match", flipped(12)},
      {"truncated or too long", valid + "x"},
      {"checksum mismatch", flipped(valid.size() / 2)},
      {"checksum mismatch", flipped(valid.size() - 1)},
  };
  for (const auto& [problem, bytes] : corruptions) {
    std::ofstream(entry, std::ios::binary | std::ios::trunc) << bytes;
    DecompositionCache cache(dir.file("cache"));
    const Decomposition rebuilt = cache.decompose(mesh, fiveMillimetres());
    const DecompositionCacheReport report = cache.report();
    EXPECT_EQ(report.rebuilt, 1U) << problem;
    EXPECT_EQ(report.hits + report.misses, 0U) << problem;
    ASSERT_EQ(report.warnings.size(), 1U) << problem;
    EXPECT_NE(report.warnings[0].find(entry.string()), std::string::npos) << report.warnings[0];
    EXPECT_NE(report.warnings[0].find(problem), std::string::npos) << report.warnings[0];
    expectIdentical(computed, rebuilt);
    DecompositionCache after(dir.file("cache"));
    (void)after.decompose(mesh, fiveMillimetres());
    EXPECT_EQ(after.report().hits, 1U) << problem << ": overwritten by a valid entry";
  }
}

TEST(DecompositionCache, TwoThreadsFillingOneDirectoryLeaveOneValidEntry) {
  const test::ScratchDir dir;
  const TriangleMesh mesh = fingerAdapter();
  std::vector<Decomposition> results(2);
  std::vector<DecompositionCacheReport> reports(2);
  {
    std::vector<std::jthread> threads;
    for (std::size_t t = 0; t < 2; ++t) {
      threads.emplace_back([&, t] {
        DecompositionCache cache(dir.file("cache"));
        results[t] = cache.decompose(mesh, fiveMillimetres());
        reports[t] = cache.report();
      });
    }
  }
  expectIdentical(results[0], results[1]);
  for (const DecompositionCacheReport& report : reports) {
    EXPECT_EQ(report.hits + report.misses, 1U);
    EXPECT_TRUE(report.warnings.empty());
  }
  const std::vector<std::filesystem::path> files = filesIn(dir.file("cache"));
  ASSERT_EQ(files.size(), 1U) << "no temporary file is left";
  DecompositionCache reader(dir.file("cache"));
  expectIdentical(results[0], reader.decompose(mesh, fiveMillimetres()));
  EXPECT_EQ(reader.report().hits, 1U);
}

TEST(DecompositionCache, ADirectoryThatCannotBeCreatedIsNamed) {
  const test::ScratchDir dir;
  const std::string blocked = dir.write("file", "not a directory") + "/cache";
  try {
    DecompositionCache cache(blocked);
    FAIL() << "no error";
  } catch (const InputError& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find(blocked + ": cannot create the cache directory"), std::string::npos)
        << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  }
}

}  // namespace
}  // namespace kaboum::io
