#include "kaboum/symbolic/packed_set.hpp"

#include <algorithm>

namespace kaboum::symbolic {

PackedSet::PackedSet(std::size_t width) : width_(width), slots_(64, kMissing) {}

std::uint64_t PackedSet::hash(std::span<const std::uint64_t> record) const {
  std::uint64_t h = 0x9e3779b97f4a7c15ull ^ record.size();
  for (const std::uint64_t word : record) {
    std::uint64_t k = word * 0xff51afd7ed558ccdull;
    k ^= k >> 33;
    h = (h ^ k) * 0xc4ceb9fe1a85ec53ull;
    h ^= h >> 29;
  }
  return h;
}

bool PackedSet::equals(std::uint32_t id, std::span<const std::uint64_t> record) const {
  return std::equal(record.begin(), record.end(), data_.begin() + static_cast<long>(id * width_));
}

std::uint32_t PackedSet::find(std::span<const std::uint64_t> record) const {
  const std::size_t mask = slots_.size() - 1;
  for (std::size_t i = hash(record) & mask;; i = (i + 1) & mask) {
    const std::uint32_t id = slots_[i];
    if (id == kMissing) return kMissing;
    if (equals(id, record)) return id;
  }
}

std::pair<std::uint32_t, bool> PackedSet::insert(std::span<const std::uint64_t> record) {
  if ((size_ + 1) * 2 > slots_.size()) grow();
  const std::size_t mask = slots_.size() - 1;
  std::size_t i = hash(record) & mask;
  for (;; i = (i + 1) & mask) {
    const std::uint32_t id = slots_[i];
    if (id == kMissing) break;
    if (equals(id, record)) return {id, false};
  }
  const auto id = static_cast<std::uint32_t>(size_++);
  data_.insert(data_.end(), record.begin(), record.end());
  slots_[i] = id;
  return {id, true};
}

void PackedSet::grow() {
  std::vector<std::uint32_t> old(slots_.size() * 2, kMissing);
  old.swap(slots_);
  const std::size_t mask = slots_.size() - 1;
  for (std::uint32_t id = 0; id < size_; ++id) {
    std::size_t i = hash(get(id)) & mask;
    while (slots_[i] != kMissing) i = (i + 1) & mask;
    slots_[i] = id;
  }
}

}  // namespace kaboum::symbolic
