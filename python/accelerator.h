#pragma once
// passtrace.build()'s result: one registry row built over a scene for the
// CPU renderer (or Embree) or the GPU stream renderer, tracing numpy arrays
// of rays. Build and trace run without the GIL; the CPU ones on the
// renderer's threads, the GPU ones on the module's GL thread (gl_thread.h).
#include <memory>
#include <string>
#include <vector>
#include <pybind11/pybind11.h>
#include "accel/registry.h"
#include "scenes/scene.h"
#include "stream/stream_stage.h"

namespace passtrace {
class StreamRayQuery;
}

namespace passtrace::python {

namespace py = pybind11;

class Accelerator {
 public:
  // `structure` a registry name (or thesis number), `renderer` "cpu", "gpu"
  // or "embree" ("cpu" also takes the embree row); `params` build and
  // traversal flags by long name (kd_builder="binned"), plus threads= and,
  // on "gpu", stage=. An unknown structure, renderer or parameter, or one the
  // structure does not read, is a ValueError with the program's message.
  Accelerator(std::shared_ptr<const Scene> scene, const std::string& structure, const std::string& renderer,
              const py::dict& params);
  // Every triangle tested, in scene order (accel/cpu_accelerator.h): the
  // reference the structures are compared with. triangleTest as --triangle-test.
  static std::unique_ptr<Accelerator> bruteForce(std::shared_ptr<const Scene> scene, const std::string& triangleTest);
  ~Accelerator();
  Accelerator(const Accelerator&) = delete;
  Accelerator& operator=(const Accelerator&) = delete;

  py::dict intersect(const py::handle& origins, const py::handle& directions, const py::handle& tmax, bool counters);
  py::object occluded(const py::handle& origins, const py::handle& directions, const py::handle& tmax);
  py::dict stats() const;
  std::string repr() const;

 private:
  explicit Accelerator(std::shared_ptr<const Scene> scene);
  // Traces in the scene's units; stats may be null.
  void trace(const std::vector<Ray>& rays, bool anyHit, std::vector<Hit>& hits, std::vector<RayStats>* stats);

  std::shared_ptr<const Scene> scene_;  // the CPU structures keep spans of its triangles
  const Structure* row_ = nullptr;
  RendererId renderer_ = RendererId::Cpu;
  unsigned threads_ = 0;
  StreamStage stage_ = StreamStage::Fragment;
  std::unique_ptr<CpuAccelerator> cpu_;
  // GPU: made, used and freed on the GL thread only.
  std::unique_ptr<GpuTraversal> gpu_;
  std::unique_ptr<StreamRayQuery> query_;
  AccelStats stats_;
};

// The parameters build() takes, by keyword name ("kd_builder", ...).
std::vector<std::string> buildParameterNames();

}  // namespace passtrace::python
