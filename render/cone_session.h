#pragma once
// The --cone part of a run (render/session.cpp calls it): checks the cone
// flags before anything is loaded, then builds the structure's cone query,
// traces one cone per pixel per angle (the fastest of the repeats) and
// writes --cone-hits and --heatmap (nodes + triangles per pixel) into the
// run's outputs, which the session commits with the report.

#include <vector>

#include "render/output_files.h"
#include "render/run_report.h"
#include "render/session.h"

namespace passtrace {

// Throws a one-line error for a cone run that cannot be made: a renderer
// or structure without a cone query (naming those that have one), outputs
// that do not apply, a bad --cone-hits name.
void checkConeRun(const RunSettings& o);

void traceConeRun(const RunSettings& o, const Structure& structure, const Scene& scene,
                  const std::vector<CameraSpec>& views, RunReport& report, Progress& progress, OutputFiles& outputs);

}  // namespace passtrace
