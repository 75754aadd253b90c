#pragma once
// Which GL stage runs the stream kernels (-r 2 --stage). The thesis's model,
// Fragment: every kernel a fragment program drawn as a full-screen quad,
// finished elements masked by the depth test, active ones counted by
// occlusion queries. Compute: the same GLSL sources as compute shaders
// (stream/compute_variant.h) over index lists of the active elements
// (stream/active_elements.h), counted with atomic counters.
//
// Streams and kernels take the stage current when they are made, so a
// renderer, its structure and their kernels all follow the one setting the
// run makes (StreamStageScope), as they all follow the one GL context.

#include <optional>
#include <string_view>

namespace passtrace {

enum class StreamStage { Fragment, Compute };

const char* streamStageName(StreamStage stage);  // "fragment", "compute"
std::optional<StreamStage> parseStreamStage(std::string_view name);

// The stage new streams and kernels take; Fragment unless a scope says otherwise.
StreamStage currentStreamStage();

// Sets the current stage for its lifetime, then restores the previous one.
class StreamStageScope {
 public:
  explicit StreamStageScope(StreamStage stage);
  ~StreamStageScope();
  StreamStageScope(const StreamStageScope&) = delete;
  StreamStageScope& operator=(const StreamStageScope&) = delete;

 private:
  StreamStage previous_;
};

}  // namespace passtrace
