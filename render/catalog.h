#pragma once
// What this passtrace offers, read from the registries: renderers,
// structures (accel/registry.h) and scenes (scenes/scene_registry.h). The
// command line prints it for --list (text) and --list --json (the contract
// scripts/bench.py and the tests read); --help shows the text.

#include <string>

#include <nlohmann/json.hpp>

namespace passtrace {

// {"version", "renderers": [{"name","id"}], "accelerators": [{"name",
// "renderers", "number", "description"}], "scenes": [{"name","number"}]}.
nlohmann::json catalogJson();
// The same as aligned text: one line per structure and per scene.
std::string catalogText();

}  // namespace passtrace
