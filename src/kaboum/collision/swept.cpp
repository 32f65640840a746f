#include "kaboum/collision/swept.hpp"

#include <algorithm>
#include <bit>
#include <cstdint>
#include <limits>

namespace kaboum::collision {

using namespace kaboum::geometry;
using namespace kaboum::kinematics;

namespace {

// A region holding everything: no piece is left out for being far from it.
const Aabb kEverywhere{Vec3::Constant(-std::numeric_limits<double>::infinity()),
                       Vec3::Constant(std::numeric_limits<double>::infinity())};

}  // namespace

RobotSweep::RobotSweep(const RobotCollisionModel& robot)
    : robot_(robot), chains_(linkSweepChains(robot.model())) {
  const RobotModel& model = robot.model();
  linkVariables_.resize(model.links().size());
  // Joints are stored parent-first, so a link's parent path is complete before the link.
  for (const Joint& joint : model.joints()) {
    std::vector<int> path = linkVariables_[static_cast<std::size_t>(joint.parentLink)];
    if (joint.variable >= 0) path.push_back(joint.variable);
    linkVariables_[static_cast<std::size_t>(joint.childLink)] = std::move(path);
  }
}

bool RobotSweep::rigidDuringMotion(int linkA, int linkB) const {
  // The moving joints on the two root paths, in path order, must be the same: those are the
  // common ancestors', which move both links alike.
  const std::vector<int>& a = linkVariables_[static_cast<std::size_t>(linkA)];
  const std::vector<int>& b = linkVariables_[static_cast<std::size_t>(linkB)];
  std::size_t i = 0, j = 0;
  for (;;) {
    while (i < a.size() && !moved_[static_cast<std::size_t>(a[i])]) ++i;
    while (j < b.size() && !moved_[static_cast<std::size_t>(b[j])]) ++j;
    if (i == a.size() || j == b.size()) return i == a.size() && j == b.size();
    if (a[i] != b[j]) return false;
    ++i;
    ++j;
  }
}

std::size_t RobotSweep::sample(std::span<const double> qa, std::span<const double> qb,
                               std::span<const Attachment> held, double epsilon) {
  robot_.checkHeld(held);
  const RobotModel& model = robot_.model();
  const std::size_t links = model.links().size();
  subdivisions_.assign(robot_.partCount(held), 0);
  unsigned finest = 1;
  for (std::size_t i = 0; i < robot_.partCount(held); ++i) {
    const Attachment& part = robot_.part(i, held);
    const int n = sweepSubdivisions(chains_[static_cast<std::size_t>(part.link)], qa, qb,
                                    part.inLink.translation().norm() + part.body->reach(), epsilon);
    const unsigned rounded = std::bit_ceil(static_cast<unsigned>(n));
    subdivisions_[i] = static_cast<int>(rounded);
    finest = std::max(finest, rounded);
  }
  samples_ = finest + 1;
  poses_.resize(samples_ * links);
  q_.resize(qa.size());
  for (std::size_t s = 0; s < samples_; ++s) {
    const double t = static_cast<double>(s) / finest;
    for (std::size_t v = 0; v < q_.size(); ++v) q_[v] = qa[v] + t * (qb[v] - qa[v]);
    model.linkPoses(q_, std::span<Pose>(poses_.data() + s * links, links));
  }
  return finest;
}

void RobotSweep::sweptPieces(std::size_t part, std::span<const Attachment> held,
                             std::span<const Pose> start, std::span<const Pose> end,
                             const Aabb& region, std::vector<Piece>& out) const {
  const CollisionBody& body = *robot_.part(part, held).body;
  const Pose from = robot_.partPose(part, start, held), to = robot_.partPose(part, end, held);
  out.clear();
  for (std::size_t p = 0; p < body.pieceCount(); ++p) {
    const PieceBounds& bounds = body.pieceBounds(p);
    const Vec3 centreStart = from * bounds.centre, centreEnd = to * bounds.centre;
    const Vec3 centre = 0.5 * (centreStart + centreEnd);
    const double radius = bounds.radius + 0.5 * (centreEnd - centreStart).norm();
    if ((centre.cwiseMax(region.lo).cwiseMin(region.hi) - centre).squaredNorm() > radius * radius) {
      continue;
    }
    out.push_back(
        {SweptPiece(TransformedSupport(body.piece(p), from), TransformedSupport(body.piece(p), to)),
         transformedAabb(bounds.box, from).merged(transformedAabb(bounds.box, to)), centre, radius,
         part});
  }
}

std::span<const RobotSweep::Piece> RobotSweep::sweep(std::span<const double> qa,
                                                     std::span<const double> qb,
                                                     std::span<const Attachment> held,
                                                     double epsilon) {
  pieces_.clear();
  for (const PartStep& step : partSteps(qa, qb, held, epsilon)) {
    stepPieces(step, held, kEverywhere, piecesI_);
    pieces_.insert(pieces_.end(), piecesI_.begin(), piecesI_.end());
  }
  return pieces_;
}

std::span<const RobotSweep::PartStep> RobotSweep::partSteps(std::span<const double> qa,
                                                            std::span<const double> qb,
                                                            std::span<const Attachment> held,
                                                            double epsilon) {
  const std::size_t finest = sample(qa, qb, held, epsilon);
  partSteps_.clear();
  for (std::size_t i = 0; i < robot_.partCount(held); ++i) {
    const PieceBounds& bounds = robot_.part(i, held).body->bounds();
    const std::size_t n = static_cast<std::size_t>(subdivisions_[i]);
    const std::size_t stride = finest / n;
    for (std::size_t k = 0; k < n; ++k) {
      const Pose from = robot_.partPose(i, samplePoses(k * stride), held);
      const Pose to = robot_.partPose(i, samplePoses((k + 1) * stride), held);
      const Vec3 centreStart = from * bounds.centre, centreEnd = to * bounds.centre;
      partSteps_.push_back(
          {i, k, transformedAabb(bounds.box, from).merged(transformedAabb(bounds.box, to)),
           0.5 * (centreStart + centreEnd),
           bounds.radius + 0.5 * (centreEnd - centreStart).norm()});
    }
  }
  return partSteps_;
}

void RobotSweep::stepPieces(const PartStep& step, std::span<const Attachment> held,
                            const Aabb& region, std::vector<Piece>& out) const {
  const std::size_t stride = (samples_ - 1) / static_cast<std::size_t>(subdivisions_[step.part]);
  sweptPieces(step.part, held, samplePoses(step.step * stride),
              samplePoses((step.step + 1) * stride), region, out);
}

std::optional<std::size_t> RobotSweep::firstSceneCollision(std::span<const double> qa,
                                                           std::span<const double> qb,
                                                           std::span<const Attachment> held,
                                                           const CollisionScene& scene,
                                                           std::span<const Placement> sceneState,
                                                           double margin, double epsilon) {
  for (const PartStep& step : partSteps(qa, qb, held, epsilon)) {
    // With no scene piece near the part step's bounds, its pieces need not be built.
    if (!scene.anyPieceNear(sceneState, step.box, step.centre, step.radius, margin + epsilon)) {
      continue;
    }
    stepPieces(step, held, kEverywhere, piecesI_);
    for (const Piece& piece : piecesI_) {
      if (auto hit = scene.firstWithin(sceneState, piece.shape, piece.box, piece.centre,
                                       piece.radius, margin + epsilon)) {
        return hit;
      }
    }
  }
  return std::nullopt;
}

namespace {

// True if swept piece `pb` comes within `reach` of `pa`, whose box inflated by `reach` is `box`
// (box, then bounding spheres, then GJK).
bool pieceWithin(const RobotSweep::Piece& pa, const Aabb& box, const RobotSweep::Piece& pb,
                 double reach) {
  return box.overlaps(pb.box) && spheresWithin(pa.centre, pa.radius, pb.centre, pb.radius, reach) &&
         intersects(pa.shape, pb.shape, reach);
}

// The indices of the pieces of `pieces` whose boxes overlap `region`, into `out`.
void piecesIn(std::span<const RobotSweep::Piece> pieces, const Aabb& region,
              std::vector<std::uint32_t>& out) {
  out.clear();
  for (std::size_t p = 0; p < pieces.size(); ++p) {
    if (pieces[p].box.overlaps(region)) out.push_back(static_cast<std::uint32_t>(p));
  }
}

Aabb boxOf(std::span<const RobotSweep::Piece> pieces) {
  Aabb box = pieces.front().box;
  for (const RobotSweep::Piece& piece : pieces) box = box.merged(piece.box);
  return box;
}

}  // namespace

bool RobotSweep::anyPiecesWithin(std::span<const Piece> a, std::span<const Piece> b, double reach) {
  if (a.empty() || b.empty()) return false;
  // Only a piece within reach of the other side's overall box can meet one of its pieces: two
  // parts that come close meet along a small share of their pieces.
  piecesIn(a, boxOf(b).inflated(reach), nearA_);
  if (nearA_.empty()) return false;
  piecesIn(b, boxOf(a).inflated(reach), nearB_);
  for (const std::uint32_t i : nearA_) {
    const Piece& pa = a[i];
    const Aabb box = pa.box.inflated(reach);
    for (const std::uint32_t j : nearB_) {
      if (pieceWithin(pa, box, b[j], reach)) return true;
    }
  }
  return false;
}

bool RobotSweep::partsMeetDuring(std::size_t i, std::size_t j, std::span<const Attachment> held,
                                 std::span<const double> qa, std::span<const double> qb,
                                 const Interval& interval, int depth, double reach) {
  // The parts' bounding spheres swept over the interval contain every swept piece: apart, no
  // piece pair can meet, and the pieces need not be built; near, only the pieces near the other
  // part's swept box are.
  const auto sweptBounds = [&](std::size_t part) {
    const PieceBounds& bounds = robot_.part(part, held).body->bounds();
    const Pose from = robot_.partPose(part, interval.start, held);
    const Pose to = robot_.partPose(part, interval.end, held);
    const Vec3 start = from * bounds.centre, end = to * bounds.centre;
    return PartStep{part, 0,
                    transformedAabb(bounds.box, from).merged(transformedAabb(bounds.box, to)),
                    0.5 * (start + end), bounds.radius + 0.5 * (end - start).norm()};
  };
  const PartStep stepI = sweptBounds(i), stepJ = sweptBounds(j);
  if (!spheresWithin(stepI.centre, stepI.radius, stepJ.centre, stepJ.radius, reach)) return false;
  sweptPieces(i, held, interval.start, interval.end, stepJ.box.inflated(reach), piecesI_);
  sweptPieces(j, held, interval.start, interval.end, stepI.box.inflated(reach), piecesJ_);
  if (!anyPiecesWithin(piecesI_, piecesJ_, reach)) return false;
  if (depth == kSelfRefinements) return true;
  // Halving a sub-step keeps its chord error within ε (the bound of Eq. 4.19 only shrinks).
  const std::size_t links = robot_.model().links().size();
  const std::span<Pose> middle(midPoses_.data() + static_cast<std::size_t>(depth) * links, links);
  const double tm = 0.5 * (interval.t0 + interval.t1);
  for (std::size_t v = 0; v < q_.size(); ++v) q_[v] = qa[v] + tm * (qb[v] - qa[v]);
  robot_.model().linkPoses(q_, middle);
  return partsMeetDuring(i, j, held, qa, qb, {interval.t0, tm, interval.start, middle}, depth + 1,
                         reach) ||
         partsMeetDuring(i, j, held, qa, qb, {tm, interval.t1, middle, interval.end}, depth + 1,
                         reach);
}

bool RobotSweep::selfCollides(std::span<const double> qa, std::span<const double> qb,
                              std::span<const Attachment> held, double margin, double epsilon) {
  const std::size_t finest = sample(qa, qb, held, epsilon);
  midPoses_.resize(static_cast<std::size_t>(kSelfRefinements) * robot_.model().links().size());
  const double reach = margin + 2 * epsilon;
  moved_.resize(qa.size());
  for (std::size_t v = 0; v < qa.size(); ++v) moved_[v] = qa[v] != qb[v];
  const std::size_t count = robot_.partCount(held);
  for (std::size_t i = 0; i < count; ++i) {
    for (std::size_t j = i + 1; j < count; ++j) {
      if (!robot_.checksPair(i, j, held)) continue;
      const Attachment &partI = robot_.part(i, held), &partJ = robot_.part(j, held);
      if (rigidDuringMotion(partI.link, partJ.link)) {
        // Their distance is the same all along the motion: one static check is exact.
        if (bodiesCollide(*partI.body, robot_.partPose(i, samplePoses(0), held), *partJ.body,
                          robot_.partPose(j, samplePoses(0), held), margin)) {
          return true;
        }
        continue;
      }
      const auto steps = static_cast<std::size_t>(std::max(subdivisions_[i], subdivisions_[j]));
      const std::size_t stride = finest / steps;
      for (std::size_t k = 0; k < steps; ++k) {
        const Interval interval{static_cast<double>(k * stride) / static_cast<double>(finest),
                                static_cast<double>((k + 1) * stride) / static_cast<double>(finest),
                                samplePoses(k * stride), samplePoses((k + 1) * stride)};
        if (partsMeetDuring(i, j, held, qa, qb, interval, 0, reach)) {
          return true;
        }
      }
    }
  }
  return false;
}

bool sweptVolumesCollide(RobotSweep& a, std::span<const double> qa0, std::span<const double> qa1,
                         std::span<const Attachment> heldA, RobotSweep& b,
                         std::span<const double> qb0, std::span<const double> qb1,
                         std::span<const Attachment> heldB, double margin, double epsilon) {
  const double reach = margin + 2 * epsilon;
  const auto stepsB = b.partSteps(qb0, qb1, heldB, epsilon);
  const auto stepsA = a.partSteps(qa0, qa1, heldA, epsilon);
  // Part steps first: only the pieces of part steps whose bounds come within reach, and of those
  // only the pieces near the other step's box, are built and compared.
  for (const RobotSweep::PartStep& stepA : stepsA) {
    const Aabb boxA = stepA.box.inflated(reach);
    for (const RobotSweep::PartStep& stepB : stepsB) {
      if (!boxA.overlaps(stepB.box) ||
          !spheresWithin(stepA.centre, stepA.radius, stepB.centre, stepB.radius, reach)) {
        continue;
      }
      a.stepPieces(stepA, heldA, stepB.box.inflated(reach), a.piecesI_);
      b.stepPieces(stepB, heldB, boxA, b.piecesJ_);
      if (a.anyPiecesWithin(a.piecesI_, b.piecesJ_, reach)) return true;
    }
  }
  return false;
}

}  // namespace kaboum::collision
