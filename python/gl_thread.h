#pragma once
// The module's one OpenGL context and the thread it is current on. A GL
// context belongs to one thread, and Python calls come from any thread: so
// every GPU structure is built, traced and freed by jobs run on this thread,
// one at a time, while the calling thread waits without the GIL.
#include <functional>
#include <mutex>

namespace passtrace::python {

// Runs `job` on the GL thread (started, and its headless context created, on
// first use) and returns when it has finished; an exception the job (or the
// context's creation) throws is rethrown here.
void runOnGlThread(const std::function<void()>& job);

// Held by every use of OpenGL in the process: the GL thread's jobs, and
// render() runs on the preview or GPU stream renderer, which make their own
// context on the calling thread (the stream layer keeps per-process state).
std::mutex& glMutex();

}  // namespace passtrace::python
