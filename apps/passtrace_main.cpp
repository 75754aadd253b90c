// passtrace: the command line (tracy's flags, thesis Appendix A). Parses the
// options, then hands them to the render session (render/session.h). Under
// mpirun every rank runs this; rank 0 alone prints (render/ranks.h).
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
#include "render/ranks.h"

namespace {

int run(int argc, char** argv) {
  namespace ranks = passtrace::ranks;
  passtrace::Options options;
  try {
    if (passtrace::parseOptions(argc, argv, options, passtrace::catalogText()) < 0) return 0;  // --help
    if (options.version) {
      if (ranks::isRoot()) std::printf("passtrace %s\n", passtrace::kVersion);
      return 0;
    }
    if (options.list && !ranks::isRoot()) return 0;
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
    passtrace::Progress progress(ranks::isRoot() ? passtrace::progressMode(options) : passtrace::Progress::Mode::Quiet);
    const passtrace::RunReport report = passtrace::runSession(passtrace::toRunSettings(options), progress);
    ranks::agree();  // rank 0's outputs are written
    if (!options.quiet && ranks::isRoot()) std::cout << passtrace::summaryText(report, options.stats);
    return 0;
  } catch (const std::exception& e) {
    std::string message = e.what();
    // A rank's own error reaches the others at their next step; after that
    // every rank has the first failing rank's message.
    if (ranks::count() > 1 && !ranks::failed()) {
      try {
        ranks::agree(message);
      } catch (const ranks::RankFailure& failure) {
        message = failure.what();
      }
    }
    if (!ranks::isRoot()) return 1;
    // Exactly one line, whatever the message (driver logs span several).
    for (char& c : message)
      if (c == '\n' || c == '\r') c = ' ';
    std::fprintf(stderr, "passtrace: error: %s\n", message.c_str());
    return 1;
  }
}

}  // namespace

int main(int argc, char** argv) {
  passtrace::ranks::start(argc, argv);
  const int status = run(argc, argv);
  passtrace::ranks::stop();
  return status;
}
