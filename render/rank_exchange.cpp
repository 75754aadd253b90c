#include "render/rank_exchange.h"

#include <algorithm>
#include <cstring>
#include <stdexcept>
#include <string_view>

#include <nlohmann/json.hpp>

#include "render/row_bands.h"

namespace passtrace {
namespace {

using nlohmann::json;

// A message is chunks, each its length (8 bytes) and its bytes: first the
// description as CBOR (numbers as doubles and integers: exact, so rank 0's
// sums are the single process's), then the arrays and files as raw bytes —
// nlohmann's CBOR reads a byte string a byte at a time: a Kitchen 1024² frame
// of two ranks took about 136 ms more than its renders that way, about 20 ms
// with raw chunks.
class ChunkWriter {
 public:
  void add(const void* data, size_t bytes) {
    const uint64_t length = bytes;
    out_.append(reinterpret_cast<const char*>(&length), sizeof length);
    out_.append(static_cast<const char*>(data), bytes);
  }
  void add(const json& description) {
    const std::vector<uint8_t> cbor = json::to_cbor(description);
    add(cbor.data(), cbor.size());
  }
  template <typename T>
  void add(const std::vector<T>& values) { add(values.data(), values.size() * sizeof(T)); }
  void add(const std::string& bytes) { add(bytes.data(), bytes.size()); }
  std::string take() { return std::move(out_); }

 private:
  std::string out_;
};

class ChunkReader {
 public:
  explicit ChunkReader(const std::string& in) : in_(in) {}
  std::string_view next() {
    uint64_t length = 0;
    if (in_.size() - at_ < sizeof length) throw std::runtime_error("a rank sent a truncated message");
    std::memcpy(&length, in_.data() + at_, sizeof length);
    at_ += sizeof length;
    if (in_.size() - at_ < length) throw std::runtime_error("a rank sent a truncated message");
    const std::string_view chunk(in_.data() + at_, size_t(length));
    at_ += size_t(length);
    return chunk;
  }
  json description() {
    const std::string_view c = next();
    return json::from_cbor(c.begin(), c.end());
  }
  template <typename T>
  std::vector<T> array() {
    const std::string_view c = next();
    if (c.size() % sizeof(T) != 0) throw std::runtime_error("a rank sent a malformed array");
    std::vector<T> values(c.size() / sizeof(T));
    if (!values.empty()) std::memcpy(values.data(), c.data(), c.size());
    return values;
  }

