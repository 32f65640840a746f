#include "kaboum/collision/collision_filter.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace kaboum::collision {

void CollisionFilter::allow(std::size_t a, std::size_t b, bool allowed) {
  if (a >= size_ || b >= size_) {
    throw std::out_of_range("collision filter: body index " + std::to_string(std::max(a, b)) +
                            " out of range (" + std::to_string(size_) + " bodies)");
  }
  allowed_[a * size_ + b] = allowed_[b * size_ + a] = allowed ? 1 : 0;
}

}  // namespace kaboum::collision
