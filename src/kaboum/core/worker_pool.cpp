#include "kaboum/core/worker_pool.hpp"

#include <algorithm>
#include <condition_variable>
#include <exception>
#include <mutex>
#include <thread>
#include <utility>
#include <vector>

namespace kaboum {
namespace {

// One run() call: its tasks, how far they are handed out, and the failure of the lowest index.
struct Batch {
  void* callable;
  void (*invoke)(void* callable, std::size_t i);
  std::size_t count;
  const Batch* parent;      // the batch whose task started this one, if any
  std::size_t next = 0;     // the next index to hand out
  std::size_t running = 0;  // handed out and not finished
  std::exception_ptr error;
  std::size_t errorIndex = 0;
};

// The batch whose task this thread is running (the innermost one), null outside tasks.
thread_local const Batch* currentBatch = nullptr;

// Whether `batch` was started inside `outer` (by one of its tasks, or deeper).
bool startedInside(const Batch* batch, const Batch* outer) {
  for (; batch != nullptr; batch = batch->parent) {
    if (batch == outer) return true;
  }
  return false;
}

}  // namespace

struct WorkerPool::Shared {
  explicit Shared(unsigned threadCount) : threads(threadCount) {}
  ~Shared() {
    {
      const std::lock_guard lock(mutex);
      stopping = true;
    }
    changed.notify_all();
    for (std::thread& worker : workers) worker.join();
  }

  // A worker: runs tasks of the oldest batch with tasks left until the pool stops.
  void work() {
    std::unique_lock lock(mutex);
    while (true) {
      changed.wait(lock, [&] { return stopping || !open.empty(); });
      if (open.empty()) return;
      execute(*open.front(), lock);
    }
  }

  // Hands out the batch's next task and runs it without the lock. A failure skips the tasks not
  // handed out yet: every lower index has been, so the lowest failing index still runs.
  void execute(Batch& batch, std::unique_lock<std::mutex>& lock) {
    const std::size_t i = batch.next++;
    if (batch.next == batch.count) close(batch);
    ++batch.running;
    lock.unlock();
    const Batch* outer = std::exchange(currentBatch, &batch);
    std::exception_ptr error;
    try {
      batch.invoke(batch.callable, i);
    } catch (...) {
      error = std::current_exception();
    }
    currentBatch = outer;
    lock.lock();
    if (error && (!batch.error || i < batch.errorIndex)) {
      batch.error = std::move(error);
      batch.errorIndex = i;
      if (batch.next < batch.count) {
        batch.next = batch.count;
        close(batch);
      }
    }
    if (--batch.running == 0 && batch.next == batch.count) changed.notify_all();
  }

  // The batch has no task left to hand out.
  void close(Batch& batch) { open.erase(std::find(open.begin(), open.end(), &batch)); }

  const unsigned threads;
  std::mutex mutex;
  // Signalled when a batch opens, when a batch's last task finishes, and when the pool stops.
  std::condition_variable changed;
  std::vector<Batch*> open;  // batches with tasks left to hand out, oldest first
  bool stopping = false;
  std::vector<std::thread> workers;
};

WorkerPool::WorkerPool(unsigned threads)
    : shared_(std::make_unique<Shared>(std::max(threads, 1u))) {
  shared_->workers.reserve(shared_->threads - 1);
  for (unsigned t = 1; t < shared_->threads; ++t) {
    shared_->workers.emplace_back([shared = shared_.get()] { shared->work(); });
  }
}

WorkerPool::~WorkerPool() = default;

unsigned WorkerPool::threads() const {
  return shared_->threads;
}

void WorkerPool::runBatch(std::size_t count, void* callable, Invoke invoke) {
  if (shared_->workers.empty() || count <= 1) {
    for (std::size_t i = 0; i < count; ++i) invoke(callable, i);
    return;
  }
  Shared& shared = *shared_;
  Batch batch{callable, invoke, count, currentBatch, 0, 0, nullptr, 0};
  std::unique_lock lock(shared.mutex);
  shared.open.push_back(&batch);
  shared.changed.notify_all();
  while (batch.next < batch.count) shared.execute(batch, lock);
  // While other threads finish this batch's tasks, help with the batches those tasks started.
  while (batch.running > 0) {
    const auto inner =
        std::find_if(shared.open.begin(), shared.open.end(),
                     [&](const Batch* other) { return startedInside(other, &batch); });
    if (inner != shared.open.end()) {
      shared.execute(**inner, lock);
    } else {
      shared.changed.wait(lock);
    }
  }
  if (batch.error) std::rethrow_exception(batch.error);
}

}  // namespace kaboum
