#include "kaboum/kinematics/geometric_constraint.hpp"

#include "kaboum/core/error.hpp"

namespace kaboum::kinematics {

CostFunction costFunctionFor(ConstraintType type, PrimitiveShape::Kind first,
                             PrimitiveShape::Kind second) {
  using K = PrimitiveShape::Kind;
  switch (type) {
    case ConstraintType::Coincident:
      if (first == K::Point && second == K::Point) return CostFunction::CoincidentPointPoint;
      if (first == K::Point && second == K::Line) return CostFunction::CoincidentPointLine;
      if (first == K::Point && second == K::Plane) return CostFunction::CoincidentPointPlane;
      if (first == K::Line && second == K::Line) return CostFunction::CoincidentLineLine;
      if (first == K::Line && second == K::Plane) return CostFunction::CoincidentLinePlane;
      if (first == K::Plane && second == K::Plane) return CostFunction::CoincidentPlanePlane;
      break;
    case ConstraintType::Parallel:
      if (first == K::Line && second == K::Line) return CostFunction::ParallelLineLine;
      if (first == K::Plane && second == K::Plane) return CostFunction::ParallelPlanePlane;
      if (first == K::Line && second == K::Plane) return CostFunction::ParallelLinePlane;
      break;
    case ConstraintType::Perpendicular:
      if (first == K::Plane && second == K::Plane) return CostFunction::PerpendicularPlanePlane;
      break;
    case ConstraintType::Distance:
      if (first == K::Point && second == K::Point) return CostFunction::DistancePointPoint;
      if (first == K::Point && second == K::Line) return CostFunction::DistancePointLine;
      if (first == K::Point && second == K::Plane) return CostFunction::DistancePointPlane;
      break;
  }
  throw InputError(toString(type) + "(" + toString(first) + ", " + toString(second) +
                   ") is not a defined constraint (Table 5.1)");
}

int costDimension(CostFunction function) {
  switch (function) {
    case CostFunction::CoincidentLineLine:
      return 4;
    case CostFunction::CoincidentPointPoint:
    case CostFunction::CoincidentPlanePlane:
      return 3;
    case CostFunction::CoincidentPointLine:
    case CostFunction::CoincidentLinePlane:
    case CostFunction::ParallelLineLine:
    case CostFunction::ParallelPlanePlane:
      return 2;
    case CostFunction::CoincidentPointPlane:
    case CostFunction::ParallelLinePlane:
    case CostFunction::PerpendicularPlanePlane:
    case CostFunction::DistancePointPoint:
    case CostFunction::DistancePointLine:
    case CostFunction::DistancePointPlane:
      return 1;
  }
  return 0;
}

std::string toString(ConstraintType type) {
  switch (type) {
    case ConstraintType::Coincident:
      return "Coincident";
    case ConstraintType::Parallel:
      return "Parallel";
    case ConstraintType::Perpendicular:
      return "Perpendicular";
    case ConstraintType::Distance:
      return "Distance";
  }
  return "?";
}

std::string toString(PrimitiveShape::Kind kind) {
  switch (kind) {
    case PrimitiveShape::Kind::Point:
      return "Point";
    case PrimitiveShape::Kind::Line:
      return "Line";
    case PrimitiveShape::Kind::Plane:
      return "Plane";
  }
  return "?";
}

}  // namespace kaboum::kinematics
