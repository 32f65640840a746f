#include "kaboum/geometry/bounding_mesh_guard.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "kaboum/geometry/star_directions.hpp"
#include "kaboum/geometry/triangle_bvh.hpp"

namespace kaboum::geometry {
namespace {

// A star triangle is left out of a guard query only when the directions of the two triangles from
// the hub are more than this apart (chord on the unit sphere), and every height involved is at
// least kHubHeightRatio of the longest edge involved: then the pair stays farther than
// (2/π)·kHubMargin·kHubHeightRatio > 1e-6 of that edge apart, the separation certificate's margin.
constexpr double kHubMargin = 2e-4;
constexpr double kHubHeightRatio = 1e-2;
// A direction box spanning more cells than this per axis is not indexed (its triangle is enumerated
// with the whole star instead).
constexpr double kHubMaxCellSpan = 16.0;
// The coarse index of a hub, which prunes query pieces far from its star's directions, has cells
// this many times larger.
constexpr double kHubCoarse = 16.0;

void buildGrid(CrossingGuard& guard, const ContractionMesh& mesh, double cellSize) {
  guard.grid.emplace(cellSize, mesh.triangles.size());
  for (std::uint32_t t = 0; t < mesh.triangles.size(); ++t) {
    if (mesh.triangleAlive[t] && guard.inGrid[t]) guard.grid->insert(t, guard.boxes[t]);
  }
  guard.verticesAtGridBuild = mesh.aliveVertices;
}

// The box under which star triangle t of `hub` is indexed: its directions from the hub; empty when
// they cannot be boxed or span too many cells. A function of the current positions only, so the
// box a triangle was indexed with is found again for removal.
std::optional<Box3> starDirectionBox(const Hub& hub, const ContractionMesh& mesh, std::uint32_t t) {
  const Triangle& tri = mesh.triangles[t];
  const std::uint32_t k = tri[0] == hub.vertex ? 0 : (tri[1] == hub.vertex ? 1 : 2);
  const std::array<Vec3, 2> far{mesh.positions[tri[(k + 1) % 3]], mesh.positions[tri[(k + 2) % 3]]};
  const std::optional<std::array<Vec3, 3>> directions =
      directionsFrom(mesh.positions[hub.vertex], far);
  if (!directions) return std::nullopt;
  const Box3 box = sphericalBox(*directions, 2, 0.0);
  if ((box.hi - box.lo).maxCoeff() > kHubMaxCellSpan * hub.directions->cellSize()) {
    return std::nullopt;
  }
  return box;
}

// Registers triangle t, with its current geometry and boxes[t], in the index of each hub corner.
void indexAtHubs(CrossingGuard& guard, const ContractionMesh& mesh, std::uint32_t t) {
  for (const std::uint32_t v : mesh.triangles[t]) {
    if (!isHub(guard.hubs, v)) continue;
    Hub& hub = guard.hubs.slots[guard.hubs.slotOf[v]];
    if (const std::optional<Box3> box = starDirectionBox(hub, mesh, t)) {
      hub.directions->insert(t, *box);
      hub.coarse->insert(t, *box);
    } else {
      ++hub.unindexed;
    }
    const Triangle& tri = mesh.triangles[t];
    const std::uint32_t k = tri[0] == v ? 0 : (tri[1] == v ? 1 : 2);
    hub.minHeight = std::min(
        hub.minHeight, pointSegmentDistance(mesh.positions[v], mesh.positions[tri[(k + 1) % 3]],
                                            mesh.positions[tri[(k + 2) % 3]]));
    hub.maxEdge = std::max(hub.maxEdge, std::sqrt(guard.boxes[t].diagonalSquared()));
    hub.starBox = {hub.starBox.lo.cwiseMin(guard.boxes[t].lo),
                   hub.starBox.hi.cwiseMax(guard.boxes[t].hi)};
  }
}

// Adds to `nearby` the star triangles of hubs (other than a and b) that the new fan might meet,
// marking them `seen`. Two triangles whose directions from hub v are more than kHubMargin apart
// stay farther apart than 0.6·kHubMargin times the distance from v to either one's points away from
// v; the predicate only looks at far edges when they share v. So when every height (hub to a far
// edge of its star, hub to a new triangle or its far edge) is at least kHubHeightRatio of every
// edge involved, only the star triangles indexed in a cell the new triangles' grown direction boxes
// touch can meet them. Otherwise the whole star is listed.
void gatherNearHubs(CrossingGuard& guard, ContractionMesh& mesh, const Box3& fanBox,
                    std::uint32_t a, std::uint32_t b, std::uint32_t seen) {
  const auto add = [&](std::uint32_t u) {
    if (mesh.triangleMark[u] == seen) return;
    mesh.triangleMark[u] = seen;
    if (mesh.triangleAlive[u] && fanBox.overlaps(guard.boxes[u])) guard.nearby.push_back(u);
  };
  for (Hub& hub : guard.hubs.slots) {
    if (hub.vertex == kNoIndex || hub.vertex == a || hub.vertex == b ||
        !fanBox.overlaps(hub.starBox)) {
      continue;
    }
    const Vec3& apex = mesh.positions[hub.vertex];
    const double fine = hub.directions->cellSize(), coarse = hub.coarse->cellSize();
    bool indexed = hub.unindexed == 0;
    for (const NewTriangle& n : guard.newTriangles) {
      if (!indexed) break;
      if (!n.box.overlaps(hub.starBox)) continue;
      const std::uint32_t k = n.ids[0] == hub.vertex
                                  ? 0
                                  : (n.ids[1] == hub.vertex ? 1 : (n.ids[2] == hub.vertex ? 2 : 3));
      // A new triangle at the hub is seen from it along its far edge; the predicate ignores the
      // hub itself.
      const std::array<Vec3, 2> far{n.corners[(k + 1) % 3], n.corners[(k + 2) % 3]};
      const double height =
          k < 3 ? pointSegmentDistance(apex, far[0], far[1])
                : (closestPointOnTriangle(apex, n.corners[0], n.corners[1], n.corners[2]) - apex)
                      .norm();
      const double longest = std::max(hub.maxEdge, std::sqrt(n.sizeSquared));
      const std::optional<std::array<Vec3, 3>> directions =
          k < 3 ? directionsFrom(apex, far) : directionsFrom(apex, n.corners);
      indexed = directions && std::min(height, hub.minHeight) >= kHubHeightRatio * longest;
      if (!indexed) break;
      const int count = k < 3 ? 2 : 3;
      forEachSphericalPiece(*directions, count, kHubMargin, coarse,
                            [&](const Box3& box, const std::array<Vec3, 3>& piece) {
                              if (!hub.coarse->anyNear(box)) return;
                              forEachSphericalPiece(
                                  piece, count, kHubMargin, fine,
                                  [&](const Box3& fineBox, const std::array<Vec3, 3>&) {
                                    hub.directions->forEachNear(fineBox, add);
                                  });
                            });
    }
    if (!indexed) forEachTriangle(mesh, hub.vertex, add);
  }
}

}  // namespace

void buildGuard(CrossingGuard& guard, const ContractionMesh& mesh, double diagonal) {
  const std::size_t triangleCount = mesh.triangles.size();
  double edgeLengthSum = 0.0;
  for (const Triangle& t : mesh.triangles) {
    edgeLengthSum += (mesh.positions[t[0]] - mesh.positions[t[1]]).norm();
  }
  guard.boxes.resize(triangleCount);
  guard.inGrid.assign(triangleCount, 1);
  guard.hubs.slotOf.assign(mesh.positions.size(), kNoIndex);
  for (std::uint32_t t = 0; t < triangleCount; ++t) guard.boxes[t] = boxOf(mesh, t);
  for (std::uint32_t v = 0; v < mesh.positions.size(); ++v) {
    if (mesh.triangleCount[v] >= kHubValence) acquireHub(guard.hubs, mesh, v);
  }
  for (std::uint32_t t = 0; t < triangleCount; ++t) {
    guard.inGrid[t] = hasHubCorner(guard.hubs, mesh, t) ? 0 : 1;
    if (!guard.inGrid[t]) indexAtHubs(guard, mesh, t);
  }
  buildGrid(
      guard, mesh,
      std::max(2.0 * edgeLengthSum / std::max<double>(1.0, static_cast<double>(triangleCount)),
               1e-9 * diagonal + 1e-300));
}

void coarsenGridIfSparse(CrossingGuard& guard, const ContractionMesh& mesh) {
  if (mesh.aliveVertices * 2 < guard.verticesAtGridBuild) {
    buildGrid(guard, mesh, guard.grid->cellSize() * std::sqrt(2.0));
  }
}

void acquireHub(Hubs& hubs, const ContractionMesh& mesh, std::uint32_t v) {
  if (!isHub(hubs, v)) {
    std::uint32_t slot = 0;
    while (slot < hubs.slots.size() && hubs.slots[slot].vertex != kNoIndex) ++slot;
    if (slot == hubs.slots.size()) hubs.slots.emplace_back();
    hubs.slotOf[v] = slot;
  }
  Hub& hub = hubs.slots[hubs.slotOf[v]];
  hub.vertex = v;
  const std::uint32_t valence = mesh.triangleCount[v];
  if (!hub.directions) {
    const double cellSize =
        std::max(4.0 * std::numbers::pi / std::max<double>(valence, 1.0), 8.0 * kHubMargin);
    hub.directions.emplace(cellSize, valence);
    // The coarse index holds about one entry per triangle (the fine one a few): a third of the
    // table and pool keeps its memory at a third.
    hub.coarse.emplace(kHubCoarse * cellSize, valence / 3);
  }
  const float inf = std::numeric_limits<float>::infinity();
  hub.starBox = {Eigen::Vector3f::Constant(inf), Eigen::Vector3f::Constant(-inf)};
  hub.minHeight = std::numeric_limits<double>::infinity();
  hub.maxEdge = 0.0;
  hub.unindexed = 0;
  hub.raised.clear();  // v's edges are all queued afresh by their lower bounds
  // Room for every edge at v now, so that the first contractions next to it do not allocate.
  hub.raised.reserve(valence);
}

void releaseHub(Hubs& hubs, std::uint32_t v) {
  if (!isHub(hubs, v)) return;
  hubs.slots[hubs.slotOf[v]].vertex = kNoIndex;
  hubs.slotOf[v] = kNoIndex;
}

void unindexAtHubs(CrossingGuard& guard, const ContractionMesh& mesh, std::uint32_t t) {
  for (const std::uint32_t v : mesh.triangles[t]) {
    if (!isHub(guard.hubs, v)) continue;
    Hub& hub = guard.hubs.slots[guard.hubs.slotOf[v]];
    if (const std::optional<Box3> box = starDirectionBox(hub, mesh, t)) {
      hub.directions->remove(t, *box);
      hub.coarse->remove(t, *box);
    } else {
      --hub.unindexed;
    }
  }
}

void removeFromGrid(CrossingGuard& guard, std::uint32_t t) {
  if (guard.inGrid[t]) guard.grid->remove(t, guard.boxes[t]);
  guard.inGrid[t] = 0;
}

void placeTriangle(CrossingGuard& guard, const ContractionMesh& mesh, std::uint32_t t,
                   const Box3& box) {
  if (hasHubCorner(guard.hubs, mesh, t)) {
    removeFromGrid(guard, t);
    guard.boxes[t] = box;
    indexAtHubs(guard, mesh, t);
    return;
  }
  if (guard.inGrid[t]) {
    guard.grid->move(t, guard.boxes[t], box);
  } else {
    guard.grid->insert(t, box);
  }
  guard.inGrid[t] = 1;
  guard.boxes[t] = box;
}

// Keeps outer results free of folds (which parity-based inside tests misread) and inner results
// inside the original. Each pair whose boxes overlap is first given the cheap certificate
// certainlyApart (cached unit normals and twice-areas); only the pairs it cannot clear reach the
// exact predicate, so the verdict is the predicate's.
bool newFanCrossesMesh(CrossingGuard& guard, ContractionMesh& mesh, const ContractionCosts& costs,
                       const Contraction& c, std::span<const std::uint32_t> fanA,
                       std::span<const std::uint32_t> fanB) {
  const std::uint32_t a = c.a, b = c.b;
  const std::uint32_t exclude = ++mesh.stamp;
  guard.newTriangles.clear();
  Box3 fanBox{Eigen::Vector3f::Constant(std::numeric_limits<float>::infinity()),
              Eigen::Vector3f::Constant(-std::numeric_limits<float>::infinity())};
  const auto addNew = [&](std::uint32_t t) {
    mesh.triangleMark[t] = exclude;
    if (triangleHas(mesh, t, a) && triangleHas(mesh, t, b)) return;
    NewTriangle& n = guard.newTriangles.emplace_back();
    n.ids = mesh.triangles[t];
    for (int k = 0; k < 3; ++k) {
      if (n.ids[k] == b) n.ids[k] = a;
      n.corners[k] = n.ids[k] == a ? c.position : mesh.positions[n.ids[k]];
    }
    const Vec3 cross = (n.corners[1] - n.corners[0]).cross(n.corners[2] - n.corners[0]);
    n.crossLength = cross.norm();  // > 0: the collapse refused degenerate new triangles
    n.unitNormal = cross / n.crossLength;
    n.box = triangleBox(n.corners[0], n.corners[1], n.corners[2]);
    n.sizeSquared = n.box.diagonalSquared();
    fanBox = {fanBox.lo.cwiseMin(n.box.lo), fanBox.hi.cwiseMax(n.box.hi)};
  };
  for (std::uint32_t t : fanA) addNew(t);
  for (std::uint32_t t : fanB) addNew(t);
  guard.newPlaned.clear();
  for (const NewTriangle& n : guard.newTriangles) {
    guard.newPlaned.push_back({{&n.corners[0], &n.corners[1], &n.corners[2]},
                               n.ids,
                               n.unitNormal,
                               n.crossLength,
                               n.sizeSquared});
  }

  // One grid query for the whole fan; then each nearby triangle is tested against the new
  // triangles whose boxes it overlaps.
  guard.nearby.clear();
  guard.grid->forEachNear(fanBox, [&](std::uint32_t u) {
    if (mesh.triangleMark[u] == exclude) return;
    mesh.triangleMark[u] = exclude;  // seen
    if (mesh.triangleAlive[u] && fanBox.overlaps(guard.boxes[u])) guard.nearby.push_back(u);
  });
  if (!guard.hubs.slots.empty()) gatherNearHubs(guard, mesh, fanBox, a, b, exclude);
  const std::vector<NewTriangle>& fresh = guard.newTriangles;
  for (std::size_t i = 0; i < fresh.size(); ++i) {
    for (std::size_t j = i + 1; j < fresh.size(); ++j) {
      if (!certainlyApart(guard.newPlaned[i], guard.newPlaned[j]) &&
          meshTrianglesIntersect(fresh[i].corners, fresh[i].ids, fresh[j].corners, fresh[j].ids)) {
        return true;
      }
    }
  }
  for (std::uint32_t u : guard.nearby) {
    const Triangle& ids = mesh.triangles[u];
    const PlanedTriangle old{
        {&mesh.positions[ids[0]], &mesh.positions[ids[1]], &mesh.positions[ids[2]]},
        ids,
        costs.normals[u],
        costs.crossLengths[u],
        guard.boxes[u].diagonalSquared()};
    for (std::size_t i = 0; i < fresh.size(); ++i) {
      const NewTriangle& n = fresh[i];
      if (!n.box.overlaps(guard.boxes[u]) || certainlyApart(guard.newPlaned[i], old)) continue;
      const std::array<Vec3, 3> corners{mesh.positions[ids[0]], mesh.positions[ids[1]],
                                        mesh.positions[ids[2]]};
      if (meshTrianglesIntersect(n.corners, n.ids, corners, ids)) return true;
    }
  }
  return false;
}

}  // namespace kaboum::geometry
