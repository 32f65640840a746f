#include "cancellable.hpp"

#include <chrono>
#include <exception>
#include <future>
#include <optional>
#include <thread>

#include "bindings.hpp"

namespace kaboum::python {

void runCancellable(const std::function<void()>& work, std::atomic<bool>& cancel) {
  std::exception_ptr failure;
  std::promise<void> done;
  std::future<void> finished = done.get_future();
  std::thread worker([&] {
    {
      // The thread's Python state lives as long as the work, so that each attachment call only
      // takes the GIL.
      py::gil_scoped_acquire threadState;
      py::gil_scoped_release unlocked;
      try {
        work();
      } catch (...) {
        failure = std::current_exception();
      }
    }
    done.set_value();
  });
  std::optional<py::error_already_set> interruption;
  {
    py::gil_scoped_release unlocked;
    while (finished.wait_for(std::chrono::milliseconds(50)) != std::future_status::ready) {
      py::gil_scoped_acquire locked;
      if (!interruption && PyErr_CheckSignals() != 0) {
        interruption.emplace();
        cancel = true;
      }
    }
    worker.join();
  }
  if (interruption) throw std::move(*interruption);
  if (failure) std::rethrow_exception(failure);
}

}  // namespace kaboum::python
