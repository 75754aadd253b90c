#include "render/shading_config.h"

namespace passtrace {

std::optional<ShadingMode> shadingModeByName(std::string_view name) {
  if (name == "thesis") return ShadingMode::Thesis;
  if (name == "whitted") return ShadingMode::Whitted;
  if (name == "ao") return ShadingMode::Ao;
  return std::nullopt;
}

const char* shadingModeName(ShadingMode mode) {
  switch (mode) {
    case ShadingMode::Thesis: return "thesis";
    case ShadingMode::Whitted: return "whitted";
    case ShadingMode::Ao: return "ao";
  }
  return "thesis";
}

}  // namespace passtrace
