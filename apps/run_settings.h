#pragma once
// The parsed command line as the render session's typed settings.

#include "apps/cli_options.h"
#include "render/session.h"

namespace passtrace {

// Throws std::runtime_error for a flag value the session cannot take.
RunSettings toRunSettings(const Options& options);
Progress::Mode progressMode(const Options& options);

}  // namespace passtrace
