// Hash set of fixed-width records of 64-bit words, stored contiguously (Fast Downward's packed
// state registry idea). Used for search states and for memoized attachment calls; inserting
// allocates only when the arena grows.
#pragma once

#include <cstdint>
#include <span>
#include <utility>
#include <vector>

namespace kaboum::symbolic {

class PackedSet {
 public:
  explicit PackedSet(std::size_t width);

  // Adds `record` (exactly width() words) unless present; returns its id and whether it was new.
  std::pair<std::uint32_t, bool> insert(std::span<const std::uint64_t> record);
  // Id of `record`, or kMissing.
  std::uint32_t find(std::span<const std::uint64_t> record) const;
  std::span<const std::uint64_t> get(std::uint32_t id) const {
    return {data_.data() + static_cast<std::size_t>(id) * width_, width_};
  }
  std::size_t size() const { return size_; }
  std::size_t width() const { return width_; }
  std::size_t bytes() const {
    return data_.capacity() * sizeof(std::uint64_t) + slots_.capacity() * sizeof(std::uint32_t);
  }

  static constexpr std::uint32_t kMissing = 0xffffffffu;

 private:
  std::uint64_t hash(std::span<const std::uint64_t> record) const;
  bool equals(std::uint32_t id, std::span<const std::uint64_t> record) const;
  void grow();

  std::size_t width_;
  std::size_t size_ = 0;
  std::vector<std::uint64_t> data_;
  std::vector<std::uint32_t> slots_;  // open addressing, kMissing when empty
};

}  // namespace kaboum::symbolic
