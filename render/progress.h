#pragma once
// What a run tells the user on stderr while it works: stages (loading,
// building, uploading, frame k of n) when stderr is a terminal or
// --progress was given, so a 50-second build does not look hung; warnings
// unless --quiet. Errors are not reported here: they end the run as one
// exception, printed by main.

#include <cstddef>
#include <string>
#include <string_view>

namespace passtrace {

class Progress {
 public:
  enum class Mode {
    Auto,    // stages when stderr is a terminal
    Always,  // --progress
    Quiet    // --quiet: warnings and stages silenced
  };
  explicit Progress(Mode mode = Mode::Auto);
  ~Progress();

  void stage(std::string_view what);     // "loading bunny"
  void frame(size_t k, size_t n);        // frame k (0-based) of n
  void warn(const std::string& message);  // "passtrace: warning: MESSAGE"
  void notice(const std::string& message);  // "passtrace: MESSAGE" (not silenced by Auto)
  void finish();                          // clears a terminal's progress line

 private:
  void show(const std::string& line);
  bool stages_ = false, terminal_ = false, quiet_ = false, lineOpen_ = false;
};

}  // namespace passtrace
