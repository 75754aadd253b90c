#pragma once
// One passtrace run: load the scene, build the accelerator, render every
// camera angle -m times keeping the fastest, write the outputs, report.

#include "apps/cli_options.h"

namespace passtrace {

// Throws std::runtime_error (or a subclass) with a one-line message on any
// bad input or failure; outputs are written only after every frame rendered.
void runPassTrace(const Options& options);

}  // namespace passtrace
