// trace_cli.cpp — the `trace` and `demo` subcommands on the command line.
#include "engine/app/scene_overrides.hpp"
#include "engine/app/start_inside_warning.hpp"
#include "engine/app/subcommands.hpp"
#include "engine/app/trace_command.hpp"
#include "haptics/scene_io.hpp"

#include <contactlab/version.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>

namespace contactlab::app {
namespace {

int trace_main(const std::string& scene_path, const std::string& input, const std::string& output,
               const SceneOverrides& overrides) {
    Scene scene = load_scene_file(scene_path);
    apply_overrides(scene, overrides);
    const auto samples = read_finger_samples_file(input);
    if (!samples.empty()) {
        const FingerSample& first = samples.front();
        const std::string warning = start_inside_warning("trace", scene, first.t, first.x, first.phi);
        if (!warning.empty()) std::fprintf(stderr, "%s\n", warning.c_str());
    }
    const auto outputs = run_trace(scene, samples);
    write_trace_file(output, samples, outputs);
    std::size_t in_contact = 0;
    for (const auto& o : outputs) in_contact += o.contact ? 1 : 0;
    std::fprintf(stderr, "trace: %zu samples, %zu in contact, written to %s\n", outputs.size(), in_contact,
                 output.c_str());
    return 0;
}

int demo_main(const std::string& scene_path, const SceneOverrides& overrides) {
    Scene scene = load_scene_file(scene_path);
    apply_overrides(scene, overrides);
    std::printf("ContactLab %s — headless demo (the editor: contactlab edit).\n", CONTACTLAB_VERSION);
    std::printf("Scene %s: finger R = %.1f mm, L = %.1f mm; Ke = %.0f N/m, max force %.2f N.\n",
                scene_path.c_str(), scene.finger.radius * 1e3, scene.finger.length * 1e3, scene.force.stiffness,
                scene.force.max_force);
    const double press = 0.001;  // m below the surface
    const double x0 = -0.12, speed = 0.03, duration = 8.0;  // m, m/s, s
    const auto run = run_contour_follow(scene, x0, speed, press, duration);
    const auto& samples = run.samples;
    const auto& outputs = run.outputs;
    std::printf("A scripted hand descends at x = %.0f mm, then follows the contour at %.0f mm/s pressing\n"
                "%.1f mm into it and tipping the finger so the pad faces the surface (seed 000's block task);\n"
                "one proxy tick per 1 ms:\n\n", x0 * 1e3, speed * 1e3, press * 1e3);
    std::printf("   t (s)   x_f (mm)  y_f (mm)  phi (deg)  proxy x,y (mm)      contacts  depth (mm)  |F| (N)  l_d (mm)\n");
    double max_force = 0.0, l_min = 1e9, l_max = -1e9;
    int changes = 0, prev_count = -1;
    for (std::size_t i = 0; i < outputs.size(); ++i) {
        const ProxyOutput& o = outputs[i];
        const double f = std::hypot(o.force.x, o.force.y);
        max_force = std::max(max_force, f);
        if (o.contact) { l_min = std::min(l_min, o.l_d); l_max = std::max(l_max, o.l_d); }
        const bool changed = o.contact_count != prev_count;
        changes += changed && i > 0 ? 1 : 0;
        prev_count = o.contact_count;
        if (i % 250 == 0 || (changed && i > 0))
            std::printf("%8.3f  %8.2f  %8.2f  %9.1f  (%7.2f, %7.2f)  %8d  %10.3f  %7.3f  %8.3f%s\n", samples[i].t,
                        o.finger.x * 1e3, o.finger.y * 1e3, o.phi * 180.0 / kPi, o.proxy.x * 1e3, o.proxy.y * 1e3, o.contact_count,
                        o.depth * 1e3, f, o.l_d * 1e3, changed && i > 0 ? "   <- contacts changed" : "");
    }
    std::printf("\n%zu ticks, %d contact changes, max |F| = %.3f N, l_d in [%.2f, %.2f] mm.\n", outputs.size(),
                changes, max_force, l_min * 1e3, l_max * 1e3);
    std::printf("\nHeadless commands:\n"
                "  contactlab trace SCENE --input IN.csv --output OUT.csv   (IN header: t,x,y,phi)\n"
                "  contactlab --help\n");
    return 0;
}


// Options shared by both subcommands (CLI11 keeps pointers into it until parsing ends).
struct TraceArgs {
    std::string scene_path, input, output;
    SceneOverrides overrides;
};

}  // namespace

void register_trace_commands(CLI::App& app, int& rc) {
    static TraceArgs trace_args, demo_args;  // outlive parsing; one process, one parse
    CLI::App* trace = app.add_subcommand("trace", "Run the arc-finger proxy over finger samples (CSV in, CSV out)");
    trace->add_option("scene", trace_args.scene_path, "Scene file (JSON, scenes/README.md)")->required();
    trace->add_option("--input,-i", trace_args.input, "Finger samples, header t,x,y,phi (s, m, m, rad)")->required();
    trace->add_option("--output,-o", trace_args.output,
                      "Proxy states, header t,x,y,phi,proxy_x,proxy_y,contact,depth,fx,fy,l_d,stiction_x,stiction_y")->required();
    add_override_options(trace, trace_args.overrides);
    trace->callback([&rc] {
        rc = trace_main(installed_data_path(trace_args.scene_path), trace_args.input, trace_args.output, trace_args.overrides);
    });

    CLI::App* demo = app.add_subcommand("demo", "Headless demo: a scripted hand follows a scene's contour");
    demo->add_option("--scene", demo_args.scene_path, "Scene file")->default_val("scenes/block.json");
    add_override_options(demo, demo_args.overrides);
    demo->callback([&rc] { rc = demo_main(installed_data_path(demo_args.scene_path), demo_args.overrides); });
}

}  // namespace contactlab::app
