#include "kaboum/collision/gjk.hpp"

namespace kaboum::collision::detail {
namespace {

// The closest point of a face of the simplex: which points it keeps and their weights.
struct FaceSolution {
  std::array<int, 4> index{};
  std::array<double, 4> lambda{};
  int count = 0;
  Vec3 point = Vec3::Zero();
  double squaredNorm = 0.0;
};

bool sameSign(double a, double b) {
  return (a > 0.0 && b > 0.0) || (a < 0.0 && b < 0.0);
}

void setVertex(const Vec3* w, int i, FaceSolution& out) {
  out.count = 1;
  out.index[0] = i;
  out.lambda[0] = 1.0;
  out.point = w[i];
  out.squaredNorm = out.point.squaredNorm();
}

void keepCloser(const FaceSolution& candidate, FaceSolution& best) {
  if (best.count == 0 || candidate.squaredNorm < best.squaredNorm) best = candidate;
}

// Segment (Montanari's S1D): the origin's projection parameter along the segment.
void closestOnSegment(const Vec3* w, int i0, int i1, FaceSolution& out) {
  const Vec3 t = w[i1] - w[i0];
  const double tt = t.squaredNorm();
  const double mu = tt > 0.0 ? -w[i0].dot(t) / tt : 0.0;
  if (mu <= 0.0) return setVertex(w, i0, out);
  if (mu >= 1.0) return setVertex(w, i1, out);
  out.count = 2;
  out.index[0] = i0;
  out.index[1] = i1;
  out.lambda[0] = 1.0 - mu;
  out.lambda[1] = mu;
  // Exactly orthogonal to the segment: a rounding error along it would bias every later lower
  // bound w.v / |v| by about eps |w| / |v| when the distance is tiny.
  const Vec3 point = w[i0] + mu * t;
  out.point = point - t * (point.dot(t) / tt);
  out.squaredNorm = out.point.squaredNorm();
}

// Replaces `best` by the segment's solution when that is closer (or `best` is still empty).
void closerOnSegment(const Vec3* w, int i0, int i1, FaceSolution& best) {
  FaceSolution candidate;
  closestOnSegment(w, i0, i1, candidate);
  keepCloser(candidate, best);
}

// Triangle (S2D): project the origin on the plane, then compare signed areas in the coordinate
// plane where the triangle's projection is largest; edges facing the origin are tried otherwise.
void closestOnTriangle(const Vec3* w, int i0, int i1, int i2, FaceSolution& out) {
  const Vec3& p0 = w[i0];
  const Vec3& p1 = w[i1];
  const Vec3& p2 = w[i2];
  const Vec3 e1 = p1 - p0;
  const Vec3 e2 = p2 - p0;
  const Vec3 n = e1.cross(e2);
  const double nn = n.squaredNorm();
  // Flat (sine of the angle below 1e-12): only the edges are meaningful.
  if (nn > 1e-24 * e1.squaredNorm() * e2.squaredNorm()) {
    const Vec3 projected = n * (p0.dot(n) / nn);
    Eigen::Index largest = 0;
    n.cwiseAbs().maxCoeff(&largest);
    const int axis = static_cast<int>(largest);
    const int j = (axis + 1) % 3;
    const int k = (axis + 2) % 3;
    auto area = [j, k](const Vec3& a, const Vec3& b, const Vec3& c) {
      return (b[j] - a[j]) * (c[k] - a[k]) - (b[k] - a[k]) * (c[j] - a[j]);
    };
    const std::array<double, 3> c = {area(projected, p1, p2), area(p0, projected, p2),
                                     area(p0, p1, projected)};
    const double total = n[axis];
    if (sameSign(total, c[0]) && sameSign(total, c[1]) && sameSign(total, c[2])) {
      out.count = 3;
      out.index = {i0, i1, i2, 0};
      out.lambda = {c[0] / total, c[1] / total, c[2] / total, 0.0};
      // The projection itself, exactly along the normal (see closestOnSegment).
      out.point = projected;
      out.squaredNorm = out.point.squaredNorm();
      return;
    }
    out.count = 0;
    if (!sameSign(total, c[0])) closerOnSegment(w, i1, i2, out);
    if (!sameSign(total, c[1])) closerOnSegment(w, i0, i2, out);
    if (!sameSign(total, c[2])) closerOnSegment(w, i0, i1, out);
    return;
  }
  out.count = 0;
  closerOnSegment(w, i0, i1, out);
  closerOnSegment(w, i0, i2, out);
  closerOnSegment(w, i1, i2, out);
}

double determinant(const Vec3& a, const Vec3& b, const Vec3& c) {
  return a.dot(b.cross(c));
}

// Signed volumes of the tetrahedron (w0, w1, w2, w3) with the origin in place of each vertex;
// they sum to the whole volume.
std::array<double, 4> signedVolumes(const Vec3& w0, const Vec3& w1, const Vec3& w2,
                                    const Vec3& w3) {
  return {determinant(w1, w2, w3), -determinant(w0, w2, w3), determinant(w0, w1, w3),
          -determinant(w0, w1, w2)};
}

bool allShareSign(double total, const std::array<double, 4>& c) {
  return sameSign(total, c[0]) && sameSign(total, c[1]) && sameSign(total, c[2]) &&
         sameSign(total, c[3]);
}

// Tetrahedron (S3D): signed volumes with the origin in place of each vertex; they all share the
// sign of the whole volume exactly when the origin is inside. Returns true then.
bool closestOnTetrahedron(const Vec3* w, FaceSolution& out) {
  const std::array<double, 4> c = signedVolumes(w[0], w[1], w[2], w[3]);
  const double total = c[0] + c[1] + c[2] + c[3];
  if (allShareSign(total, c)) {
    out.count = 4;
    out.index = {0, 1, 2, 3};
    for (int i = 0; i < 4; ++i) out.lambda[i] = c[i] / total;
    out.point = Vec3::Zero();
    out.squaredNorm = 0.0;
    return true;
  }
  out.count = 0;
  const auto closerOnTriangle = [&](int i0, int i1, int i2) {
    FaceSolution candidate;
    closestOnTriangle(w, i0, i1, i2, candidate);
    keepCloser(candidate, out);
  };
  if (!sameSign(total, c[0])) closerOnTriangle(1, 2, 3);
  if (!sameSign(total, c[1])) closerOnTriangle(0, 2, 3);
  if (!sameSign(total, c[2])) closerOnTriangle(0, 1, 3);
  if (!sameSign(total, c[3])) closerOnTriangle(0, 1, 2);
  return false;
}

}  // namespace

bool reduceSimplex(Simplex& simplex, Vec3& closest) {
  FaceSolution solution;
  bool inside = false;
  switch (simplex.size) {
    case 1:
      setVertex(simplex.w.data(), 0, solution);
      break;
    case 2:
      closestOnSegment(simplex.w.data(), 0, 1, solution);
      break;
    case 3:
      closestOnTriangle(simplex.w.data(), 0, 1, 2, solution);
      break;
    default:
      inside = closestOnTetrahedron(simplex.w.data(), solution);
      break;
  }
  // Compact the kept points to the front (indices are increasing, so in place is safe).
  for (int i = 0; i < solution.count; ++i) {
    const int from = solution.index[i];
    simplex.w[i] = simplex.w[from];
    simplex.kept[i] = from;
    simplex.lambda[i] = solution.lambda[i];
  }
  simplex.size = solution.count;
  closest = solution.point;
  return inside;
}

bool originInsideTetrahedron(const Vec3& w0, const Vec3& w1, const Vec3& w2, const Vec3& w3) {
  const std::array<double, 4> c = signedVolumes(w0, w1, w2, w3);
  return allShareSign(c[0] + c[1] + c[2] + c[3], c);
}

}  // namespace kaboum::collision::detail
