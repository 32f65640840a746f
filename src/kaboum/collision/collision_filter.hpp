// Pairs of a robot's link parts exempt from collision checks (thesis §4.3): adjacent links and
// pairs the user allows. Held objects follow RobotCollisionModel::checksPair instead.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace kaboum::collision {

// Symmetric allowed-collision matrix over body indices [0, size()), fixed in size. A pair is
// checked unless it is allowed; a body is never checked against itself.
class CollisionFilter {
 public:
  // Every pair of `bodyCount` bodies checked.
  explicit CollisionFilter(std::size_t bodyCount = 0)
      : size_(bodyCount), allowed_(bodyCount * bodyCount, 0) {}

  [[nodiscard]] std::size_t size() const { return size_; }

  // Exempts the pair (a, b) from checks, or checks it again. Throws std::out_of_range for an
  // index not below size().
  void allow(std::size_t a, std::size_t b, bool allowed = true);
  [[nodiscard]] bool allowed(std::size_t a, std::size_t b) const {
    return a == b || allowed_[a * size_ + b] != 0;
  }

 private:
  std::size_t size_ = 0;
  std::vector<std::uint8_t> allowed_;  // size_ x size_, symmetric
};

}  // namespace kaboum::collision
