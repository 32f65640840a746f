// A fixed set of worker threads that run batches of indexed tasks together with the thread that
// asks for them (a parallel for, in the spirit of oneTBB's task_group and parallel_for), shared
// by the bounding convex decomposition, the mesh verifier and the planners.
#pragma once

#include <algorithm>
#include <cstddef>
#include <memory>
#include <type_traits>

namespace kaboum {

class WorkerPool {
 public:
  // `threads` threads run a batch: the caller of run() and threads - 1 workers started here.
  // With 0 or 1 no thread is started and run() runs every task inline on its caller.
  explicit WorkerPool(unsigned threads);
  // Joins the workers; no batch may be running.
  ~WorkerPool();
  WorkerPool(const WorkerPool&) = delete;
  WorkerPool& operator=(const WorkerPool&) = delete;

  // The threads that run a batch, the caller included (at least 1).
  [[nodiscard]] unsigned threads() const;

  // Runs task(i) once for every i < count and returns when all have finished. The caller runs
  // tasks of the batch too, idle workers take the others (in index order); while it waits for
  // tasks running elsewhere it runs only tasks of batches started inside this one (a task may call
  // run() again), never unrelated work. When tasks throw, the tasks not yet started are skipped
  // and the exception of the lowest index is rethrown: the same one as running them in order on
  // one thread. So results do not depend on the thread count when task i writes only its own
  // outputs. Several threads may run batches at once. Allocates nothing per task.
  template <typename Task>
  void run(std::size_t count, Task&& task) {
    using Callable = std::remove_reference_t<Task>;
    runBatch(count, const_cast<void*>(static_cast<const void*>(std::addressof(task))),
             [](void* callable, std::size_t i) { (*static_cast<Callable*>(callable))(i); });
  }

  // Runs body(i) once for every i < count, in contiguous blocks of at least `minimumPerTask`
  // indices, at most threads() of them (one task each); a block's indices run in order.
  template <typename Body>
  void forEachIndex(std::size_t count, std::size_t minimumPerTask, Body&& body) {
    const std::size_t blocks =
        std::clamp<std::size_t>(count / std::max<std::size_t>(minimumPerTask, 1), 1, threads());
    const auto start = [&](std::size_t block) {  // count * block / blocks, without overflow
      return count / blocks * block + count % blocks * block / blocks;
    };
    run(blocks, [&](std::size_t block) {
      for (std::size_t i = start(block), end = start(block + 1); i < end; ++i) body(i);
    });
  }

 private:
  using Invoke = void (*)(void* callable, std::size_t i);
  void runBatch(std::size_t count, void* callable, Invoke invoke);

  struct Shared;
  std::unique_ptr<Shared> shared_;
};

}  // namespace kaboum
