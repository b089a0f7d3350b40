// render_cli.cpp — the `render` subcommand: a scene drawn offscreen with Vulkan into a PNG.
//
//   contactlab render SCENE.json --output OUT.png [--width 1280] [--height 720]
//       [--finger x,y,phi] [--overlay cspace,zones] [--theme dark|light] [--wearable]
//       [--view X Y W H] [--software]
//
// The finger, proxy, force and contacts are what the haptics Proxy computes for that finger
// configuration approached from free space (engine/render/finger_state.hpp). Without a Vulkan
// device the command exits 2 and names the Debian package that provides one.
#include "engine/app/subcommands.hpp"
#include "engine/render/context.hpp"
#include "engine/render/scene_render.hpp"
#include "engine/render/vk_check.hpp"
#include "haptics/scene_io.hpp"

#include <cmath>
#include <cstdio>
#include <sstream>
#include <string>
#include <vector>

namespace contactlab::app {
namespace {

struct RenderArgs {
    std::string scene_path, output;
    int width = 1280, height = 720;
    std::string finger;                // "x,y,phi" (m, m, rad)
    std::vector<std::string> overlays; // cspace, zones
    std::string theme = "dark";
    bool software = false;
    bool no_text = false;
    bool wearable = false;
    std::vector<double> view_mm;       // X Y W H (mm): lower-left corner, width, height
#ifdef NDEBUG
    bool validation = false;
#else
    bool validation = true;  // debug builds: validation layers on by default
#endif
};

render::FingerPose parse_finger(const std::string& text) {
    std::vector<double> v;
    std::stringstream ss(text);
    std::string item;
    while (std::getline(ss, item, ',')) {
        std::size_t used = 0;
        double d = 0.0;
        try {
            d = std::stod(item, &used);
        } catch (const std::exception&) {
            used = 0;
        }
        while (used < item.size() && item[used] == ' ') ++used;
        if (item.empty() || used != item.size() || !std::isfinite(d))
            throw BadInput("--finger: not a number: \"" + item + "\" (expected x,y,phi in m, m, rad)");
        v.push_back(d);
    }
    if (v.size() != 3) throw BadInput("--finger: expected three numbers x,y,phi (m, m, rad), got \"" + text + "\"");
    return {{v[0], v[1]}, v[2]};
}

int render_main(const RenderArgs& args) {
    Scene scene = load_scene_file(args.scene_path);
    render::RenderRequest req;
    if (args.width < 1 || args.width > 16384) throw BadInput("--width: must be in 1..16384 px");
    if (args.height < 1 || args.height > 16384) throw BadInput("--height: must be in 1..16384 px");
    req.width = args.width;
    req.height = args.height;
    if (!args.finger.empty()) req.finger = parse_finger(args.finger);
    for (const std::string& o : args.overlays) {
        if (o == "cspace") req.overlays.cspace = true;
        else if (o == "zones") req.overlays.zones = true;
        else throw BadInput("--overlay: unknown overlay \"" + o + "\" (known: cspace, zones)");
    }
    const auto theme = render::theme_by_name(args.theme);
    if (!theme) throw BadInput("--theme: unknown theme \"" + args.theme + "\" (known: dark, light)");
    req.theme = *theme;
    req.text = !args.no_text;
    req.wearable = args.wearable;
    if (!args.view_mm.empty()) {
        const auto& v = args.view_mm;
        if (v.size() != 4) throw BadInput("--view: expected X Y W H (mm), got " + std::to_string(v.size()) + " number(s)");
        for (double d : v)
            if (!std::isfinite(d)) throw BadInput("--view: X Y W H must be finite numbers (mm)");
        if (!(v[2] > 0.0 && v[3] > 0.0)) throw BadInput("--view: W and H must be > 0 mm");
        Aabb box;
        box.grow(Vec2(v[0], v[1]) * 1e-3);
        box.grow(Vec2(v[0] + v[2], v[1] + v[3]) * 1e-3);
        req.view_box = box;
    }

    render::ContextOptions options;
    options.software = args.software;
    options.validation = args.validation;
    try {
        const render::VulkanContext ctx(options);
        const render::RenderResult r = render::render_scene(ctx, scene, req);
        render::write_png(args.output, r.image);
        const double f = std::hypot(r.proxy.force.x, r.proxy.force.y);
        std::fprintf(stderr,
                     "render: %dx%d on %s, finger (%.2f, %.2f) mm phi %.3f rad, %s, |F| = %.3f N, l_d = %.2f mm; "
                     "written to %s\n",
                     req.width, req.height, ctx.device_name().c_str(), r.proxy.finger.x * 1e3, r.proxy.finger.y * 1e3,
                     r.proxy.phi, r.proxy.contact ? "in contact" : "free", f, r.proxy.l_d * 1e3, args.output.c_str());
        if (ctx.validation_messages() > 0) {
            std::fprintf(stderr, "render: %d validation messages\n", ctx.validation_messages());
            return 1;
        }
    } catch (const render::NoVulkanDevice& e) {
        throw BadInput(e.what());
    }
    return 0;
}

}  // namespace

void register_render_command(CLI::App& app, int& rc) {
    static RenderArgs args;  // outlives parsing; one process, one parse
    CLI::App* cmd = app.add_subcommand("render", "Draw a scene offscreen with Vulkan into a PNG");
    cmd->add_option("scene", args.scene_path, "Scene file (JSON, scenes/README.md)")->required();
    cmd->add_option("--output,-o", args.output, "PNG file to write")->required();
    cmd->add_option("--width", args.width, "Image width (px)")->default_val(1280);
    cmd->add_option("--height", args.height, "Image height (px)")->default_val(720);
    cmd->add_option("--finger", args.finger,
                    "Finger centre and angle x,y,phi (m, m, rad); default: 1 mm into the top of the scene, mid-way");
    cmd->add_option("--overlay", args.overlays, "Overlays: cspace (c-space boundary), zones (anticipation zones)")
        ->delimiter(',');
    cmd->add_option("--theme", args.theme, "Colour theme: dark or light")->default_val("dark");
    cmd->add_flag("--no-text", args.no_text, "Leave out the labels (scale and force values, status line)");
    cmd->add_flag("--wearable", args.wearable,
                  "Draw seed 003's wearable platform under the pad as the servo would command it for this contact "
                  "(tilt, press, cables and their tensions, the contact frame), zoomed on the fingertip unless --view");
    cmd->add_option("--view", args.view_mm,
                    "The part of the world to draw: X Y W H in mm (lower-left corner, width, height; also X,Y,W,H), "
                    "fitted to the image; default: the whole scene (with --wearable: the fingertip)")
        ->expected(4)
        ->delimiter(',')
        ->allow_extra_args(false);
    cmd->add_flag("--software", args.software, "Use the CPU Vulkan device (lavapipe): bit-stable output");
    cmd->add_flag("--validation,!--no-validation", args.validation,
                  "Vulkan validation layers (default: on in debug builds); any validation message makes the "
                  "command fail (exit 1)");
    cmd->callback([&rc] {
        args.scene_path = installed_data_path(args.scene_path);
        rc = render_main(args);
    });
}

}  // namespace contactlab::app
