// Bounding swept volumes of robot motions (thesis §4.5, Proposition 3, Eq. 4.22): each convex
// piece swept over one sampling step is conv(piece at pose i ∪ piece at pose i+1), queried through
// its support mapping (never built as a hull) with the ε offset added to the query margin.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "kaboum/collision/robot_collision.hpp"
#include "kaboum/collision/swept_step.hpp"

namespace kaboum::collision {

using namespace kaboum::geometry;
using namespace kaboum::kinematics;

// conv(start ∪ end) of a convex shape at two poses: its support point in direction d is the
// better of the two poses' support points.
template <SupportMapping Shape>
class SweptSupport {
 public:
  struct Hint {
    typename Shape::Hint start{}, end{};
  };
  SweptSupport(const Shape& start, const Shape& end) : start_(start), end_(end) {}

  [[nodiscard]] Vec3 support(const Vec3& direction, Hint& hint) const {
    const Vec3 a = start_.support(direction, hint.start);
    const Vec3 b = end_.support(direction, hint.end);
    return direction.dot(b) > direction.dot(a) ? b : a;
  }
  [[nodiscard]] Vec3 center() const { return 0.5 * (start_.center() + end_.center()); }

 private:
  Shape start_, end_;
};

using SweptPiece = SweptSupport<TransformedSupport>;
static_assert(SupportMapping<SweptPiece>);

// Swept pieces of a robot along straight joint-space motions: a caller-owned workspace over the
// shared robot model, whose buffers grow to the longest motion and the most held objects seen;
// after that no query allocates. An answer depends only on the query's arguments (the objects
// `held` during the motion come with it), so one sweep serves any sequence of states.
class RobotSweep {
 public:
  // Holds a reference: `robot` must outlive it.
  explicit RobotSweep(const RobotCollisionModel& robot);

  struct Piece {
    SweptPiece shape;
    Aabb box;     // world box of both poses
    Vec3 centre;  // bounding sphere of both poses
    double radius = 0;
    std::size_t part = 0;  // RobotCollisionModel::part(part, held)
  };

  // Splits qa -> qb per part with sweepSubdivisions() (rounded up to powers of two, so that all
  // parts share the forward-kinematics samples) and returns the swept pieces: every point of every
  // part of the robot holding `held` along the motion lies within `epsilon` of one of them.
  std::span<const Piece> sweep(std::span<const double> qa, std::span<const double> qb,
                               std::span<const Attachment> held, double epsilon);

  // One part over one of its sub-steps, with bounds of all its swept pieces there: the part's box
  // at both ends merged, and the sphere holding its bounding sphere at both ends.
  struct PartStep {
    std::size_t part = 0, step = 0;
    Aabb box;
    Vec3 centre;
    double radius = 0;
  };
  // Samples qa -> qb as sweep() does and returns every part's sub-steps; stepPieces() builds the
  // swept pieces of one of them whose bounding spheres meet `region` (valid until the next
  // sampling).
  std::span<const PartStep> partSteps(std::span<const double> qa, std::span<const double> qb,
                                      std::span<const Attachment> held, double epsilon);
  void stepPieces(const PartStep& step, std::span<const Attachment> held, const Aabb& region,
                  std::vector<Piece>& out) const;

  // Definition 1 (2): the first object of `scene` in `sceneState` within margin + ε of the swept
  // volume of qa -> qb, holding `held`. Never misses an object the robot comes within `margin` of
  // anywhere along the motion.
  std::optional<std::size_t> firstSceneCollision(std::span<const double> qa,
                                                 std::span<const double> qb,
                                                 std::span<const Attachment> held,
                                                 const CollisionScene& scene,
                                                 std::span<const Placement> sceneState,
                                                 double margin, double epsilon);

  // Swept self-collision (§4.5, Eq. 4.19–4.22 applied to pairs of the robot's own parts, with its
  // collision filter): whether two parts of the robot holding `held` that it checks against each
  // other (RobotCollisionModel::checksPair) come within `margin` at the same instant of qa -> qb.
  // Each pair is compared sub-step by sub-step over the finer of its two subdivisions, with both
  // parts swept over the same time interval and queried at margin + 2ε; an interval whose swept
  // pieces meet is bisected (fresh forward kinematics at its middle, still within ε) up to
  // kSelfRefinements times, since two parts may sweep through the same place at different times of
  // one sub-step. A pair that no moving joint moves relative to each other (two fingers during an
  // arm motion) is checked once, at qa, at `margin`. Never misses a self-collision anywhere along
  // the motion; allocates nothing once the buffers have grown.
  bool selfCollides(std::span<const double> qa, std::span<const double> qb,
                    std::span<const Attachment> held, double margin, double epsilon);
  static constexpr int kSelfRefinements = 6;

