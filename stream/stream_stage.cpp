#include "stream/stream_stage.h"

namespace passtrace {
namespace {

// Per thread, as a GL context is current per thread.
thread_local StreamStage current = StreamStage::Fragment;

}  // namespace

const char* streamStageName(StreamStage stage) { return stage == StreamStage::Compute ? "compute" : "fragment"; }

std::optional<StreamStage> parseStreamStage(std::string_view name) {
  if (name == "fragment") return StreamStage::Fragment;
  if (name == "compute") return StreamStage::Compute;
  return std::nullopt;
}

StreamStage currentStreamStage() { return current; }

StreamStageScope::StreamStageScope(StreamStage stage) : previous_(current) { current = stage; }

StreamStageScope::~StreamStageScope() { current = previous_; }

}  // namespace passtrace
