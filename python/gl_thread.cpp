#include "python/gl_thread.h"

#include <condition_variable>
#include <deque>
#include <exception>
#include <future>
#include <memory>
#include <thread>

#include "stream/gl_context.h"

namespace passtrace::python {

namespace {

class GlThread {
 public:
  GlThread() : thread_([this] { loop(); }) {
    // Never joined: the thread waits for jobs until the process ends, so
    // that structures freed while Python shuts down still find it.
    thread_.detach();
  }

  void run(const std::function<void()>& job) {
    std::promise<void> done;
    std::future<void> finished = done.get_future();
    {
      std::lock_guard<std::mutex> lock(queueMutex_);
      queue_.push_back([&] {
        try {
          useContext();
          job();
          done.set_value();
        } catch (...) {
          done.set_exception(std::current_exception());
        }
      });
    }
    wake_.notify_one();
    finished.get();
  }

 private:
  // Created by the first job; a failure is every later job's error too.
  void useContext() {
    if (contextError_) std::rethrow_exception(contextError_);
    if (context_) return;
    try {
      context_ = GlContext::create(GlBackend::Auto);
    } catch (...) {
      contextError_ = std::current_exception();
      throw;
    }
  }

  void loop() {
    for (;;) {
      std::function<void()> job;
      {
        std::unique_lock<std::mutex> lock(queueMutex_);
        wake_.wait(lock, [this] { return !queue_.empty(); });
        job = std::move(queue_.front());
        queue_.pop_front();
      }
      std::lock_guard<std::mutex> gl(glMutex());
      job();
    }
  }

  std::unique_ptr<GlContext> context_;
  std::exception_ptr contextError_;
  std::mutex queueMutex_;
  std::condition_variable wake_;
  std::deque<std::function<void()>> queue_;
  std::thread thread_;  // last: it starts once the members above exist
};

}  // namespace

std::mutex& glMutex() {
  static std::mutex* mutex = new std::mutex;  // never destroyed: see GlThread
  return *mutex;
}

void runOnGlThread(const std::function<void()>& job) {
  static GlThread* thread = new GlThread;
  thread->run(job);
}

}  // namespace passtrace::python
