#include "accel/embree/embree_accelerator.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <limits>
#include <mutex>
#include <stdexcept>
#include <string>

#include <embree3/rtcore.h>

namespace passtrace {
namespace {

const char* errorName(RTCError code) {
  switch (code) {
    case RTC_ERROR_NONE: return "no error";
    case RTC_ERROR_UNKNOWN: return "unknown error";
    case RTC_ERROR_INVALID_ARGUMENT: return "invalid argument";
    case RTC_ERROR_INVALID_OPERATION: return "invalid operation";
    case RTC_ERROR_OUT_OF_MEMORY: return "out of memory";
    case RTC_ERROR_UNSUPPORTED_CPU: return "unsupported CPU";
    case RTC_ERROR_CANCELLED: return "cancelled";
  }
  return "unrecognised error";
}

// One line: newlines in Embree's message become spaces.
std::string oneLine(std::string s) {
  for (char& c : s)
    if (c == '\n' || c == '\r') c = ' ';
  while (!s.empty() && s.back() == ' ') s.pop_back();
  return s;
}

// The first error Embree reported through the device's error function. The
// callback must not throw (it is called from inside Embree, possibly on a
// worker thread), so it records; construction checks after each step.
struct ErrorSink {
  std::mutex mutex;
  RTCError code = RTC_ERROR_NONE;
  std::string message;

  static void callback(void* userPtr, RTCError code, const char* str) {
    auto* self = static_cast<ErrorSink*>(userPtr);
    std::lock_guard lock(self->mutex);
    if (self->code != RTC_ERROR_NONE) return;  // keep the first
    self->code = code;
    self->message = str ? str : "";
  }

  void throwIfError(const char* during) {
    std::lock_guard lock(mutex);
    if (code == RTC_ERROR_NONE) return;
    std::string line = std::string("embree: ") + errorName(code) + " during " + during;
    if (!message.empty()) line += ": " + oneLine(message);
    throw std::runtime_error(line);
  }
};

// Embree's packet types and calls by width, so that one loop serves all three.
template <int K> struct EmbreePacket;
template <> struct EmbreePacket<4> {
  using RayHit = RTCRayHit4;
  static void intersect(const int* v, RTCScene s, RTCIntersectContext* c, RTCRayHit4* r) { rtcIntersect4(v, s, c, r); }
  static void occluded(const int* v, RTCScene s, RTCIntersectContext* c, RTCRay4* r) { rtcOccluded4(v, s, c, r); }
};
template <> struct EmbreePacket<8> {
  using RayHit = RTCRayHit8;
  static void intersect(const int* v, RTCScene s, RTCIntersectContext* c, RTCRayHit8* r) { rtcIntersect8(v, s, c, r); }
  static void occluded(const int* v, RTCScene s, RTCIntersectContext* c, RTCRay8* r) { rtcOccluded8(v, s, c, r); }
};
template <> struct EmbreePacket<16> {
  using RayHit = RTCRayHit16;
  static void intersect(const int* v, RTCScene s, RTCIntersectContext* c, RTCRayHit16* r) {
    rtcIntersect16(v, s, c, r);
  }
  static void occluded(const int* v, RTCScene s, RTCIntersectContext* c, RTCRay16* r) { rtcOccluded16(v, s, c, r); }
};

class EmbreeAccelerator final : public CpuAccelerator {
public:
  explicit EmbreeAccelerator(std::span<const Triangle> tris) : errors_(std::make_unique<ErrorSink>()) {
    const auto start = std::chrono::steady_clock::now();
    if (tris.size() > std::numeric_limits<uint32_t>::max() / 3)
      throw std::runtime_error("embree: too many triangles (" + std::to_string(tris.size()) +
                               ") for 32-bit vertex indices");

    device_.reset(rtcNewDevice(nullptr));
    if (!device_) {
      const RTCError code = rtcGetDeviceError(nullptr);
      throw std::runtime_error(std::string("embree: cannot create a device: ") + errorName(code));
    }
    rtcSetDeviceErrorFunction(device_.get(), &ErrorSink::callback, errors_.get());

    scene_.reset(rtcNewScene(device_.get()));
    errors_->throwIfError("scene creation");
    if (!scene_) throw std::runtime_error("embree: scene creation failed");
    rtcSetSceneBuildQuality(scene_.get(), RTC_BUILD_QUALITY_HIGH);
    rtcSetSceneFlags(scene_.get(), RTC_SCENE_FLAG_NONE);

    if (!tris.empty()) {
      const size_t vertexCount = 3 * tris.size();
      // Released at the end of this block (or on a throw); the scene keeps its own reference.
      const std::unique_ptr<RTCGeometryTy, GeometryRelease> owned(
          rtcNewGeometry(device_.get(), RTC_GEOMETRY_TYPE_TRIANGLE));
      errors_->throwIfError("geometry creation");
      if (!owned) throw std::runtime_error("embree: geometry creation failed");
      RTCGeometry geom = owned.get();
      // Embree pads its own buffers so that the last vertex may be read with
      // a 16-byte load; a shared buffer over the caller's triangles would not be.
      auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(
          geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), vertexCount));
      auto* indices = static_cast<uint32_t*>(rtcSetNewGeometryBuffer(
          geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(uint32_t), tris.size()));
      if (!vertices || !indices) {
        errors_->throwIfError("buffer allocation");
        throw std::runtime_error("embree: buffer allocation failed");
      }
      for (size_t i = 0; i < tris.size(); ++i) {
        const glm::vec3* v[3] = {&tris[i].v0, &tris[i].v1, &tris[i].v2};
        for (size_t k = 0; k < 3; ++k) {
          float* out = vertices + 3 * (3 * i + k);
          out[0] = v[k]->x;
          out[1] = v[k]->y;
          out[2] = v[k]->z;
          indices[3 * i + k] = static_cast<uint32_t>(3 * i + k);
        }
      }
      rtcSetGeometryBuildQuality(geom, RTC_BUILD_QUALITY_HIGH);
      rtcCommitGeometry(geom);
      rtcAttachGeometryByID(scene_.get(), geom, 0);
      errors_->throwIfError("geometry setup");
    }

