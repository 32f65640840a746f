#include "kaboum/collision/broad_phase.hpp"

#include <algorithm>
#include <numeric>

namespace kaboum::collision {

using namespace kaboum::geometry;

Aabb transformedAabb(const Aabb& local, const Eigen::Isometry3d& pose) {
  const Vec3 centre = pose * (0.5 * (local.lo + local.hi));
  const Vec3 half = pose.linear().cwiseAbs() * (0.5 * (local.hi - local.lo));
  return {centre - half, centre + half};
}

void AabbTree::build(std::span<const Aabb> boxes) {
  nodes_.clear();
  boxes_.assign(boxes.begin(), boxes.end());
  ids_.resize(boxes.size());
  std::iota(ids_.begin(), ids_.end(), 0U);
  centres_.resize(boxes.size());
  for (std::size_t i = 0; i < boxes.size(); ++i) centres_[i] = boxes[i].lo + boxes[i].hi;
  if (boxes.empty()) return;
  nodes_.reserve(2 * boxes.size());
  buildNode(0, static_cast<std::uint32_t>(boxes.size()));
}

void AabbTree::buildNode(std::uint32_t begin, std::uint32_t end) {
  const auto index = static_cast<std::uint32_t>(nodes_.size());
  nodes_.emplace_back();
  Aabb box = boxes_[begin];
  Vec3 centreLo = centres_[begin], centreHi = centres_[begin];
  for (std::uint32_t i = begin + 1; i < end; ++i) {
    box = box.merged(boxes_[i]);
    centreLo = centreLo.cwiseMin(centres_[i]);
    centreHi = centreHi.cwiseMax(centres_[i]);
  }
  nodes_[index].box = box;
  if (end - begin <= kLeafSize) {
    nodes_[index].first = begin;
    nodes_[index].count = end - begin;
    return;
  }
  int axis = 0;
  (centreHi - centreLo).maxCoeff(&axis);
  const std::uint32_t middle = begin + (end - begin) / 2;
  // Sort slots [begin, end) by centre along the axis, keeping boxes, ids and centres together.
  std::vector<std::uint32_t> order(end - begin);
  std::iota(order.begin(), order.end(), begin);
  std::nth_element(order.begin(), order.begin() + (middle - begin), order.end(),
                   [&](std::uint32_t a, std::uint32_t b) {
                     return centres_[a][axis] < centres_[b][axis] ||
                            (centres_[a][axis] == centres_[b][axis] && ids_[a] < ids_[b]);
                   });
  std::vector<Aabb> boxes(end - begin);
  std::vector<std::uint32_t> ids(end - begin);
  std::vector<Vec3> centres(end - begin);
  for (std::size_t k = 0; k < order.size(); ++k) {
    boxes[k] = boxes_[order[k]];
    ids[k] = ids_[order[k]];
    centres[k] = centres_[order[k]];
  }
  std::copy(boxes.begin(), boxes.end(), boxes_.begin() + begin);
  std::copy(ids.begin(), ids.end(), ids_.begin() + begin);
  std::copy(centres.begin(), centres.end(), centres_.begin() + begin);
  buildNode(begin, middle);
  nodes_[index].first = static_cast<std::uint32_t>(nodes_.size());
  buildNode(middle, end);
}

}  // namespace kaboum::collision