 private:
  const std::string& in_;
  size_t at_ = 0;
};

json statsJson(const FrameStats& s) {
  json j = {{"rays", s.rays},         {"passes", s.passes},       {"steps", s.steps},
            {"tests", s.triangleTests}, {"max_steps", s.maxStepsPerRay}, {"max_tests", s.maxTriangleTestsPerRay},
            {"ms", s.frameMs}};
  if (s.filter)
    j["filter"] = {s.filter->rayBox, s.filter->coneBox, s.filter->triangleBox, s.filter->rayTriangle, s.filter->nodes};
  return j;
}

FrameStats statsOf(const json& j) {
  FrameStats s;
  s.rays = j.at("rays"), s.passes = j.at("passes"), s.steps = j.at("steps"), s.triangleTests = j.at("tests");
  s.maxStepsPerRay = j.at("max_steps"), s.maxTriangleTestsPerRay = j.at("max_tests"), s.frameMs = j.at("ms");
  if (j.contains("filter")) {
    const json& f = j["filter"];
    s.filter = FilterStats{f.at(0), f.at(1), f.at(2), f.at(3), f.at(4)};
  }
  return s;
}

json accelJson(const AccelStats& s) {
  return {s.name, s.buildMs, s.floatsPerTriangle, s.nodes, s.leaves, s.references,
          s.depth, s.sahCost, s.structureBytes, s.nodeTestBytes, s.triangleTestBytes};
}

AccelStats accelOf(const json& j) {
  AccelStats s;
  s.name = j.at(0), s.buildMs = j.at(1), s.floatsPerTriangle = j.at(2), s.nodes = j.at(3), s.leaves = j.at(4);
  s.references = j.at(5), s.depth = j.at(6), s.sahCost = j.at(7), s.structureBytes = j.at(8);
  s.nodeTestBytes = j.at(9), s.triangleTestBytes = j.at(10);
  return s;
}

json sequenceJson(const SequenceFrame& f) {
  return {f.frame, f.time, f.triangles, f.movingTriangles, f.buildMs, f.frameMs, f.rays, f.mraysPerS, f.totalMs};
}

SequenceFrame sequenceOf(const json& j) {
  SequenceFrame f;
  f.frame = j.at(0), f.time = j.at(1), f.triangles = j.at(2), f.movingTriangles = j.at(3), f.buildMs = j.at(4);
  f.frameMs = j.at(5), f.rays = j.at(6), f.mraysPerS = j.at(7), f.totalMs = j.at(8);
  return f;
}

}  // namespace

std::string packShare(const RankShare& share) {
  json angles = json::array(), frames = json::array(), files = json::array();
  for (const AngleOutcome& a : share.angles) angles.push_back({a.angle, statsJson(a.stats)});
  for (const SequenceOutcome& f : share.frames)
    frames.push_back({sequenceJson(f.record), statsJson(f.stats), accelJson(f.structure)});
  for (const FileBytes& f : share.files) files.push_back(f.path);
  const RankRun& r = share.run;
  ChunkWriter out;
  out.add(json{{"run", {r.rank, r.host, r.buildMs, r.traceMs, r.share}},
               {"angles", angles},
               {"frames", frames},
               {"files", files}});
  for (const FileBytes& f : share.files) out.add(f.bytes);
  return out.take();
}

RankShare unpackShare(const std::string& bytes) {
  ChunkReader in(bytes);
  const json j = in.description();
  RankShare share;
  const json& r = j.at("run");
  share.run = RankRun{r.at(0), r.at(1), r.at(2), r.at(3), r.at(4)};
  for (const json& a : j.at("angles")) share.angles.push_back({a.at(0), statsOf(a.at(1))});
  for (const json& f : j.at("frames")) share.frames.push_back({sequenceOf(f.at(0)), statsOf(f.at(1)), accelOf(f.at(2))});
  for (const json& path : j.at("files")) share.files.push_back({path, std::string(in.next())});
  return share;
}

std::string packBand(const FrameResult& band) {
  ChunkWriter out;
  out.add(json{{"width", band.width}, {"height", band.height}, {"stats", statsJson(band.stats)}});
  out.add(band.rgb);
  out.add(band.steps);
  out.add(band.primaryHits);
  return out.take();
}

FrameResult assembleBands(const std::vector<std::string>& parts, int fullHeight) {
  FrameResult whole;
  whole.height = fullHeight;
  const int ranks = int(parts.size());
  for (int r = 0; r < ranks; ++r) {
    ChunkReader in(parts[size_t(r)]);
    const json j = in.description();
    const RowBands rows = RowBands::interleaved(fullHeight, ranks, r);
    const int width = j.at("width"), height = j.at("height");
    if (height != rows.localHeight()) throw std::runtime_error("rank " + std::to_string(r) + " sent the wrong rows");
    const std::vector<float> rgb = in.array<float>(), steps = in.array<float>();
    const std::vector<HitRecord> hits = in.array<HitRecord>();
    if (r == 0) {
      whole.width = width;
      const size_t pixels = size_t(width) * size_t(fullHeight);
      whole.rgb.assign(3 * pixels, 0.0f);
      if (!steps.empty()) whole.steps.assign(pixels, 0.0f);
      if (!hits.empty()) whole.primaryHits.assign(pixels, HitRecord{});
    }
    for (int y = 0; y < height; ++y) {
      const size_t from = size_t(y) * size_t(width), to = size_t(rows.globalRow(y)) * size_t(width);
      std::copy_n(rgb.begin() + std::ptrdiff_t(3 * from), 3 * width, whole.rgb.begin() + std::ptrdiff_t(3 * to));
      if (!whole.steps.empty() && !steps.empty())
        std::copy_n(steps.begin() + std::ptrdiff_t(from), width, whole.steps.begin() + std::ptrdiff_t(to));
      if (!whole.primaryHits.empty() && !hits.empty())
        std::copy_n(hits.begin() + std::ptrdiff_t(from), width, whole.primaryHits.begin() + std::ptrdiff_t(to));
    }
    const FrameStats s = statsOf(j.at("stats"));
    FrameStats& w = whole.stats;
    w.rays += s.rays, w.steps += s.steps, w.triangleTests += s.triangleTests;
    w.passes = std::max(w.passes, s.passes);
    w.frameMs = std::max(w.frameMs, s.frameMs);
    w.maxStepsPerRay = std::max(w.maxStepsPerRay, s.maxStepsPerRay);
    w.maxTriangleTestsPerRay = std::max(w.maxTriangleTestsPerRay, s.maxTriangleTestsPerRay);
    if (s.filter) w.filter = w.filter.value_or(FilterStats{}) += *s.filter;
  }
  return whole;
}

}  // namespace passtrace