    rtcCommitScene(scene_.get());
    errors_->throwIfError("scene build");
    packetWidth_ = nativePacketWidth(device_.get());

    stats_.name = "embree";
    stats_.buildMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    stats_.floatsPerTriangle = 0;  // Embree does not report its layout
    stats_.nodes = 0;
    stats_.leaves = 0;
    stats_.references = tris.size();
    stats_.depth = 0;
  }

  EmbreeAccelerator(const EmbreeAccelerator&) = delete;
  EmbreeAccelerator& operator=(const EmbreeAccelerator&) = delete;

  Hit intersect(const Ray& ray, bool anyHit, RayStats* /*stats: Embree counts nothing*/) const override {
    Hit none{ray.tMax};
    // Passtrace accepts 0 < t < tMax; Embree accepts tnear < t <= tfar and
    // wants tnear <= tfar. Nothing can be hit when tMax <= 0 (or is NaN).
    if (!(ray.tMax > 0.0f)) return none;
    const float tfar = std::isinf(ray.tMax) ? ray.tMax : std::nextafter(ray.tMax, 0.0f);

    RTCIntersectContext context;
    rtcInitIntersectContext(&context);

    if (anyHit) {
      RTCRay r{};
      setRay(r, ray, tfar);
      rtcOccluded1(scene_.get(), &context, &r);
      if (r.tfar == -std::numeric_limits<float>::infinity()) return Hit{0.0f, 0.0f, 0.0f, 0u};
      return none;
    }

    RTCRayHit rh;  // no zero fill: setRay and the lines below set every input field
    setRay(rh.ray, ray, tfar);
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.primID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(scene_.get(), &context, &rh);
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return none;
    // Embree compares before dividing (with an approximate reciprocal), so
    // the reported t could round up to tMax itself; keep it below.
    return Hit{std::min(rh.ray.tfar, tfar), rh.hit.u, rh.hit.v, rh.hit.primID};
  }

  int packetSize() const override { return packetWidth_; }

  // Packets of up to packetWidth_ rays through rtcIntersect16/8/4 and
  // rtcOccluded16/8/4, one lane per ray (a larger packet goes as several);
  // lanes past the packet's end and rays with nothing to hit (tMax <= 0 or
  // NaN) are masked off. Same results as intersect() ray by ray
  // (tests/unit/embree_packet_test.cpp).
  void tracePacket(const RayPacket& rays, bool anyHit, std::span<Hit> hits,
                   std::span<RayStats> /*stats: Embree counts nothing*/) const override {
    for (int first = 0; first < rays.count; first += packetWidth_) {
      const int m = std::min(packetWidth_, rays.count - first);
      const std::span<Hit> out = hits.subspan(size_t(first), size_t(m));
      switch (packetWidth_) {
        case 16: tracePacketK<16>(rays, first, m, anyHit, out); break;
        case 8: tracePacketK<8>(rays, first, m, anyHit, out); break;
        default: tracePacketK<4>(rays, first, m, anyHit, out); break;
      }
    }
  }

