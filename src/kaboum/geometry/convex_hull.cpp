#include "kaboum/geometry/convex_hull.hpp"

#include <cstdio>
#include <memory>
#include <string>

#include "kaboum/core/error.hpp"

extern "C" {
#include <libqhull_r/qhull_ra.h>
}

namespace kaboum::geometry {
namespace {

// qhull's own state, freed on every exit path.
class QhullSession {
 public:
  QhullSession() : errors_(open_memstream(&errorText_, &errorSize_)) { qh_zero(&qh_, errors_); }
  ~QhullSession() {
    int currentLong = 0;
    int totalLong = 0;
    qh_freeqhull(&qh_, !qh_ALL);
    qh_memfreeshort(&qh_, &currentLong, &totalLong);
    if (errors_ != nullptr) std::fclose(errors_);
    std::free(errorText_);
  }
  QhullSession(const QhullSession&) = delete;
  QhullSession& operator=(const QhullSession&) = delete;

  // Runs qhull on `coordinates` (x y z per point); returns qhull's exit code. 'Q5' skips the
  // final pass that measures how far points lie above their facets (qh_check_maxout, 8% of a
  // bounding convex decomposition's instructions): it changes no facet, only statistics this code
  // never reads, and an error exit when a merge left a point ~100 rounding errors (~1e-12 of the
  // coordinates) above a facet, which is returned as a hull instead.
  int run(std::vector<coordT>& coordinates) {
    char options[] = "qhull Q5";
    return qh_new_qhull(&qh_, 3, static_cast<int>(coordinates.size() / 3), coordinates.data(),
                        False, options, nullptr, errors_);
  }

  // The first line qhull wrote to its error stream.
  std::string firstErrorLine() {
    std::fflush(errors_);
    std::string text = errorText_ != nullptr ? std::string(errorText_, errorSize_) : "";
    return text.substr(0, text.find('\n'));
  }

  qhT* get() { return &qh_; }

 private:
  qhT qh_{};
  char* errorText_ = nullptr;
  std::size_t errorSize_ = 0;
  FILE* errors_;
};

}  // namespace

ConvexHull convexHull(std::span<const Vec3> points, const std::string& what) {
  if (points.size() < 4) {
    throw InputError(locate(
        what, "a convex hull needs at least 4 points, got " + std::to_string(points.size())));
  }
  std::vector<coordT> coordinates;
  coordinates.reserve(points.size() * 3);
  for (const Vec3& p : points) {
    if (!p.allFinite()) throw InputError(locate(what, "a point is not finite"));
    coordinates.insert(coordinates.end(), {p.x(), p.y(), p.z()});
  }

  QhullSession session;
  qhT* qh = session.get();
  if (session.run(coordinates) != 0) {
    throw InputError(
        locate(what, "no 3-d convex hull (are all points coplanar?): " + session.firstErrorLine()));
  }

  ConvexHull hull;
  std::vector<std::uint32_t> hullIndex(points.size(), UINT32_MAX);
  auto hullVertex = [&](vertexT* vertex) {
    const auto input = static_cast<std::uint32_t>(qh_pointid(qh, vertex->point));
    if (hullIndex[input] == UINT32_MAX) {
      hullIndex[input] = static_cast<std::uint32_t>(hull.mesh.vertices.size());
      hull.mesh.vertices.push_back(points[input]);
      hull.inputIndex.push_back(input);
    }
    return hullIndex[input];
  };

  facetT* facet = nullptr;
  FORALLfacets {
    const Vec3 normal(facet->normal[0], facet->normal[1], facet->normal[2]);
    hull.planes.push_back({normal, -facet->offset});
    // The facet's vertices in cyclic order; fan-triangulate, oriented along the outward normal.
    setT* cycle = qh_facet3vertex(qh, facet);
    std::vector<std::uint32_t> polygon;
    vertexT* vertex = nullptr;
    vertexT** vertexp = nullptr;
    FOREACHvertex_(cycle) polygon.push_back(hullVertex(vertex));
    qh_settempfree(qh, &cycle);
    const Vec3& a = hull.mesh.vertices[polygon[0]];
    Vec3 area = Vec3::Zero();
    for (std::size_t i = 1; i + 1 < polygon.size(); ++i) {
      area += (hull.mesh.vertices[polygon[i]] - a).cross(hull.mesh.vertices[polygon[i + 1]] - a);
    }
    const bool reversed = area.dot(normal) < 0.0;
    for (std::size_t i = 1; i + 1 < polygon.size(); ++i) {
      Triangle t{polygon[0], polygon[i], polygon[i + 1]};
      if (reversed) std::swap(t[1], t[2]);
      hull.mesh.triangles.push_back(t);
    }
  }
  return hull;
}

}  // namespace kaboum::geometry