  [[nodiscard]] const RobotCollisionModel& robot() const { return robot_; }
  // Number of forward-kinematics samples the last sweep used (n_max + 1).
  [[nodiscard]] std::size_t sampleCount() const { return samples_; }

 private:
  [[nodiscard]] std::span<const Pose> samplePoses(std::size_t sample) const {
    const std::size_t links = robot_.model().links().size();
    return {poses_.data() + sample * links, links};
  }
  // Whether the pose of link `linkB` relative to link `linkA` stays the same over the motion whose
  // moving variables are moved_: no moving joint lies on one of their root paths only.
  [[nodiscard]] bool rigidDuringMotion(int linkA, int linkB) const;
  // Subdivisions per part and forward kinematics at the finest one's samples; returns the finest.
  std::size_t sample(std::span<const double> qa, std::span<const double> qb,
                     std::span<const Attachment> held, double epsilon);
  struct Interval {  // [t0, t1] of the motion qa -> qb, with the link poses at both ends
    double t0, t1;
    std::span<const Pose> start, end;
  };
  // Whether parts i and j, both swept over `interval` of qa -> qb, come within `reach`, refining
  // by bisection from `depth` on.
  bool partsMeetDuring(std::size_t i, std::size_t j, std::span<const Attachment> held,
                       std::span<const double> qa, std::span<const double> qb,
                       const Interval& interval, int depth, double reach);
  // True if some piece of `a` comes within `reach` of some piece of `b` (box, bounding spheres,
  // then GJK, on the pieces within reach of the other side's overall box).
  bool anyPiecesWithin(std::span<const Piece> a, std::span<const Piece> b, double reach);
  // The swept pieces of part `part` between two link-pose sets whose bounding spheres meet
  // `region`, into `out` (resized): the others cannot come within it.
  void sweptPieces(std::size_t part, std::span<const Attachment> held, std::span<const Pose> start,
                   std::span<const Pose> end, const Aabb& region, std::vector<Piece>& out) const;

  const RobotCollisionModel& robot_;
  std::vector<LinkSweepChain> chains_;
  std::vector<std::vector<int>> linkVariables_;  // per link: the variables on its root path
  std::vector<std::uint8_t> moved_;              // per variable: whether the query moves it
  std::vector<int> subdivisions_;  // per part of the robot holding the objects of the query
  std::vector<Pose> poses_;        // samples x links
  std::vector<Pose> midPoses_;     // kSelfRefinements x links: bisection samples, one per depth
  std::vector<Piece> piecesI_, piecesJ_;  // scratch: one part's pieces over one sub-step
  std::vector<double> q_;
  std::vector<Piece> pieces_;
  std::vector<std::uint32_t> nearA_, nearB_;  // scratch of anyPiecesWithin
  std::vector<PartStep> partSteps_;
  std::size_t samples_ = 0;

  friend bool sweptVolumesCollide(RobotSweep& a, std::span<const double> qa0,
                                  std::span<const double> qa1, std::span<const Attachment> heldA,
                                  RobotSweep& b, std::span<const double> qb0,
                                  std::span<const double> qb1, std::span<const Attachment> heldB,
                                  double margin, double epsilon);
};

// Definition 1 (3): whether the swept volumes of two motions (each bounded at `epsilon`; robot a
// holding `heldA`, b holding `heldB`) come within `margin` (queried at margin + 2ε). Allocates
// only through the sweeps' buffers.
bool sweptVolumesCollide(RobotSweep& a, std::span<const double> qa0, std::span<const double> qa1,
                         std::span<const Attachment> heldA, RobotSweep& b,
                         std::span<const double> qb0, std::span<const double> qb1,
                         std::span<const Attachment> heldB, double margin, double epsilon);

}  // namespace kaboum::collision
