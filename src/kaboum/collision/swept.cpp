#include "kaboum/collision/swept.hpp"

#include <algorithm>
#include <bit>
#include <limits>
#include <numeric>

namespace kaboum::collision {

using namespace kaboum::geometry;
using namespace kaboum::kinematics;

RobotSweep::RobotSweep(const RobotCollisionModel& robot)
    : robot_(robot), chains_(linkSweepChains(robot.model())) {}

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
                             std::vector<Piece>& out) const {
  const CollisionBody& body = *robot_.part(part, held).body;
  const Pose from = robot_.partPose(part, start, held), to = robot_.partPose(part, end, held);
  out.clear();
  for (std::size_t p = 0; p < body.pieceCount(); ++p) {
    const PieceBounds& bounds = body.pieceBounds(p);
    const Vec3 centreStart = from * bounds.centre, centreEnd = to * bounds.centre;
    out.push_back(
        {SweptPiece(TransformedSupport(body.piece(p), from), TransformedSupport(body.piece(p), to)),
         transformedAabb(bounds.box, from).merged(transformedAabb(bounds.box, to)),
         0.5 * (centreStart + centreEnd), bounds.radius + 0.5 * (centreEnd - centreStart).norm(),
         part});
  }
}

std::span<const RobotSweep::Piece> RobotSweep::sweep(std::span<const double> qa,
                                                     std::span<const double> qb,
                                                     std::span<const Attachment> held,
                                                     double epsilon) {
  constexpr double kEverywhere = std::numeric_limits<double>::infinity();
  return sweepNear(qa, qb, held, epsilon,
                   {Vec3::Constant(-kEverywhere), Vec3::Constant(kEverywhere)});
}

std::span<const RobotSweep::Piece> RobotSweep::sweepNear(std::span<const double> qa,
                                                         std::span<const double> qb,
                                                         std::span<const Attachment> held,
                                                         double epsilon, const Aabb& region) {
  const std::size_t finest = sample(qa, qb, held, epsilon);
  pieces_.clear();
  for (std::size_t i = 0; i < robot_.partCount(held); ++i) {
    const Aabb& box = robot_.part(i, held).body->bounds().box;
    const std::size_t n = static_cast<std::size_t>(subdivisions_[i]);
    const std::size_t stride = finest / n;
    for (std::size_t k = 0; k < n; ++k) {
      const std::span<const Pose> start = samplePoses(k * stride),
                                  end = samplePoses((k + 1) * stride);
      // The part's box at both ends contains its swept pieces' boxes over the sub-step.
      const Aabb swept = transformedAabb(box, robot_.partPose(i, start, held))
                             .merged(transformedAabb(box, robot_.partPose(i, end, held)));
      if (!swept.overlaps(region)) continue;
      sweptPieces(i, held, start, end, piecesI_);
      pieces_.insert(pieces_.end(), piecesI_.begin(), piecesI_.end());
    }
  }
  return pieces_;
}

