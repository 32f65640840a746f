// The bounding mesh verifier behind `kaboum check`: Hausdorff figures as in Table 4.2 (Eq. 4.1 on
// dense surface samples) and the containment guarantee of outer and inner bounding meshes (§4.2).
#pragma once

#include <cstdint>
#include <memory>
#include <string>

#include "kaboum/geometry/bound_side.hpp"
#include "kaboum/geometry/triangle_mesh.hpp"

namespace kaboum::geometry {

struct DistanceStats {
  double min = 0, mean = 0, max = 0;  // absolute units
};

// Both one-sided distances of Eq. 4.1, each over the samples (sampleSurface) of its source mesh.
struct HausdorffReport {
  DistanceStats originalToResult, resultToOriginal;
  double diagonal = 0;      // bounding-box diagonal of the original's vertices
  std::size_t samples = 0;  // samples measured, both directions together
};

// Throws InputError when either mesh has no triangles (or bad indices or coordinates).
HausdorffReport measureHausdorff(const TriangleMesh& original, const TriangleMesh& result,
                                 std::size_t randomSamples, std::uint64_t seed);

// measureHausdorff against one original, many results (a search over simplifications): the
// original's BVH and samples are built once.
class HausdorffMeter {
 public:
  // Throws like measureHausdorff for a bad original.
  HausdorffMeter(const TriangleMesh& original, std::size_t randomSamples, std::uint64_t seed);
  ~HausdorffMeter();
  HausdorffMeter(const HausdorffMeter&) = delete;
  HausdorffMeter& operator=(const HausdorffMeter&) = delete;

  // Equal to measureHausdorff(original, result, randomSamples, seed).
  [[nodiscard]] HausdorffReport measure(const TriangleMesh& result) const;
  // Whether both one-sided maxima of measure(result) are within `limit`, answered with less work:
  // a sample is settled by finding one triangle that close (not the closest one), and the first
  // sample farther ends the test.
  [[nodiscard]] bool within(const TriangleMesh& result, double limit) const;

 private:
  struct Original;
  std::unique_ptr<const Original> original_;
  std::size_t randomSamples_;
  std::uint64_t seed_;
};

struct ContainmentReport {
  // False when a mesh the check needs closed is not (the original for either side, the result for
  // an outer bound): containment is only defined for closed meshes. Closed means every directed
  // edge (a, b) is matched by as many (b, a): no border, consistently oriented.
  bool defined = false;
  std::string note;  // plain-language reason when !defined or insideOut
  // A closed mesh the check relies on points its faces inward (negative signed volume): a
  // violation, reported without sampling.
  bool insideOut = false;
  std::size_t checked = 0, violations = 0;
  double worstViolation = 0;  // largest distance to the container of a sample outside it
  std::size_t selfIntersectingPairs = 0;  // countSelfIntersections(result), for either side
};

// Outer: every sample of `original` is inside or on (within tolerance) `result`.
// Inner: every sample of `result` is inside or on `original`, and `result` does not self-intersect.
// A sample within `tolerance` of the container's surface counts as contained, otherwise
// TriangleBvh::contains decides. tolerance < 0 means 1e-9 * diagonal of the original. Sample loops
// run on two threads; results do not depend on that. Throws like measureHausdorff.
ContainmentReport verifyContainment(const TriangleMesh& original, const TriangleMesh& result,
                                    BoundSide side, std::size_t randomSamples, std::uint64_t seed,
                                    double tolerance = -1);

// Pairs of triangles that intersect although they are not neighbours (BVH-accelerated). Pairs
// sharing an edge are neighbours; pairs sharing one vertex count when they meet anywhere else
// (a fold through the shared vertex). Zero-area triangles are skipped.
std::size_t countSelfIntersections(const TriangleMesh& mesh);

}  // namespace kaboum::geometry
