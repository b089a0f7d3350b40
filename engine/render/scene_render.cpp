// scene_render.cpp — scene -> settled proxy -> frame -> offscreen pixels.
#include "engine/render/scene_render.hpp"

#include "engine/render/offscreen.hpp"
#include "haptics/wearable/contact_display.hpp"

namespace contactlab::render {

RenderResult render_scene(const VulkanContext& ctx, const Scene& scene, const RenderRequest& request) {
    const Environment env = build_environment(scene);
    const ProxyDef def = proxy_def_of(scene);
    const FingerPose pose = request.finger ? *request.finger : default_finger_pose(env, def);

    FrameContent content;
    content.scene = &scene;
    content.env = &env;
    content.finger = settle_proxy(env, def, pose);
    content.shape = def.finger;
    content.max_force = def.max_force;
    content.overlays = request.overlays;
    content.text = request.text;
    content.top_inset_px = request.top_inset_px;
    content.left_inset_px = request.left_inset_px;
    content.bottom_inset_px = request.bottom_inset_px;
    content.right_inset_px = request.right_inset_px;
    content.status_line = request.status_line;
    if (request.wearable) {
        const ProxyOutput& o = *content.finger;
        const wearable::PlatformDisplayState st = wearable::platform_display_state(o.force.x, o.force.y, o.phi);
        PlatformDrawing pd;
        pd.roll = st.command.roll;
        pd.press = st.command.press;
        pd.tension = {st.tension(0), st.tension(1), st.tension(2)};
        content.platform = pd;
    }

    RenderResult result;
    result.view = request.view_box    ? fit_view(*request.view_box, request.width, request.height, 0.0)
                  : request.wearable ? fingertip_view(content, request.width, request.height)
                                     : default_view(content, request.width, request.height);
    result.proxy = *content.finger;
    DrawList list(request.width, request.height);
    build_frame(content, result.view, request.theme, list, &result.labels);
    OffscreenTarget target(ctx, request.width, request.height);
    result.image = target.render(list, request.theme.background);
    return result;
}

}  // namespace contactlab::render
