// scene_layer_key.hpp — what the frame's scene layer (grid and solids, render::build_scene_layer)
// depends on, so the editor rebuilds its draw list and its kept picture (scene_layer_cache.hpp)
// only when one of these changes: the document's revision (unique across documents, so File >
// New or Open changes it too), whether an experiment hides the scene, the view (size, centre,
// zoom) and the theme. The zones overlay makes the layer follow the finger as well; the editor
// then builds it every frame and does not keep it.
#pragma once

#include "engine/render/theme.hpp"
#include "engine/render/view.hpp"

#include <cstdint>

namespace contactlab::editor {

struct SceneLayerKey {
    std::uint64_t revision = 0;
    bool hidden = false;  // an experiment: the stimulus is felt, not drawn
    int width = 0, height = 0;
    double center_x = 0.0, center_y = 0.0, px_per_m = 0.0;
    const render::Theme* theme = nullptr;

    static SceneLayerKey of(std::uint64_t revision, bool hidden, const render::View& v, const render::Theme& theme) {
        return {hidden ? 0 : revision, hidden, v.width, v.height, v.center.x, v.center.y, v.px_per_m, &theme};
    }
    bool operator==(const SceneLayerKey&) const = default;
};

}  // namespace contactlab::editor
