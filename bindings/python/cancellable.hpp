// Long computations that Ctrl-C stops: the work runs on a thread of its own without the GIL
// (Python attachments it calls take the GIL per call), while the calling thread checks for
// signals every 50 ms and, on an exception from a handler (KeyboardInterrupt), sets the cancel
// flag that the work's deadlines poll (core/deadline.hpp), waits for it and raises the exception.
#pragma once

#include <atomic>
#include <functional>

namespace kaboum::python {

// Runs `work`; rethrows its exception, or the signal handler's. Call with the GIL held.
void runCancellable(const std::function<void()>& work, std::atomic<bool>& cancel);

}  // namespace kaboum::python