  std::string name() const override { return "embree"; }
  AccelStats stats() const override { return stats_; }

private:
  // Rays first .. first + n - 1 of the packet as one rtcIntersectK / rtcOccludedK.
  template <int K>
  void tracePacketK(const RayPacket& rays, int first, int n, bool anyHit, std::span<Hit> hits) const {
    using P = EmbreePacket<K>;
    alignas(64) int valid[K];
    alignas(64) typename P::RayHit rh;
    auto& r = rh.ray;
    bool any = false;
    for (int k = 0; k < K; ++k) {
      // Lanes past the end trace nothing; their fields still get finite values.
      const int i = first + (k < n ? k : 0);
      const float tMax = rays.tMax[i];
      const bool live = k < n && tMax > 0.0f;
      valid[k] = live ? -1 : 0;
      any = any || live;
      r.org_x[k] = rays.ox[i];
      r.org_y[k] = rays.oy[i];
      r.org_z[k] = rays.oz[i];
      r.tnear[k] = 0.0f;
      r.dir_x[k] = rays.dx[i];
      r.dir_y[k] = rays.dy[i];
      r.dir_z[k] = rays.dz[i];
      r.time[k] = 0.0f;
      r.tfar[k] = !live ? 0.0f : std::isinf(tMax) ? tMax : std::nextafter(tMax, 0.0f);
      r.mask[k] = static_cast<unsigned>(-1);
      r.id[k] = 0;
      r.flags[k] = 0;
      rh.hit.geomID[k] = RTC_INVALID_GEOMETRY_ID;
      rh.hit.primID[k] = RTC_INVALID_GEOMETRY_ID;
      rh.hit.instID[0][k] = RTC_INVALID_GEOMETRY_ID;
    }
    if (any) {
      RTCIntersectContext context;
      rtcInitIntersectContext(&context);
      if (anyHit)
        P::occluded(valid, scene_.get(), &context, &r);
      else
        P::intersect(valid, scene_.get(), &context, &rh);
    }
    for (int k = 0; k < n; ++k) {
      const float tMax = rays.tMax[first + k];
      const Hit none{tMax};
      if (!valid[k]) {
        hits[size_t(k)] = none;
      } else if (anyHit) {
        hits[size_t(k)] = r.tfar[k] == -std::numeric_limits<float>::infinity() ? Hit{0.0f, 0.0f, 0.0f, 0u} : none;
      } else if (rh.hit.geomID[k] == RTC_INVALID_GEOMETRY_ID) {
        hits[size_t(k)] = none;
      } else {
        const float tfar = std::isinf(tMax) ? tMax : std::nextafter(tMax, 0.0f);
        hits[size_t(k)] = Hit{std::min(r.tfar[k], tfar), rh.hit.u[k], rh.hit.v[k], rh.hit.primID[k]};
      }
    }
  }

  // The widest packet Embree's build runs natively on this CPU (16 with
  // AVX-512, 8 with AVX2, else 4); narrower ones are emulated by Embree.
  static int nativePacketWidth(RTCDevice device) {
    if (rtcGetDeviceProperty(device, RTC_DEVICE_PROPERTY_NATIVE_RAY16_SUPPORTED)) return 16;
    if (rtcGetDeviceProperty(device, RTC_DEVICE_PROPERTY_NATIVE_RAY8_SUPPORTED)) return 8;
    if (rtcGetDeviceProperty(device, RTC_DEVICE_PROPERTY_NATIVE_RAY4_SUPPORTED)) return 4;
    return 0;
  }

  static void setRay(RTCRay& r, const Ray& ray, float tfar) {
    r.org_x = ray.origin.x;
    r.org_y = ray.origin.y;
    r.org_z = ray.origin.z;
    r.tnear = 0.0f;
    r.dir_x = ray.direction.x;
    r.dir_y = ray.direction.y;
    r.dir_z = ray.direction.z;
    r.time = 0.0f;
    r.tfar = tfar;
    r.mask = static_cast<unsigned>(-1);
    r.id = 0;
    r.flags = 0;
  }

  struct DeviceRelease {
    void operator()(RTCDevice d) const { rtcReleaseDevice(d); }
  };
  struct GeometryRelease {
    void operator()(RTCGeometry g) const { rtcReleaseGeometry(g); }
  };
  struct SceneRelease {
    void operator()(RTCScene s) const { rtcReleaseScene(s); }
  };

  // RAII, in this order so that destruction (reverse order, also after a
  // constructor throws) releases the scene, then the device, and only then
  // the error sink the device calls into. errors_ is heap-allocated so the
  // address registered with the device never moves.
  std::unique_ptr<ErrorSink> errors_;
  std::unique_ptr<RTCDeviceTy, DeviceRelease> device_;
  std::unique_ptr<RTCSceneTy, SceneRelease> scene_;
  AccelStats stats_;
  int packetWidth_ = 0;  // 0: Embree was built without packet support
};

}  // namespace

std::unique_ptr<CpuAccelerator> makeEmbreeAccelerator(std::span<const Triangle> tris) {
  return std::make_unique<EmbreeAccelerator>(tris);
}

std::unique_ptr<CpuAccelerator> makeEmbreeCpu(std::span<const Triangle> tris, const AccelBuildConfig&) {
  return makeEmbreeAccelerator(tris);
}

}  // namespace passtrace
