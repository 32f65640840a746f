#include "kaboum/geometry/mesh_cleanup.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <span>

#include "kaboum/geometry/mesh_analysis.hpp"

namespace kaboum::geometry {

namespace {

constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();

std::uint64_t mix(std::uint64_t x) {  // splitmix64 finaliser
  x ^= x >> 30;
  x *= 0xbf58476d1ce4e5b9ULL;
  x ^= x >> 27;
  x *= 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

std::uint64_t combine(std::uint64_t x, std::uint64_t y, std::uint64_t z) {
  return mix(x ^ mix(y ^ mix(z)));
}

// Open-addressing table from a 64-bit key (already well mixed) to the newest kept vertex with that
// key; older ones with the same key are chained through `next`. The table doubles when half full,
// so it stays as small (and cache-friendly) as the number of distinct keys allows.
class KeyChains {
 public:
  explicit KeyChains(std::size_t vertices) : slots_(1024), next_(vertices, kNone) {}

  std::uint32_t head(std::uint64_t key) const { return slots_[find(key)].head; }
  std::uint32_t next(std::uint32_t vertex) const { return next_[vertex]; }

  void insert(std::uint64_t key, std::uint32_t vertex) {
    std::size_t i = find(key);
    if (slots_[i].head == kNone) {
      if (2 * (used_ + 1) > slots_.size()) {
        grow();
        i = find(key);
      }
      ++used_;
    }
    next_[vertex] = slots_[i].head;
    slots_[i] = {key, vertex};
  }

 private:
  struct Slot {
    std::uint64_t key = 0;
    std::uint32_t head = kNone;
  };

  // The slot holding `key`, or the empty slot where it would go.
  std::size_t find(std::uint64_t key) const {
    const std::size_t mask = slots_.size() - 1;
    std::size_t i = key & mask;
    while (slots_[i].head != kNone && slots_[i].key != key) i = (i + 1) & mask;
    return i;
  }

  void grow() {
    std::vector<Slot> old(2 * slots_.size());
    old.swap(slots_);
    for (const Slot& slot : old) {
      if (slot.head != kNone) slots_[find(slot.key)] = slot;
    }
  }

  std::vector<Slot> slots_;
  std::size_t used_ = 0;
  std::vector<std::uint32_t> next_;
};

std::uint64_t exactKey(const Vec3& p) {
  // Adding +0.0 turns -0.0 into +0.0, so both zeros share a key.
  return combine(std::bit_cast<std::uint64_t>(p.x() + 0.0),
                 std::bit_cast<std::uint64_t>(p.y() + 0.0),
                 std::bit_cast<std::uint64_t>(p.z() + 0.0));
}

std::int64_t cellOf(double coordinate, double tolerance) {
  constexpr double kLimit = 4.0e18;  // keeps the cell index and its neighbours in int64 range
  const double cell = std::floor(coordinate / tolerance);
  return static_cast<std::int64_t>(std::clamp(cell, -kLimit, kLimit));
}

std::uint64_t cellKey(std::int64_t x, std::int64_t y, std::int64_t z) {
  return combine(static_cast<std::uint64_t>(x), static_cast<std::uint64_t>(y),
                 static_cast<std::uint64_t>(z));
}

// The earliest kept vertex within `tolerance` of p (kNone if none): scans the 27 cells around p.
std::uint32_t findNear(const KeyChains& chains, const std::vector<Vec3>& kept, const Vec3& p,
                       double tolerance) {
  const std::int64_t cx = cellOf(p.x(), tolerance), cy = cellOf(p.y(), tolerance),
                     cz = cellOf(p.z(), tolerance);
  const double squaredTolerance = tolerance * tolerance;
  std::uint32_t best = kNone;
  for (std::int64_t dx = -1; dx <= 1; ++dx) {
    for (std::int64_t dy = -1; dy <= 1; ++dy) {
      for (std::int64_t dz = -1; dz <= 1; ++dz) {
        for (std::uint32_t v = chains.head(cellKey(cx + dx, cy + dy, cz + dz)); v != kNone;
             v = chains.next(v)) {
          if (v < best && (kept[v] - p).squaredNorm() <= squaredTolerance) best = v;
        }
      }
    }
  }
  return best;
}

// True when triangle `n` has the directed edge a->b.
bool hasDirectedEdge(const Triangle& n, std::uint32_t a, std::uint32_t b) {
  for (int k = 0; k < 3; ++k) {
    if (n[k] == a && n[(k + 1) % 3] == b) return true;
  }
  return false;
}

}  // namespace

void weldVertices(TriangleMesh& mesh, double tolerance) {
  std::vector<std::uint32_t> remap(mesh.vertices.size(), kNone);
  for (const Triangle& t : mesh.triangles) {
    for (const std::uint32_t v : t) remap[v] = 0;  // marks referenced vertices
  }
  KeyChains chains(mesh.vertices.size());
  std::uint32_t keptCount = 0;
  for (std::uint32_t i = 0; i < mesh.vertices.size(); ++i) {
    if (remap[i] == kNone) continue;
    const Vec3 p = mesh.vertices[i];
    std::uint32_t match = kNone;
    std::uint64_t key = 0;
    if (tolerance > 0.0) {
      match = findNear(chains, mesh.vertices, p, tolerance);
      key = cellKey(cellOf(p.x(), tolerance), cellOf(p.y(), tolerance), cellOf(p.z(), tolerance));
    } else {
      key = exactKey(p);
      for (std::uint32_t v = chains.head(key); v != kNone && match == kNone; v = chains.next(v)) {
        if (mesh.vertices[v] == p) match = v;
      }
    }
    if (match == kNone) {
      match = keptCount++;
      mesh.vertices[match] = p;  // compacts in place: match <= i
      chains.insert(key, match);
    }
    remap[i] = match;
  }
  mesh.vertices.resize(keptCount);
  for (Triangle& t : mesh.triangles) {
    for (std::uint32_t& v : t) v = remap[v];
  }
}

void removeUnreferencedVertices(TriangleMesh& mesh) {
  std::vector<std::uint32_t> remap(mesh.vertices.size(), kNone);
  for (const Triangle& t : mesh.triangles) {
    for (const std::uint32_t v : t) remap[v] = 0;
  }
  std::uint32_t keptCount = 0;
  for (std::uint32_t i = 0; i < mesh.vertices.size(); ++i) {
    if (remap[i] == kNone) continue;
    mesh.vertices[keptCount] = mesh.vertices[i];
    remap[i] = keptCount++;
  }
  mesh.vertices.resize(keptCount);
  for (Triangle& t : mesh.triangles) {
    for (std::uint32_t& v : t) v = remap[v];
  }
}

bool repairOrientation(TriangleMesh& mesh) {
  const EdgeNeighbors neighbors = findEdgeNeighbors(mesh);
  const std::size_t triangleCount = mesh.triangles.size();
  std::vector<char> visited(triangleCount, 0), flip(triangleCount, 0);
  std::vector<std::uint32_t> order;  // BFS order; each component is one contiguous stretch
  order.reserve(triangleCount);
  bool allRepaired = true;

  for (std::uint32_t seed = 0; seed < triangleCount; ++seed) {
    if (visited[seed] || neighbors.across[3 * seed] == EdgeNeighbors::kNoEdge) continue;
    const std::size_t begin = order.size();
    order.push_back(seed);
    visited[seed] = 1;
    bool orientable = true, closed = true;
    for (std::size_t i = begin; i < order.size(); ++i) {
      const std::uint32_t t = order[i];
      const Triangle& tri = mesh.triangles[t];
      for (std::uint32_t k = 0; k < 3; ++k) {
        const std::uint32_t n = neighbors.across[3 * t + k];
        if (n == EdgeNeighbors::kBorder || n == EdgeNeighbors::kNonManifold) {
          closed = false;
          orientable = orientable && n == EdgeNeighbors::kBorder;
          continue;
        }
        // n must run the shared edge against t's (possibly flipped) direction.
        const bool sameDirection = hasDirectedEdge(mesh.triangles[n], tri[k], tri[(k + 1) % 3]);
        const char required = static_cast<char>(flip[t] ^ static_cast<char>(sameDirection));
        if (!visited[n]) {
          visited[n] = 1;
          flip[n] = required;
          order.push_back(n);
        } else if (flip[n] != required) {
          orientable = false;
        }
      }
    }

    const auto component = std::span(order).subspan(begin);
    if (!orientable) {
      allRepaired = false;
      continue;  // flips are applied below only for orientable components
    }
    bool invert = false;
    if (closed) {
      const Vec3& origin = mesh.vertices[mesh.triangles[seed][0]];
      double volume = 0.0;
      for (const std::uint32_t t : component) {
        const Triangle& tri = mesh.triangles[t];
        const double signedVolume =
            (mesh.vertices[tri[0]] - origin)
                .dot((mesh.vertices[tri[1]] - origin).cross(mesh.vertices[tri[2]] - origin));
        volume += flip[t] ? -signedVolume : signedVolume;
      }
      invert = volume < 0.0;
    } else {
      std::size_t flipped = 0;
      for (const std::uint32_t t : component) flipped += static_cast<std::size_t>(flip[t]);
      invert = 2 * flipped > component.size();
    }
    for (const std::uint32_t t : component) {
      if ((flip[t] != 0) != invert) std::swap(mesh.triangles[t][1], mesh.triangles[t][2]);
    }
  }
  return allRepaired;
}

bool orientOutward(TriangleMesh& mesh, bool& changed) {
  changed = false;
  const MeshAnalysis before = analyzeMesh(mesh);
  if (!before.consistentlyOriented || (before.closed && !before.outwardOriented)) {
    if (!repairOrientation(mesh)) return false;
    changed = true;
  }
  if (!before.closed && analyzeMesh(mesh).volume < 0.0) {
    for (Triangle& t : mesh.triangles) std::swap(t[1], t[2]);
    changed = true;
  }
  return true;
}

}  // namespace kaboum::geometry