std::optional<std::size_t> RobotSweep::firstSceneCollision(std::span<const double> qa,
                                                           std::span<const double> qb,
                                                           std::span<const Attachment> held,
                                                           const CollisionScene& scene,
                                                           std::span<const Placement> sceneState,
                                                           double margin, double epsilon) {
  const std::size_t finest = sample(qa, qb, held, epsilon);
  for (std::size_t i = 0; i < robot_.partCount(held); ++i) {
    const PieceBounds& bounds = robot_.part(i, held).body->bounds();
    const std::size_t n = static_cast<std::size_t>(subdivisions_[i]);
    const std::size_t stride = finest / n;
    for (std::size_t k = 0; k < n; ++k) {
      const std::span<const Pose> start = samplePoses(k * stride),
                                  end = samplePoses((k + 1) * stride);
      // The part's swept box and bounding sphere contain its swept pieces: with no scene piece
      // near them, the pieces need not be built.
      const Pose from = robot_.partPose(i, start, held), to = robot_.partPose(i, end, held);
      const Vec3 centreStart = from * bounds.centre, centreEnd = to * bounds.centre;
      if (!scene.anyPieceNear(
              sceneState, transformedAabb(bounds.box, from).merged(transformedAabb(bounds.box, to)),
              0.5 * (centreStart + centreEnd),
              bounds.radius + 0.5 * (centreEnd - centreStart).norm(), margin + epsilon)) {
        continue;
      }
      sweptPieces(i, held, start, end, piecesI_);
      for (const Piece& piece : piecesI_) {
        if (auto hit = scene.firstWithin(sceneState, piece.shape, piece.box, piece.centre,
                                         piece.radius, margin + epsilon)) {
          return hit;
        }
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

// True if some swept piece of `a` comes within `reach` of some swept piece of `b`.
bool anyPiecesWithin(std::span<const RobotSweep::Piece> a, std::span<const RobotSweep::Piece> b,
                     double reach) {
  for (const RobotSweep::Piece& pa : a) {
    const Aabb box = pa.box.inflated(reach);
    for (const RobotSweep::Piece& pb : b) {
      if (pieceWithin(pa, box, pb, reach)) return true;
    }
  }
  return false;
}

// The same verdict for many pieces (two robots' whole sweeps), by sweep and prune along one axis:
// the axis on which the two sweeps' overall boxes overlap least (relative to b's extent), `order`
// (scratch) b's pieces sorted by their boxes' lower end on it, and each piece of `a` meets only the
// pieces of b whose ranges on it overlap its inflated box. Allocates nothing once `order` has
// grown.
bool anyPiecesWithinSorted(std::span<const RobotSweep::Piece> a,
                           std::span<const RobotSweep::Piece> b, double reach,
                           std::vector<std::uint32_t>& order) {
  if (a.empty() || b.empty()) return false;
  Aabb all{a[0].box}, bAll{b[0].box};
  for (const RobotSweep::Piece& pa : a) all = all.merged(pa.box);
  for (const RobotSweep::Piece& pb : b) bAll = bAll.merged(pb.box);
  int axis = 0;
  double least = std::numeric_limits<double>::infinity();
  for (int k = 0; k < 3; ++k) {
    const double overlap = std::min(all.hi[k], bAll.hi[k]) - std::max(all.lo[k], bAll.lo[k]);
    const double share = overlap / std::max(bAll.hi[k] - bAll.lo[k], 1e-12);
    if (share < least) {
      least = share;
      axis = k;
    }
  }
  order.resize(b.size());
  std::iota(order.begin(), order.end(), 0U);
  const auto lower = [&](std::uint32_t i) { return b[i].box.lo[axis]; };
  std::sort(order.begin(), order.end(),
            [&](std::uint32_t i, std::uint32_t j) { return lower(i) < lower(j); });
  double widest = 0;  // of b's boxes on the axis: a box reaching x starts at x - widest or later
  for (const RobotSweep::Piece& pb : b) {
    widest = std::max(widest, pb.box.hi[axis] - pb.box.lo[axis]);
  }
  for (const RobotSweep::Piece& pa : a) {
    const Aabb box = pa.box.inflated(reach);
    auto it = std::lower_bound(order.begin(), order.end(), box.lo[axis] - widest,
                               [&](std::uint32_t i, double x) { return lower(i) < x; });
    for (; it != order.end() && lower(*it) <= box.hi[axis]; ++it) {
      if (pieceWithin(pa, box, b[*it], reach)) return true;
    }
  }
  return false;
}

}  // namespace

bool RobotSweep::partsMeetDuring(std::size_t i, std::size_t j, std::span<const Attachment> held,
                                 std::span<const double> qa, std::span<const double> qb,
                                 const Interval& interval, int depth, double reach) {
  // The parts' bounding spheres swept over the interval contain every swept piece: apart, no
  // piece pair can meet, and the pieces need not be built.
  const auto sweptSphere = [&](std::size_t part) {
    const PieceBounds& bounds = robot_.part(part, held).body->bounds();
    const Vec3 start = robot_.partPose(part, interval.start, held) * bounds.centre;
    const Vec3 end = robot_.partPose(part, interval.end, held) * bounds.centre;
    return std::pair{0.5 * (start + end), bounds.radius + 0.5 * (end - start).norm()};
  };
  const auto [centreI, radiusI] = sweptSphere(i);
  const auto [centreJ, radiusJ] = sweptSphere(j);
  if (!spheresWithin(centreI, radiusI, centreJ, radiusJ, reach)) return false;
  sweptPieces(i, held, interval.start, interval.end, piecesI_);
  sweptPieces(j, held, interval.start, interval.end, piecesJ_);
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
  const std::size_t count = robot_.partCount(held);
  for (std::size_t i = 0; i < count; ++i) {
    for (std::size_t j = i + 1; j < count; ++j) {
      if (!robot_.checksPair(i, j, held)) continue;
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
  const auto piecesB = b.sweep(qb0, qb1, heldB, epsilon);
  if (piecesB.empty()) return false;
  // Only a's pieces near b's whole sweep can meet one of b's.
  Aabb region = piecesB.front().box;
  for (const RobotSweep::Piece& piece : piecesB) region = region.merged(piece.box);
  const auto piecesA = a.sweepNear(qa0, qa1, heldA, epsilon, region.inflated(reach));
  return anyPiecesWithinSorted(piecesA, piecesB, reach, b.order_);
}

}  // namespace kaboum::collision
