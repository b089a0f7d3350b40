// render_fixture.hpp — shared helpers of the render tests: the lavapipe context with validation,
// scene loading, rendering a scene at a small size.
#pragma once

#include "engine/render/context.hpp"
#include "engine/render/scene_render.hpp"
#include "haptics/scene_io.hpp"

#include <filesystem>
#include <string>
#include <vector>

namespace render_test {

namespace fs = std::filesystem;
using namespace contactlab;
using namespace contactlab::render;

inline fs::path source_dir() { return fs::path(CONTACTLAB_SOURCE_DIR); }

// One context per test process: lavapipe (CPU device), validation layers on, messages printed.
// Every test checks at its end that the message count is still zero.
inline const VulkanContext& lavapipe() {
    static const VulkanContext ctx(ContextOptions{.software = true, .validation = true, .quiet = false});
    return ctx;
}

inline Scene load_scene(const std::string& name) { return load_scene_file((source_dir() / "scenes" / name).string()); }

// Every shipped scene file name (scenes/*.json), sorted.
inline std::vector<std::string> shipped_scenes() {
    std::vector<std::string> names;
    for (const auto& e : fs::directory_iterator(source_dir() / "scenes"))
        if (e.path().extension() == ".json") names.push_back(e.path().filename().string());
    std::sort(names.begin(), names.end());
    return names;
}

// Golden size: small, so goldens stay a few kB each and renders take milliseconds.
inline constexpr int kGoldenWidth = 320, kGoldenHeight = 180;

}  // namespace render_test
