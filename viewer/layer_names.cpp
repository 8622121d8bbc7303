// The layers' names (renderer.hpp's Layer), for the panels, the script and messages.
#include <optional>
#include <string>
#include <string_view>

#include "renderer.hpp"

namespace cudahull::viewer {

namespace {

constexpr const char* kLayerNames[kLayerCount] = {"hull",       "wireframe", "internal", "external",
                                                  "vertices",   "cells",     "swaps",    "normals",
                                                  "refinement", "labels",    "input"};

}  // namespace

const char* layer_name(Layer layer) {
  return kLayerNames[static_cast<int>(layer)];
}

std::optional<Layer> layer_from_name(std::string_view name) {
  for (int i = 0; i < kLayerCount; ++i) {
    if (name == kLayerNames[i]) return static_cast<Layer>(i);
  }
  return std::nullopt;
}

std::string layer_names() {
  std::string out;
  for (int i = 0; i < kLayerCount; ++i)
    out += (i ? ", " : "") + std::string(kLayerNames[i]);
  return out;
}

}  // namespace cudahull::viewer
