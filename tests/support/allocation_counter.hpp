// Counts global operator new calls, for the "hot paths allocate nothing per call" tests. It
// replaces the global allocation functions, so include it from exactly one file per test
// executable.
#pragma once

#include <atomic>
#include <cstdlib>
#include <new>

// The replacements below pair malloc/free themselves; GCC cannot see that through inlining.
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"

namespace kaboum::test {
inline std::atomic<long> allocations{0};

// Number of operator new calls made while `call` runs.
template <typename F>
long allocationsDuring(F&& call) {
  const long before = allocations.load();
  call();
  return allocations.load() - before;
}
}  // namespace kaboum::test

void* operator new(std::size_t size) {
  ++kaboum::test::allocations;
  if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
  throw std::bad_alloc();
}
// The nothrow form too (std::get_temporary_buffer uses it): under ASan its own nothrow new would
// otherwise be paired with the free() below.
void* operator new(std::size_t size, const std::nothrow_t&) noexcept {
  ++kaboum::test::allocations;
  return std::malloc(size == 0 ? 1 : size);
}
void operator delete(void* p) noexcept {
  std::free(p);
}
void operator delete(void* p, std::size_t) noexcept {
  std::free(p);
}
void operator delete(void* p, const std::nothrow_t&) noexcept {
  std::free(p);
}
