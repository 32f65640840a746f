#include "kaboum/testing/test_shapes.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <unordered_map>

namespace kaboum::testing {

using namespace kaboum::geometry;

namespace {

std::uint32_t toIndex(std::size_t index) {
  return static_cast<std::uint32_t>(index);
}

// Index of the vertex halfway along edge (a, b) on the unit sphere, created on first use.
std::uint32_t sphereMidpoint(std::uint32_t a, std::uint32_t b, TriangleMesh& mesh,
                             std::unordered_map<std::uint64_t, std::uint32_t>& midpoints) {
  const std::uint64_t key = (std::uint64_t{std::min(a, b)} << 32) | std::max(a, b);
  const auto [it, inserted] = midpoints.try_emplace(key, toIndex(mesh.vertices.size()));
  if (inserted) mesh.vertices.push_back((mesh.vertices[a] + mesh.vertices[b]).normalized());
  return it->second;
}

// Appends the quad (a, b, c, d), counter-clockwise seen from outside, as two triangles.
void addQuad(TriangleMesh& mesh, std::uint32_t a, std::uint32_t b, std::uint32_t c,
             std::uint32_t d) {
  mesh.triangles.push_back({a, b, c});
  mesh.triangles.push_back({a, c, d});
}

// Box faces as grids on the integer lattice [0, segments]^3, shared lattice points welded.
TriangleMesh makeBoxFaces(const Vec3& min, const Vec3& max, int segments, bool withTop) {
  TriangleMesh mesh;
  const int n = std::max(segments, 1);
  std::unordered_map<int, std::uint32_t> latticeIndex;
  const auto vertexAt = [&](const std::array<int, 3>& lattice) {
    const int key = (lattice[0] * (n + 1) + lattice[1]) * (n + 1) + lattice[2];
    const auto [it, inserted] = latticeIndex.try_emplace(key, toIndex(mesh.vertices.size()));
    if (inserted) {
      Vec3 position;
      for (int axis = 0; axis < 3; ++axis) {
        const double t = static_cast<double>(lattice[axis]) / n;
        position[axis] = (1.0 - t) * min[axis] + t * max[axis];
      }
      mesh.vertices.push_back(position);
    }
    return it->second;
  };
  for (int normalAxis = 0; normalAxis < 3; ++normalAxis) {
    const int u = (normalAxis + 1) % 3, v = (normalAxis + 2) % 3;  // e_u x e_v = e_normal
    for (int side = 0; side < 2; ++side) {
      if (normalAxis == 2 && side == 1 && !withTop) continue;
      for (int i = 0; i < n; ++i) {
        for (int j = 0; j < n; ++j) {
          std::array<std::uint32_t, 4> quad{};
          const std::array<std::array<int, 2>, 4> corners{
              {{i, j}, {i + 1, j}, {i + 1, j + 1}, {i, j + 1}}};
          for (std::size_t k = 0; k < 4; ++k) {
            std::array<int, 3> lattice{};
            lattice[normalAxis] = side * n;
            lattice[u] = corners[k][0];
            lattice[v] = corners[k][1];
            quad[k] = vertexAt(lattice);
          }
          if (side == 1) {
            addQuad(mesh, quad[0], quad[1], quad[2], quad[3]);
          } else {
            addQuad(mesh, quad[0], quad[3], quad[2], quad[1]);
          }
        }
      }
    }
  }
  return mesh;
}

}  // namespace

TriangleMesh makeIcosphere(int subdivisions, double radius, const Vec3& center) {
  const double t = std::numbers::phi;
  TriangleMesh mesh;
  for (const Vec3& v : {Vec3(-1, t, 0), Vec3(1, t, 0), Vec3(-1, -t, 0), Vec3(1, -t, 0),
                        Vec3(0, -1, t), Vec3(0, 1, t), Vec3(0, -1, -t), Vec3(0, 1, -t),
                        Vec3(t, 0, -1), Vec3(t, 0, 1), Vec3(-t, 0, -1), Vec3(-t, 0, 1)}) {
    mesh.vertices.push_back(v.normalized());
  }
  mesh.triangles = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                    {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                    {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                    {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
  for (int level = 0; level < subdivisions; ++level) {
    std::unordered_map<std::uint64_t, std::uint32_t> midpoints;
    std::vector<Triangle> finer;
    finer.reserve(mesh.triangles.size() * 4);
    for (const Triangle& tri : mesh.triangles) {
      const std::uint32_t ab = sphereMidpoint(tri[0], tri[1], mesh, midpoints);
      const std::uint32_t bc = sphereMidpoint(tri[1], tri[2], mesh, midpoints);
      const std::uint32_t ca = sphereMidpoint(tri[2], tri[0], mesh, midpoints);
      finer.push_back({tri[0], ab, ca});
      finer.push_back({tri[1], bc, ab});
      finer.push_back({tri[2], ca, bc});
      finer.push_back({ab, bc, ca});
    }
    mesh.triangles = std::move(finer);
  }
  for (Vec3& v : mesh.vertices) v = center + radius * v;
  return mesh;
}

TriangleMesh makeBox(const Vec3& min, const Vec3& max, int segments) {
  return makeBoxFaces(min, max, segments, true);
}

TriangleMesh makeOpenBox(const Vec3& min, const Vec3& max, int segments) {
  return makeBoxFaces(min, max, segments, false);
}

TriangleMesh makeTorus(double majorRadius, double minorRadius, int majorSegments,
                       int minorSegments) {
  TriangleMesh mesh;
  const int nu = std::max(majorSegments, 3), nv = std::max(minorSegments, 3);
  for (int i = 0; i < nu; ++i) {
    const double u = 2.0 * std::numbers::pi * i / nu;
    for (int j = 0; j < nv; ++j) {
      const double v = 2.0 * std::numbers::pi * j / nv;
      const double ring = majorRadius + minorRadius * std::cos(v);
      mesh.vertices.emplace_back(ring * std::cos(u), ring * std::sin(u), minorRadius * std::sin(v));
    }
  }
  const auto index = [&](int i, int j) {
    return toIndex(static_cast<std::size_t>((i % nu) * nv + j % nv));
  };
  for (int i = 0; i < nu; ++i) {
    for (int j = 0; j < nv; ++j) {
      addQuad(mesh, index(i, j), index(i + 1, j), index(i + 1, j + 1), index(i, j + 1));
    }
  }
  return mesh;
}

TriangleMesh makeLPrism(double height) {
  const std::array<std::array<double, 2>, 6> outline{
      {{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}}};
  TriangleMesh mesh;
  for (const double z : {0.0, height}) {
    for (const auto& [x, y] : outline) mesh.vertices.emplace_back(x, y, z);
  }
  const std::uint32_t top = 6;
  // The L split into the quads (0,1,2,3) and (0,3,4,5); the bottom is seen from below.
  addQuad(mesh, top + 0, top + 1, top + 2, top + 3);
  addQuad(mesh, top + 0, top + 3, top + 4, top + 5);
  addQuad(mesh, 0, 3, 2, 1);
  addQuad(mesh, 0, 5, 4, 3);
  for (std::uint32_t k = 0; k < 6; ++k) {
    const std::uint32_t next = (k + 1) % 6;
    addQuad(mesh, k, next, top + next, top + k);
  }
  return mesh;
}

TriangleMesh makeDoubleCone(int rimVertices) {
  TriangleMesh mesh;
  mesh.vertices = {Vec3(0, 0, 1), Vec3(0, 0, -1)};
  const std::uint32_t n = toIndex(static_cast<std::size_t>(rimVertices));
  for (std::uint32_t k = 0; k < n; ++k) {
    const double angle = 2.0 * std::numbers::pi * k / n;
    mesh.vertices.emplace_back(std::cos(angle), std::sin(angle), 0.0);
  }
  for (std::uint32_t k = 0; k < n; ++k) {
    const std::uint32_t here = 2 + k, next = 2 + (k + 1) % n;
    mesh.triangles.push_back({0, here, next});
    mesh.triangles.push_back({1, next, here});
  }
  return mesh;
}

TriangleMesh makeFannedCylinder(int segments, int rings, double height) {
  TriangleMesh mesh;
  const std::uint32_t n = toIndex(static_cast<std::size_t>(segments));
  const std::uint32_t rows = toIndex(static_cast<std::size_t>(rings));
  for (std::uint32_t r = 0; r <= rows; ++r) {
    for (std::uint32_t k = 0; k < n; ++k) {
      const double angle = 2.0 * std::numbers::pi * k / n;
      mesh.vertices.emplace_back(std::cos(angle), std::sin(angle), height * r / rows);
    }
  }
  const std::uint32_t bottom = toIndex(mesh.vertices.size()), top = bottom + 1;
  mesh.vertices.emplace_back(0.0, 0.0, 0.0);
  mesh.vertices.emplace_back(0.0, 0.0, height);
  for (std::uint32_t k = 0; k < n; ++k) {
    const std::uint32_t next = (k + 1) % n;
    for (std::uint32_t r = 0; r < rows; ++r) {
      const std::uint32_t a = r * n + k, b = r * n + next, c = (r + 1) * n + next,
                          d = (r + 1) * n + k;
      mesh.triangles.push_back({a, b, c});
      mesh.triangles.push_back({a, c, d});
    }
    mesh.triangles.push_back({bottom, next, k});
    mesh.triangles.push_back({top, rows * n + k, rows * n + next});
  }
  return mesh;
}

TriangleMesh transformMesh(const TriangleMesh& mesh, double scale, const Vec3& center,
                           const Vec3& offset) {
  TriangleMesh result = mesh;
  for (Vec3& v : result.vertices) v = center + scale * (v - center) + offset;
  return result;
}

std::vector<Vec3> pointsBelowCut(const TriangleMesh& mesh, double height) {
  std::vector<Vec3> points;
  for (const Vec3& v : mesh.vertices) {
    if (v.z() <= height) points.push_back(v);
  }
  for (const Triangle& tri : mesh.triangles) {
    for (int k = 0; k < 3; ++k) {
      const Vec3& p = mesh.vertices[tri[k]];
      const Vec3& q = mesh.vertices[tri[(k + 1) % 3]];
      if ((p.z() - height) * (q.z() - height) < 0.0) {
        points.push_back(p + (q - p) * ((height - p.z()) / (q.z() - p.z())));
      }
    }
  }
  return points;
}

TriangleMesh mergeMeshes(const TriangleMesh& first, const TriangleMesh& second) {
  TriangleMesh merged = first;
  const std::uint32_t shift = toIndex(first.vertices.size());
  merged.vertices.insert(merged.vertices.end(), second.vertices.begin(), second.vertices.end());
  for (const Triangle& tri : second.triangles) {
    merged.triangles.push_back({tri[0] + shift, tri[1] + shift, tri[2] + shift});
  }
  return merged;
}

TriangleMesh flipMesh(const TriangleMesh& mesh) {
  TriangleMesh flipped = mesh;
  for (Triangle& tri : flipped.triangles) std::swap(tri[1], tri[2]);
  return flipped;
}

}  // namespace kaboum::testing
