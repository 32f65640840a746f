#include "kaboum/kinematics/constraint_problem.hpp"

#include <cmath>

#include "kaboum/core/error.hpp"

namespace kaboum::kinematics {
namespace {

// World quantities of one constrained shape and what moves it.
struct Side {
  Eigen::Vector3d point;
  Eigen::Vector3d direction;
  Eigen::Matrix<double, 3, 2> nullBasis;
  const Jacobian* jacobian = nullptr;  // world tool Jacobian of the robot; null for objects
  Eigen::Vector3d toolOrigin{0, 0, 0};
  Eigen::Index firstColumn = 0;
};

// Adds the derivative terms of cost row `row`; each helper covers one way a shape can move.
class RowDerivative {
 public:
  RowDerivative(Eigen::MatrixXd* jacobian, Eigen::Index row) : jacobian_(jacobian), row_(row) {}

  // d/dq of a vector rigidly attached to `side`, dotted with w: (ω × a)·b = ωᵀ (a × b).
  void rotating(const Side& side, const Eigen::Vector3d& aCrossB, double scale = 1) const {
    if (jacobian_ == nullptr || side.jacobian == nullptr) return;
    jacobian_->row(row_).segment(side.firstColumn, side.jacobian->cols()) +=
        scale * aCrossB.transpose() * side.jacobian->bottomRows<3>();
  }
  // d/dq of a · p for a point p attached to `side` (a held fixed):
  // aᵀ (v + ω × (p − o)) = aᵀ v + ((p − o) × a)ᵀ ω.
  void translating(const Side& side, const Eigen::Vector3d& a, const Eigen::Vector3d& p,
                   double scale) const {
    if (jacobian_ == nullptr || side.jacobian == nullptr) return;
    auto row = jacobian_->row(row_).segment(side.firstColumn, side.jacobian->cols());
    row += scale * a.transpose() * side.jacobian->topRows<3>();
    row += scale * (p - side.toolOrigin).cross(a).transpose() * side.jacobian->bottomRows<3>();
  }
  // f = a · (p1 − p2) with a attached to side `owner`.
  void dotDifference(const Side& owner, const Eigen::Vector3d& a, const Side& first,
                     const Side& second, double scale = 1) const {
    rotating(owner, a.cross(first.point - second.point), scale);
    translating(first, a, first.point, scale);
    translating(second, a, second.point, -scale);
  }
  // f = a · b with a attached to side `sideA` and b to `sideB`.
  void dotDirections(const Side& sideA, const Eigen::Vector3d& a, const Side& sideB,
                     const Eigen::Vector3d& b) const {
    rotating(sideA, a.cross(b));
    rotating(sideB, b.cross(a));
  }

