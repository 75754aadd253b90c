// passtrace: the command line (tracy's flags, thesis Appendix A). Parses the
// options, then hands them to the render session (render/session.h).
#include <cstdio>
#include <exception>
#include <iostream>
#include <optional>
#include <string>

#include <tbb/global_control.h>

#include "apps/cli_options.h"
#include "apps/run_settings.h"
#include "passtrace_version.h"
#include "render/output_files.h"
#include "render/catalog.h"

int main(int argc, char** argv) {
  passtrace::Options options;
  try {
    if (passtrace::parseOptions(argc, argv, options, passtrace::catalogText()) < 0) return 0;  // --help
    if (options.version) {
      std::printf("passtrace %s\n", passtrace::kVersion);
      return 0;
    }
    if (options.list) {
      const std::string text = options.listJson ? passtrace::catalogJsonText(options.scenesDir)
                                                : passtrace::catalogText(options.scenesDir);
      if (options.json.empty()) std::cout << text;
      else {
        passtrace::OutputFiles outputs;
        outputs.write(options.json, text);
        outputs.commitAll();
      }
      return 0;
    }
    // --threads caps every oneTBB pool: the renderer's and the structure builds'.
    std::optional<tbb::global_control> threadLimit;
    if (options.threads > 0) threadLimit.emplace(tbb::global_control::max_allowed_parallelism, options.threads);
    passtrace::Progress progress(passtrace::progressMode(options));
    const passtrace::RunReport report = passtrace::runSession(passtrace::toRunSettings(options), progress);
    if (!options.quiet) std::cout << passtrace::summaryText(report, options.stats);
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
