#pragma once
// What this passtrace offers, read from the registries: renderers,
// structures (accel/registry.h) and scenes (scenes/scene_registry.h). The
// command line prints it for --list (text) and --list --json (the contract
// scripts/bench.py and the tests read); --help shows the text.

#include <filesystem>
#include <string>

#include <nlohmann/json_fwd.hpp>  // the whole of it in catalog.cpp: a heavy parse

namespace passtrace {

// {"version", "renderers": [{"name","id"}], "accelerators": [{"name",
// "renderers", "number", "description"}], "scenes": [{"name","number"}]}.
// The scenes list the real benchmark scenes found under `realScenesDir`
// (--scenes-dir; empty: $PASSTRACE_SCENES_DIR or ../shared/scenes/real).
nlohmann::json catalogJson(const std::filesystem::path& realScenesDir = {});
// catalogJson() as the command line writes it (--list --json): indented, one
// newline at the end.
std::string catalogJsonText(const std::filesystem::path& realScenesDir = {});
// The same as aligned text: one line per structure and per scene.
std::string catalogText(const std::filesystem::path& realScenesDir = {});

}  // namespace passtrace
