#pragma once
// EGL contexts without a window system: the device platform (which is how a
// headless program reaches an NVIDIA GPU) and Mesa's surfaceless platform.

#include <string>

#include "stream/gl_context.h"

namespace passtrace {

// Tries a hardware EGL device first, then the surfaceless platform, then any
// (software) EGL device. Returns false with `error` set if none gives a 4.5
// core context; the context is current on success.
//
// Which hardware device, on a machine with several GPUs: PASSTRACE_EGL_DEVICE
// (0, 1, ... among the hardware devices) when set; else the process's rank on
// its node as an MPI launcher gives it (OMPI_COMM_WORLD_LOCAL_RANK, SLURM_LOCALID,
// MPI_LOCALRANKID) modulo the devices, so that `mpirun -np G` on a node with
// G GPUs puts one rank on each; else the first. Throws std::runtime_error
// for a PASSTRACE_EGL_DEVICE that names no hardware device.
bool createEglContext(PlatformContext& out, std::string& error);

}  // namespace passtrace
