// The cost F(q) of a set of geometric constraints over one or more robots (thesis §5.2, Eq. 5.1):
// shapes on robot tool frames or fixed object frames, F stacked from the Table 5.1 cost
// functions, and its Jacobian ∂F/∂q, analytic or by central differences.
#pragma once

#include <Eigen/Core>
#include <span>
#include <vector>

#include "kaboum/kinematics/geometric_constraint.hpp"
#include "kaboum/kinematics/kinematic_chain.hpp"

namespace kaboum::kinematics {

enum class JacobianMode { Analytic, CentralDifferences };

class ConstraintProblem {
 public:
  // Index of a shape attached with attachToTool/attachToObject.
  using ShapeId = int;

  // Adds a robot whose chain root sits at `base` in the world; its joints follow those of the
  // robots added before it in the configuration vector. Returns the robot index.
  int addRobot(const KinematicChain& chain, const Pose& base = Pose::Identity());
  // A shape on robot `robot`'s tool frame; `tool` is the tool frame in the chain tip frame and
  // `shape` is given in the tool frame.
  ShapeId attachToTool(int robot, const Pose& tool, const PrimitiveShape& shape);
  // A shape fixed in the world (an object frame `object`, `shape` given in it).
  ShapeId attachToObject(const Pose& object, const PrimitiveShape& shape);
  // Adds constraint `type` between two attached shapes (`distance` for Distance constraints).
  // Throws InputError for incompatible primitives or unknown shape ids.
  void addConstraint(ConstraintType type, ShapeId first, ShapeId second, double distance = 0);

  [[nodiscard]] int dof() const { return dof_; }
  [[nodiscard]] int costDimension() const { return costDimension_; }
  [[nodiscard]] int robotCount() const { return static_cast<int>(robots_.size()); }
  [[nodiscard]] const KinematicChain& chain(int robot) const {
    return *robots_[static_cast<std::size_t>(robot)].chain;
  }
  [[nodiscard]] int firstVariable(int robot) const {
    return robots_[static_cast<std::size_t>(robot)].firstVariable;
  }
  // World frame of tool shape `shape` at configuration q (for evaluation and tests).
  [[nodiscard]] PrimitiveShape worldShape(ShapeId shape, std::span<const double> q) const;

  // F(q) into `cost` (size costDimension()).
  void evaluate(std::span<const double> q, Eigen::VectorXd& cost) const;
  // F(q) and J = ∂F/∂q (costDimension() × dof()). Central differences use step 1e-6.
  void evaluate(std::span<const double> q, Eigen::VectorXd& cost, Eigen::MatrixXd& jacobian,
                JacobianMode mode = JacobianMode::Analytic) const;

 private:
  struct Robot {
    const KinematicChain* chain;
    Pose base;
    int firstVariable;
  };
  struct Attachment {
    int robot;   // -1: fixed object frame
    Pose frame;  // tool frame in the tip frame, or the object frame in the world
    PrimitiveShape shape;
    Eigen::Matrix<double, 3, 2> nullBasis;  // null(d) or null(n) in the attachment frame
  };
  struct Constraint {
    CostFunction function;
    ShapeId first, second;
    double distance;
    int row;
  };
  // Per-robot tool pose and world Jacobian, filled by computeTools.
  struct ToolState {
    Pose pose = Pose::Identity();
    Jacobian jacobian;
  };
  void computeTools(std::span<const double> q, bool withJacobian) const;
  void evaluateAnalytic(Eigen::VectorXd& cost, Eigen::MatrixXd* jacobian) const;

  std::vector<Robot> robots_;
  std::vector<Attachment> attachments_;
  std::vector<Constraint> constraints_;
  int dof_ = 0;
  int costDimension_ = 0;
  mutable std::vector<ToolState> tools_;  // scratch, sized once per robot
  mutable std::vector<double> shifted_;   // scratch for central differences
  mutable Eigen::VectorXd costPlus_, costMinus_;
};

}  // namespace kaboum::kinematics
