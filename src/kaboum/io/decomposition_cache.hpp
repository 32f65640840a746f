// Bounding convex decompositions kept on disk (thesis §6.1.1, pre-processing done once): an entry
// per mesh and options, so that loading a scene again reads its pieces instead of decomposing its
// meshes. Format, key and concurrency: docs/formats.md#decomposition-cache.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <mutex>
#include <string>
#include <vector>

#include "kaboum/geometry/convex_decomposition.hpp"

namespace kaboum::io {

using namespace kaboum::geometry;

// Version of the entry layout and of decomposeBounding's results. It is part of every key, so
// entries of another version are never read; bump it when either changes.
inline constexpr std::uint32_t kDecompositionCacheVersion = 1;

// What a cache did: entries read, entries missing (computed and stored), corrupt entries rebuilt,
// and one line per corrupt entry or failed write.
struct DecompositionCacheReport {
  std::size_t hits = 0, misses = 0, rebuilt = 0;
  std::vector<std::string> warnings;
};

// A directory of decompositions keyed by the mesh's vertex and triangle bytes, every
// DecompositionOptions field and kDecompositionCacheVersion. Entries are written to a unique
// temporary file and renamed into place, so that concurrent processes never read partial entries;
// an entry that fails its checks (magic, version, key, size, checksum) is rebuilt and overwritten.
// decompose() may be called from several threads.
class DecompositionCache {
 public:
  // Creates `directory` if needed. Throws InputError naming it when it cannot be created.
  explicit DecompositionCache(std::filesystem::path directory);

  // decomposeBounding(mesh, options): read from the entry of (mesh, options) when it is valid, else
  // computed and stored (a write that fails is a warning of the report, not an error). A hit
  // equals the computed result bit for bit, stats included (seconds: those of the run that stored
  // it). Computed on `workers` when given (decomposeBounding's overload; the same result). Throws
  // what decomposeBounding throws.
  Decomposition decompose(const TriangleMesh& mesh, const DecompositionOptions& options,
                          WorkerPool* workers = nullptr);

  [[nodiscard]] const std::filesystem::path& directory() const { return directory_; }
  // The file of the entry of (mesh, options), whether or not it exists.
  [[nodiscard]] std::filesystem::path entryPath(const TriangleMesh& mesh,
                                                const DecompositionOptions& options) const;
  [[nodiscard]] DecompositionCacheReport report() const;

 private:
  std::filesystem::path directory_;
  mutable std::mutex mutex_;  // guards report_
  DecompositionCacheReport report_;
};

}  // namespace kaboum::io
