#include "python/render_call.h"

#include <mutex>
#include <optional>

#include <pybind11/numpy.h>
#include <tbb/global_control.h>

#include "apps/run_settings.h"
#include "python/flag_arguments.h"
#include "python/gl_thread.h"
#include "python/json_value.h"
#include "render/run_report.h"

namespace passtrace::python {

namespace py = pybind11;

py::dict render(const py::dict& settings) {
  const Options options = parseFlags(flagArguments(settings));
  if (options.list || options.version)
    throwValueError(std::string(options.list ? "list" : "version") +
                    ": render() renders; passtrace.structures() and passtrace.__version__ answer that");
  RunSettings run;
  try {
    run = toRunSettings(options);
  } catch (const std::exception& e) {
    throwValueError(e.what());
  }
  RunReport report;
  {
    py::gil_scoped_release released;
    std::optional<tbb::global_control> threadLimit;
    if (run.threads > 0) threadLimit.emplace(tbb::global_control::max_allowed_parallelism, run.threads);
    // Warnings go into the report's "warnings"; progress only when asked for.
    Progress progress(options.progress ? Progress::Mode::Always : Progress::Mode::Quiet);
    // The preview and the GPU stream renderer make their own context on this
    // thread; one GL user at a time in the process (gl_thread.h).
    std::unique_lock<std::mutex> gl(glMutex(), std::defer_lock);
    if (run.renderer == RendererId::OpenGl || run.renderer == RendererId::Gpu) gl.lock();
    try {
      report = runSession(run, progress);
    } catch (const std::exception& e) {
      throwValueError(e.what());  // a Python exception only once the GIL is back
    }
  }
  py::dict out = jsonValue(toJson(report));
  if (!report.image.empty())
    out["image"] = py::array_t<float>({py::ssize_t(report.height), py::ssize_t(report.width), py::ssize_t(3)},
                                      report.image.data());
  return out;
}

}  // namespace passtrace::python
