// passtrace: the command line (tracy's flags, thesis Appendix A).
#include <cstdio>
#include <exception>
#include <string>

#include "apps/cli_options.h"
#include "apps/run_render.h"

int main(int argc, char** argv) {
  passtrace::Options options;
  try {
    if (passtrace::parseOptions(argc, argv, options) < 0) return 0;  // --help
    passtrace::runPassTrace(options);
    return 0;
  } catch (const std::exception& e) {
    // Exactly one line, whatever the message (driver logs span several).
    std::string message = e.what();
    for (char& c : message)
      if (c == '\n' || c == '\r') c = ' ';
    std::fprintf(stderr, "passtrace: error: %s\n", message.c_str());
    return 1;
  }
}
