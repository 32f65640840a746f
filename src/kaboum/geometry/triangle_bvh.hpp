// Static bounding volume hierarchy over a triangle mesh: exact closest points, inside tests and
// triangle intersection queries, the geometric core of the bounding mesh verifier (§4.2, Eq. 4.1).
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "kaboum/geometry/triangle_mesh.hpp"

namespace kaboum::geometry {

// Closest point of triangle (a, b, c) to `p`: the projection onto the plane when it falls inside,
// else the closest point of the three edges. Triangles thinner than 1e-8 of their longest edge
// use the edges only, so zero-area triangles are handled as segments or points.
Vec3 closestPointOnTriangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c);

// Closed segment/triangle and triangle/triangle intersection with a contact tolerance: true when
// the two come within 1e-12 of the longest edge involved (so touching counts), false when they are
// farther apart than that, up to rounding: ~1e-16 of the size divided by the thinness
// |(b-a) x (c-a)| / longest edge^2 of the triangles. Exact orientation signs reject pairs apart on
// either side of a plane and accept proper crossings; the rest is decided by distances between
// actual points, never by an ambiguous sign. Zero-area triangles (thinness <= 1e-12, as mesh
// analysis defines them) have no reliable plane and never intersect anything.
bool segmentIntersectsTriangle(const Vec3& p, const Vec3& q, const Vec3& a, const Vec3& b,
                               const Vec3& c);
bool trianglesIntersect(const Vec3& a0, const Vec3& a1, const Vec3& a2, const Vec3& b0,
                        const Vec3& b1, const Vec3& b2);
// Triangles (s, p1, q1) and (s, p2, q2) sharing only the vertex s meet somewhere else: then their
// intersection runs from s to a point of the edge p1q1 or p2q2, so it suffices to test those edges
// (each against the other triangle, with the contact tolerance above).
bool trianglesMeetBesideSharedVertex(const Vec3& s, const Vec3& p1, const Vec3& q1, const Vec3& p2,
                                     const Vec3& q2);

// Mesh triangles t and u, given by corner positions and vertex ids, meet somewhere other than at
// the vertices they share. Triangles sharing an edge count as not meeting (a fold across a shared
// edge is an orientation defect, caught by normal checks instead).
bool meshTrianglesIntersect(const std::array<Vec3, 3>& t, const Triangle& tIds,
                            const std::array<Vec3, 3>& u, const Triangle& uIds);

// Binned-SAH BVH over a copy of the mesh's vertices and triangles. Build O(n log n); queries are
// const and thread-safe and allocate nothing. Throws InputError for a mesh without triangles, with
// an index out of range or with a non-finite coordinate.
class TriangleBvh {
 public:
  explicit TriangleBvh(const TriangleMesh& mesh);

  struct Closest {
    Vec3 point;
    double distance;
    std::uint32_t triangle;  // index into the mesh's triangles
  };
  // Exact closest point on the surface (the first triangle found wins ties).
  [[nodiscard]] Closest closest(const Vec3& query) const;
  // Some triangle lies within `radius` of `query`: true exactly when closest(query).distance <=
  // radius (the same arithmetic), but it stops at the first such triangle, looking nearest
  // boxes first.
  [[nodiscard]] bool hasTriangleWithin(const Vec3& query, double radius) const;

  // Inside test for closed meshes by ray crossings. A ray from `p` sums +1 for every triangle it
  // leaves through (front side) and -1 for every one it enters; `p` is inside when that winding
  // number is nonzero (so overlapping and inward-oriented closed components count as solid). Each
  // crossing is decided by the signs of triple products of the vectors from `p` to the corners,
  // trusted only beyond 1e-12 of the product of those vectors' lengths (rounding is ~1e-15): a ray
  // passing that close to an edge or vertex, grazing a face, or starting on a face is discarded and
  // the next of insideTestDirections() is tried. The answer is the majority of the first three
  // valid rays (it stops at two agreeing; with fewer valid rays a tie counts as outside); a point
  // every ray finds on a face is on the surface and counts as inside. On a closed mesh every valid
  // ray gives the same winding number; on an open one the answer depends on the directions.
  [[nodiscard]] bool contains(const Vec3& p) const;
  // contains() for a mesh known to be closed and consistently oriented: there the first valid ray
  // decides (a point every ray finds on a face counts as inside, as in contains()).
  [[nodiscard]] bool containsInClosedMesh(const Vec3& p) const;

  // The fixed, deliberately irregular unit ray directions of contains(), in the order tried.
  static std::span<const Vec3> insideTestDirections();

  // True if the closed triangle (a, b, c) touches or crosses a mesh triangle, ignoring mesh
  // triangles that have a vertex listed in `ignoreVertexIds` (indices into the mesh), e.g. the
  // neighbourhood of an edge being contracted. Degenerate triangles are ignored (see above).
  [[nodiscard]] bool intersectsTriangle(const Vec3& a, const Vec3& b, const Vec3& c,
                                        std::span<const std::uint32_t> ignoreVertexIds = {}) const;

  // Calls visit(triangleIndex) for every mesh triangle whose bounding box overlaps the box [lo, hi]
  // (and for the other triangles of the same leaves); stops early when visit returns false.
  template <class Visit>
  void forEachTriangleOverlapping(const Vec3& lo, const Vec3& hi, Visit&& visit) const {
    forEachSlotOverlapping(lo, hi, [&](std::uint32_t slot) { return visit(triangleIds_[slot]); });
  }

 private:
  struct Node {
    Vec3 lo, hi;          // bounding box, padded by padding_
    std::uint32_t first;  // leaf: first slot; inner node: index of the second child
    std::uint32_t count;  // leaf: number of slots; 0 for an inner node (first child follows it)
  };
  static constexpr std::size_t kMaxDepth = 96;  // build keeps depth below this (stack size)

  struct BuildItem {  // one triangle while building, kept contiguous for cache-friendly passes
    Vec3 lo, hi, centroid;
    std::uint32_t triangle;
  };
  // Appends the subtree over items [begin, end) and returns its node index.
  std::uint32_t build(std::vector<BuildItem>& items, std::uint32_t begin, std::uint32_t end,
                      int depth);
  // Winding number along one ray, or nothing when the ray is ambiguous (see contains()).
  [[nodiscard]] std::optional<int> rayWinding(const Vec3& origin, const Vec3& direction) const;

  template <class Visit>
  void forEachSlotOverlapping(const Vec3& lo, const Vec3& hi, Visit&& visit) const {
    std::array<std::uint32_t, kMaxDepth> stack;
    std::size_t size = 0;
    std::uint32_t node = 0;
    while (true) {
      const Node& n = nodes_[node];
      if ((n.lo.array() <= hi.array()).all() && (lo.array() <= n.hi.array()).all()) {
        if (n.count == 0) {
          stack[size++] = n.first;
          node = node + 1;
          continue;
        }
        for (std::uint32_t slot = n.first; slot < n.first + n.count; ++slot) {
          if (!visit(slot)) return;
        }
      }
      if (size == 0) return;
      node = stack[--size];
    }
  }

  std::vector<Vec3> vertices_;
  std::vector<Triangle> triangles_;         // in BVH slot order
  std::vector<std::uint32_t> triangleIds_;  // slot -> index in the original mesh
  std::vector<Node> nodes_;                 // depth-first; node 0 is the root
  double padding_ = 0.0;
};

}  // namespace kaboum::geometry
