#include "fcl_shapes.hpp"

#include <vector>

#include "kaboum/geometry/convex_hull.hpp"

namespace kaboum::cli {

using namespace kaboum::geometry;

std::shared_ptr<fcl::Convexd> fclConvex(std::span<const Vec3> points) {
  const ConvexHull hull = convexHull(points, "convex piece");
  auto vertices = std::make_shared<std::vector<fcl::Vector3d>>(hull.mesh.vertices.begin(),
                                                               hull.mesh.vertices.end());
  auto faces = std::make_shared<std::vector<int>>();
  for (const Triangle& t : hull.mesh.triangles) {
    faces->insert(faces->end(),
                  {3, static_cast<int>(t[0]), static_cast<int>(t[1]), static_cast<int>(t[2])});
  }
  return std::make_shared<fcl::Convexd>(vertices, static_cast<int>(hull.mesh.triangles.size()),
                                        faces);
}

}  // namespace kaboum::cli
