// render_frames.cpp — offscreen frame time per scene size (render_frames.hpp), on Google
// Benchmark with one iteration per frame, each frame also timed on its own.
#include "engine/bench/render_frames.hpp"

#include "engine/bench/cost_scenes.hpp"
#include "engine/bench/gbench_run.hpp"
#include "engine/render/context.hpp"
#include "engine/render/finger_state.hpp"
#include "engine/render/frame.hpp"
#include "engine/render/offscreen.hpp"

#include <benchmark/benchmark.h>

#include <exception>

namespace contactlab::bench {
namespace {

RenderFrameRow time_frames(const render::VulkanContext& ctx, int segments, int frames, int width, int height) {
    const Scene scene = cost_scene(CostCase{SegmentKind::lines, Growth::dense, segments});
    const Environment env = build_environment(scene);
    const ProxyDef def = proxy_def_of(scene);
    render::FrameContent content;
    content.scene = &scene;
    content.env = &env;
    content.shape = def.finger;
    content.max_force = def.max_force;
    content.finger = render::settle_proxy(env, def, render::default_finger_pose(env, def));
    content.text = true;  // as `contactlab render` draws it: labels included
    const render::View view = render::default_view(content, width, height);
    const render::Theme& theme = render::dark_theme();

    RenderFrameRow row;
    row.segments = segments;
    render::OffscreenTarget target(ctx, width, height);
    render::DrawList list(width, height);
    // One warm-up frame outside the timing: first-use costs (pipeline caches, page faults).
    render::build_frame(content, view, theme, list);
    (void)target.render(list, theme.background);

    const std::string name = "render_frame/" + std::to_string(segments);
    benchmark::RegisterBenchmark(name.c_str(), [&](benchmark::State& state) {
        TickTimer timer(static_cast<std::size_t>(frames));
        for (auto _ : state) {
            timer.time([&] {
                render::build_frame(content, view, theme, list);
                render::Image img = target.render(list, theme.background);
                benchmark::DoNotOptimize(img.rgba.data());
            });
        }
        row.frame = timer.stats();
        row.triangles = list.indices().size() / 3;
        state.counters["median_ms"] = row.frame.median_ns / 1e6;
        state.counters["p99_ms"] = row.frame.p99_ns / 1e6;
    })->Iterations(frames)->Unit(benchmark::kMillisecond)->UseRealTime();
    run_registered();
    return row;
}

}  // namespace

RenderFrameResults render_frame_suite(bool quick) {
    RenderFrameResults r;
    const int frames = quick ? 8 : 60;
    try {
        const render::VulkanContext ctx(render::ContextOptions{});
        r.device = ctx.device_name();
        for (const int n : {10, 1000, 100000}) r.rows.push_back(time_frames(ctx, n, frames, r.width, r.height));
    } catch (const std::exception& e) {
        // No device (or a failing one) must not cost the user the proxy tables: say why instead.
        r.rows.clear();
        r.skipped = e.what();
    }
    return r;
}

}  // namespace contactlab::bench
