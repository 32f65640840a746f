// Pairs of bodies exempt from collision checks: adjacent robot links, an attached object and the
// link that holds it, and pairs the user allows (issue 3, "collision filtering").
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace kaboum::collision {

// Symmetric allowed-collision matrix over body indices [0, size()). A pair is checked unless it
// is allowed; a body is never checked against itself.
class CollisionFilter {
 public:
  explicit CollisionFilter(std::size_t bodyCount = 0) { resize(bodyCount); }

  // Keeps the entries of bodies below the new size; new bodies start with every pair checked.
  void resize(std::size_t bodyCount);
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
