// Geometric constraints between primitive shapes (thesis §5.2, Table 5.1): coincidence,
// parallelism, perpendicularity and distance between points, lines and planes.
#pragma once

#include <Eigen/Core>
#include <string>

namespace kaboum::kinematics {

// A primitive shape in some frame: a point p, a line (p, d) or a plane (p, n); d and n are unit.
struct PrimitiveShape {
  enum class Kind { Point, Line, Plane };
  Kind kind = Kind::Point;
  Eigen::Vector3d point{0, 0, 0};
  Eigen::Vector3d direction{0, 0, 1};  // line direction d or plane normal n; unused for points

  static PrimitiveShape makePoint(const Eigen::Vector3d& p) { return {Kind::Point, p, {0, 0, 1}}; }
  static PrimitiveShape makeLine(const Eigen::Vector3d& p, const Eigen::Vector3d& d) {
    return {Kind::Line, p, d.normalized()};
  }
  static PrimitiveShape makePlane(const Eigen::Vector3d& p, const Eigen::Vector3d& n) {
    return {Kind::Plane, p, n.normalized()};
  }
};

enum class ConstraintType { Coincident, Parallel, Perpendicular, Distance };

// The cost function of a constraint type between two shape kinds, in the order Table 5.1 lists
// them (first shape, second shape). Coincident(Line, Plane) is not in Table 5.1 but is used by
// Figure 5.4b; its cost n₂ᵀ[(p₁ − p₂) d₁] follows the table's pattern.
enum class CostFunction {
  CoincidentPointPoint,     // p1 − p2                         (3)
  CoincidentPointLine,      // null(d2)ᵀ (p1 − p2)             (2)
  CoincidentPointPlane,     // n2ᵀ (p1 − p2)                   (1)
  CoincidentLineLine,       // null(d1)ᵀ [(p1 − p2) d2]        (4)
  CoincidentLinePlane,      // n2ᵀ [(p1 − p2) d1]              (2)
  CoincidentPlanePlane,     // n2ᵀ [(p1 − p2) null(n1)]        (3)
  ParallelLineLine,         // null(d1)ᵀ d2                    (2)
  ParallelPlanePlane,       // null(n1)ᵀ n2                    (2)
  ParallelLinePlane,        // n2ᵀ d1                          (1)
  PerpendicularPlanePlane,  // n1ᵀ n2                          (1)
  DistancePointPoint,       // ‖p1 − p2‖ − d                   (1)
  DistancePointLine,        // ‖null(d2)ᵀ (p1 − p2)‖ − d       (1)
  DistancePointPlane,       // |n2ᵀ (p1 − p2)| − d             (1)
};

// The cost function for `type` between `first` and `second`, or InputError naming the
// incompatible pair (e.g. "Parallel(Point, Line) is not defined").
CostFunction costFunctionFor(ConstraintType type, PrimitiveShape::Kind first,
                             PrimitiveShape::Kind second);
// Number of cost components c (the constrained degrees of freedom, Table 5.1).
int costDimension(CostFunction function);
std::string toString(ConstraintType type);
std::string toString(PrimitiveShape::Kind kind);

}  // namespace kaboum::kinematics
