#include "render/progress.h"

#include <cstdio>

#include <unistd.h>

namespace passtrace {

Progress::Progress(Mode mode) {
  terminal_ = isatty(STDERR_FILENO) == 1;
  quiet_ = mode == Mode::Quiet;
  stages_ = mode == Mode::Always || (mode == Mode::Auto && terminal_);
}

Progress::~Progress() { finish(); }

void Progress::show(const std::string& line) {
  if (!stages_) return;
  if (terminal_) {
    // One line, rewritten in place.
    std::fprintf(stderr, "\r\033[Kpasstrace: %s", line.c_str());
    lineOpen_ = true;
  } else {
    std::fprintf(stderr, "passtrace: %s\n", line.c_str());
  }
  std::fflush(stderr);
}

void Progress::stage(std::string_view what) { show(std::string(what) + " ..."); }

void Progress::frame(size_t k, size_t n) { show("frame " + std::to_string(k + 1) + " of " + std::to_string(n)); }

void Progress::finish() {
  if (lineOpen_) std::fprintf(stderr, "\r\033[K");
  lineOpen_ = false;
}

void Progress::warn(const std::string& message) {
  if (quiet_) return;
  finish();
  std::fprintf(stderr, "passtrace: warning: %s\n", message.c_str());
}

void Progress::notice(const std::string& message) {
  if (quiet_) return;
  finish();
  std::fprintf(stderr, "passtrace: %s", message.c_str());
  if (message.empty() || message.back() != '\n') std::fputc('\n', stderr);
}

}  // namespace passtrace
