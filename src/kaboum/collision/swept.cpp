#include "kaboum/collision/swept.hpp"

#include <bit>

namespace kaboum::collision {

RobotSweep::RobotSweep(const RobotCollisionModel& robot)
    : robot_(robot), chains_(linkSweepChains(robot.model())) {}

std::span<const RobotSweep::Piece> RobotSweep::sweep(std::span<const double> qa,
                                                     std::span<const double> qb, double epsilon) {
  const RobotModel& model = robot_.model();
  const std::size_t links = model.links().size();
  subdivisions_.assign(robot_.partCount(), 0);
  unsigned finest = 1;
  for (std::size_t i = 0; i < robot_.partCount(); ++i) {
    const auto& part = robot_.part(i);
    if (!part.active) continue;
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
  pieces_.clear();
  for (std::size_t i = 0; i < robot_.partCount(); ++i) {
    const auto& part = robot_.part(i);
    if (!part.active) continue;
    const std::size_t n = static_cast<std::size_t>(subdivisions_[i]);
    const std::size_t stride = finest / n;
    for (std::size_t k = 0; k < n; ++k) {
      const Pose start = robot_.partPose(i, samplePoses(k * stride));
      const Pose end = robot_.partPose(i, samplePoses((k + 1) * stride));
      for (std::size_t p = 0; p < part.body->pieceCount(); ++p) {
        const PieceBounds& bounds = part.body->pieceBounds(p);
        const Vec3 centreStart = start * bounds.centre, centreEnd = end * bounds.centre;
        pieces_.push_back(
            {SweptPiece(TransformedSupport(part.body->piece(p), start),
                        TransformedSupport(part.body->piece(p), end)),
             transformedAabb(bounds.box, start).merged(transformedAabb(bounds.box, end)),
             0.5 * (centreStart + centreEnd),
             bounds.radius + 0.5 * (centreEnd - centreStart).norm(), i});
      }
    }
  }
  return pieces_;
}

std::optional<std::size_t> RobotSweep::firstSceneCollision(std::span<const double> qa,
                                                           std::span<const double> qb,
                                                           const CollisionScene& scene,
                                                           double margin, double epsilon) {
  for (const Piece& piece : sweep(qa, qb, epsilon)) {
    if (auto hit = scene.firstWithin(piece.shape, piece.box, piece.centre, piece.radius,
                                     margin + epsilon)) {
      return hit;
    }
  }
  return std::nullopt;
}

bool sweptVolumesCollide(RobotSweep& a, std::span<const double> qa0, std::span<const double> qa1,
                         RobotSweep& b, std::span<const double> qb0, std::span<const double> qb1,
                         double margin, double epsilon) {
  const auto piecesA = a.sweep(qa0, qa1, epsilon);
  const auto piecesB = b.sweep(qb0, qb1, epsilon);
  const double reach = margin + 2 * epsilon;
  for (const auto& pa : piecesA) {
    const Aabb box = pa.box.inflated(reach);
    for (const auto& pb : piecesB) {
      if (box.overlaps(pb.box) &&
          spheresWithin(pa.centre, pa.radius, pb.centre, pb.radius, reach) &&
          intersects(pa.shape, pb.shape, reach)) {
        return true;
      }
    }
  }
  return false;
}

}  // namespace kaboum::collision
