// scene_render.hpp — one call from a scene file's contents to pixels: environment, settled proxy,
// default view, draw list, offscreen render. Used by `contactlab render` and the snapshot tests.
#pragma once

#include "engine/render/context.hpp"
#include "engine/render/finger_state.hpp"
#include "engine/render/frame.hpp"
#include "engine/render/image.hpp"

#include <optional>

namespace contactlab::render {

struct RenderRequest {
    int width = 1280, height = 720;   // px
    std::optional<FingerPose> finger; // default_finger_pose when empty
    Overlays overlays;
    Theme theme = dark_theme();
    bool text = false;  // labels (FrameContent::text); the CLI turns them on, goldens leave them off
    // Draw seed 003's wearable platform under the pad as the servo would command it for this
    // contact (haptics/wearable/contact_display.hpp), with the cable tensions that hold it.
    // With it, the view is zoomed on the fingertip (fingertip_view), where the platform shows.
    bool wearable = false;
    // The part of the world to show (m, x right, y up), fitted to the image; else the default
    // view (or the fingertip's with `wearable`). `contactlab render --view X Y W H` (mm).
    std::optional<Aabb> view_box;
    // px of each edge covered by something else (FrameContent's insets: the editor's panels);
    // labels stay clear of them. 0 for a picture of its own.
    float top_inset_px = 0.0f, left_inset_px = 0.0f, bottom_inset_px = 0.0f, right_inset_px = 0.0f;
    bool status_line = true;  // with text: the proxy's state on the canvas (the editor has a row for it)
};

// What the frame showed besides the pixels (for messages and tests).
struct RenderResult {
    Image image;
    View view;
    ProxyOutput proxy;
    LabelMarks labels;  // where the canvas's labels went, what they avoided, what was left out
};

RenderResult render_scene(const VulkanContext& ctx, const Scene& scene, const RenderRequest& request);

}  // namespace contactlab::render