 private:
  Eigen::MatrixXd* jacobian_;
  Eigen::Index row_;
};

}  // namespace

int ConstraintProblem::addRobot(const KinematicChain& chain, const Pose& base) {
  robots_.push_back({&chain, base, dof_});
  dof_ += chain.dof();
  tools_.emplace_back();
  tools_.back().jacobian.resize(6, chain.dof());
  shifted_.resize(static_cast<std::size_t>(dof_));
  return static_cast<int>(robots_.size()) - 1;
}

ConstraintProblem::ShapeId ConstraintProblem::attachToTool(int robot, const Pose& tool,
                                                           const PrimitiveShape& shape) {
  if (robot < 0 || robot >= robotCount()) {
    throw InputError("shape attached to unknown robot " + std::to_string(robot));
  }
  Eigen::Matrix<double, 3, 2> basis;
  basis.col(0) = shape.direction.unitOrthogonal();
  basis.col(1) = shape.direction.cross(basis.col(0));
  attachments_.push_back({robot, tool, shape, basis});
  return static_cast<ShapeId>(attachments_.size()) - 1;
}

ConstraintProblem::ShapeId ConstraintProblem::attachToObject(const Pose& object,
                                                             const PrimitiveShape& shape) {
  Eigen::Matrix<double, 3, 2> basis;
  basis.col(0) = shape.direction.unitOrthogonal();
  basis.col(1) = shape.direction.cross(basis.col(0));
  attachments_.push_back({-1, object, shape, basis});
  return static_cast<ShapeId>(attachments_.size()) - 1;
}

void ConstraintProblem::addConstraint(ConstraintType type, ShapeId first, ShapeId second,
                                      double distance) {
  const auto count = static_cast<ShapeId>(attachments_.size());
  if (first < 0 || first >= count || second < 0 || second >= count) {
    throw InputError("constraint refers to an unknown shape");
  }
  const CostFunction function =
      costFunctionFor(type, attachments_[static_cast<std::size_t>(first)].shape.kind,
                      attachments_[static_cast<std::size_t>(second)].shape.kind);
  if (type == ConstraintType::Distance && !(distance >= 0)) {
    throw InputError("Distance constraint needs a non-negative distance");
  }
  constraints_.push_back({function, first, second, distance, costDimension_});
  costDimension_ += kaboum::kinematics::costDimension(function);
}

void ConstraintProblem::computeTools(std::span<const double> q, bool withJacobian) const {
  for (std::size_t r = 0; r < robots_.size(); ++r) {
    const Robot& robot = robots_[r];
    ToolState& tool = tools_[r];
    const auto values = q.subspan(static_cast<std::size_t>(robot.firstVariable),
                                  static_cast<std::size_t>(robot.chain->dof()));
    if (withJacobian) {
      tool.pose = robot.base * robot.chain->toolPoseAndJacobian(values, tool.jacobian);
      tool.jacobian.topRows<3>() = robot.base.linear() * tool.jacobian.topRows<3>();
      tool.jacobian.bottomRows<3>() = robot.base.linear() * tool.jacobian.bottomRows<3>();
    } else {
      tool.pose = robot.base * robot.chain->toolPose(values);
    }
  }
}

PrimitiveShape ConstraintProblem::worldShape(ShapeId shape, std::span<const double> q) const {
  computeTools(q, false);
  const Attachment& a = attachments_[static_cast<std::size_t>(shape)];
  const Pose frame =
      a.robot >= 0 ? tools_[static_cast<std::size_t>(a.robot)].pose * a.frame : a.frame;
  return {a.shape.kind, frame * a.shape.point, frame.linear() * a.shape.direction};
}

void ConstraintProblem::evaluate(std::span<const double> q, Eigen::VectorXd& cost) const {
  cost.resize(costDimension_);
  computeTools(q, false);
  evaluateAnalytic(cost, nullptr);
}

void ConstraintProblem::evaluate(std::span<const double> q, Eigen::VectorXd& cost,
                                 Eigen::MatrixXd& jacobian, JacobianMode mode) const {
  jacobian.resize(costDimension_, dof_);
  if (mode == JacobianMode::Analytic) {
    cost.resize(costDimension_);
    computeTools(q, true);
    jacobian.setZero();
    evaluateAnalytic(cost, &jacobian);
    return;
  }
  // Algorithm 3's CentralDifferences(F, q), kept for cross-checking the analytic derivatives.
  constexpr double kStep = 1e-6;
  std::copy(q.begin(), q.end(), shifted_.begin());
  costPlus_.resize(costDimension_);
  costMinus_.resize(costDimension_);
  for (int j = 0; j < dof_; ++j) {
    const auto index = static_cast<std::size_t>(j);
    shifted_[index] = q[index] + kStep;
    evaluate(shifted_, costPlus_);
    shifted_[index] = q[index] - kStep;
    evaluate(shifted_, costMinus_);
    shifted_[index] = q[index];
    jacobian.col(j) = (costPlus_ - costMinus_) / (2 * kStep);
  }
  evaluate(q, cost);
}

void ConstraintProblem::evaluateAnalytic(Eigen::VectorXd& cost, Eigen::MatrixXd* jacobian) const {
  const auto side = [&](ShapeId id) {
    const Attachment& a = attachments_[static_cast<std::size_t>(id)];
    Side s;
    Pose frame = a.frame;
    if (a.robot >= 0) {
      const ToolState& tool = tools_[static_cast<std::size_t>(a.robot)];
      frame = tool.pose * a.frame;
      s.jacobian = &tool.jacobian;
      s.toolOrigin = tool.pose.translation();
      s.firstColumn = robots_[static_cast<std::size_t>(a.robot)].firstVariable;
    }
    s.point = frame * a.shape.point;
    s.direction = frame.linear() * a.shape.direction;
    s.nullBasis = frame.linear() * a.nullBasis;
    return s;
  };
  for (const Constraint& c : constraints_) {
    const Side s1 = side(c.first);
    const Side s2 = side(c.second);
    const Eigen::Vector3d r = s1.point - s2.point;
    const auto row = [&](int k) { return RowDerivative(jacobian, c.row + k); };
    auto f = cost.segment(c.row, kaboum::kinematics::costDimension(c.function));
    switch (c.function) {
      case CostFunction::CoincidentPointPoint:
        f = r;
        for (int k = 0; k < 3; ++k) {
          const Eigen::Vector3d axis = Eigen::Vector3d::Unit(k);
          row(k).translating(s1, axis, s1.point, 1);
          row(k).translating(s2, axis, s2.point, -1);
        }
        break;
      case CostFunction::CoincidentPointLine:
        f = s2.nullBasis.transpose() * r;
        for (int k = 0; k < 2; ++k) row(k).dotDifference(s2, s2.nullBasis.col(k), s1, s2);
        break;
      case CostFunction::CoincidentPointPlane:
        f(0) = s2.direction.dot(r);
        row(0).dotDifference(s2, s2.direction, s1, s2);
        break;
      case CostFunction::CoincidentLineLine:
        for (int k = 0; k < 2; ++k) {
          f(k) = s1.nullBasis.col(k).dot(r);
          row(k).dotDifference(s1, s1.nullBasis.col(k), s1, s2);
          f(2 + k) = s1.nullBasis.col(k).dot(s2.direction);
          row(2 + k).dotDirections(s1, s1.nullBasis.col(k), s2, s2.direction);
        }
        break;
      case CostFunction::CoincidentLinePlane:
        f(0) = s2.direction.dot(r);
        row(0).dotDifference(s2, s2.direction, s1, s2);
        f(1) = s2.direction.dot(s1.direction);
        row(1).dotDirections(s2, s2.direction, s1, s1.direction);
        break;
      case CostFunction::CoincidentPlanePlane:
        f(0) = s2.direction.dot(r);
        row(0).dotDifference(s2, s2.direction, s1, s2);
        for (int k = 0; k < 2; ++k) {
          f(1 + k) = s2.direction.dot(s1.nullBasis.col(k));
          row(1 + k).dotDirections(s2, s2.direction, s1, s1.nullBasis.col(k));
        }
        break;
      case CostFunction::ParallelLineLine:
      case CostFunction::ParallelPlanePlane:
        for (int k = 0; k < 2; ++k) {
          f(k) = s1.nullBasis.col(k).dot(s2.direction);
          row(k).dotDirections(s1, s1.nullBasis.col(k), s2, s2.direction);
        }
        break;
      case CostFunction::ParallelLinePlane:
      case CostFunction::PerpendicularPlanePlane:
        f(0) = s2.direction.dot(s1.direction);
        row(0).dotDirections(s2, s2.direction, s1, s1.direction);
        break;
      case CostFunction::DistancePointPoint: {
        // §5.2.3: at p1 = p2 the norm has no gradient; any unit direction keeps the step non-zero.
        const double length = r.norm();
        const Eigen::Vector3d unit =
            length > 1e-12 ? Eigen::Vector3d(r / length) : Eigen::Vector3d::UnitX();
        f(0) = length - c.distance;
        row(0).translating(s1, unit, s1.point, 1);
        row(0).translating(s2, unit, s2.point, -1);
        break;
      }
      case CostFunction::DistancePointLine: {
        // §5.2.3: the squared cost peaks on the line itself; step along a fixed normal there.
        const Eigen::Vector2d offset = s2.nullBasis.transpose() * r;
        const double length = offset.norm();
        const Eigen::Vector2d unit =
            length > 1e-12 ? Eigen::Vector2d(offset / length) : Eigen::Vector2d::UnitX();
        f(0) = length - c.distance;
        for (int k = 0; k < 2; ++k) row(0).dotDifference(s2, s2.nullBasis.col(k), s1, s2, unit(k));
        break;
      }
      case CostFunction::DistancePointPlane: {
        const double signedDistance = s2.direction.dot(r);
        f(0) = std::abs(signedDistance) - c.distance;
        row(0).dotDifference(s2, s2.direction, s1, s2, signedDistance < 0 ? -1.0 : 1.0);
        break;
      }
    }
  }
}

}  // namespace kaboum::kinematics
