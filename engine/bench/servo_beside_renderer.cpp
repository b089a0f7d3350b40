// servo_beside_renderer.cpp — see servo_beside_renderer.hpp.
#include "engine/bench/servo_beside_renderer.hpp"

#include "drivers/servo_loop.hpp"
#include "drivers/servo_runner.hpp"
#include "drivers/sim/sim_cld_device.hpp"
#include "drivers/tasks.hpp"
#include "engine/bench/cost_scenes.hpp"
#include "engine/render/context.hpp"
#include "engine/render/finger_state.hpp"
#include "engine/render/frame.hpp"
#include "engine/render/offscreen.hpp"
#include "haptics/servo_tick.hpp"

#include <atomic>
#include <chrono>
#include <exception>
#include <memory>
#include <sched.h>
#include <thread>

namespace contactlab::bench {
namespace {

// One servo run of `seconds` at `rate` (Hz) on sim-cld's block task, pinned to `core`, while
// `beside` runs on the calling thread (returns when the servo is done).
template <class Beside>
ServoPeriodFigures run_servo(int core, double rate, double seconds, std::string& scheduling, Beside&& beside) {
    using namespace drivers;
    const Scene scene = block_scene();
    BlockTaskParams bp;
    bp.finger_radius = scene.finger.radius;
    sim::SimCldParams sp;
    sim::SimCldDevice dev(sp, contour_block_task(bp));
    ServoParams params;
    params.stiffness = scene.force.stiffness;
    params.max_force = scene.force.max_force;
    params.passivity = scene.force.passivity;
    ServoTick tick(servo_config_for(dev, rate), params);
    tick.scenes().publish(std::make_unique<ServoScene>(scene));
    ServoLoop loop(dev, tick, 1.0 / rate, nullptr);
    if (!loop.start()) throw std::runtime_error(std::string("sim-cld did not open: ") + dev.fault().detail);
    RunnerOptions opt;
    opt.core = core;
    opt.lock_memory = true;
    opt.max_ticks = static_cast<std::uint64_t>(seconds * rate);
    opt.zero_on_exit = true;
    ServoRunner runner(loop, opt);
    runner.start();
    beside(runner);
    runner.join();
    scheduling = runner.scheduling();
    ServoPeriodFigures f;
    f.ticks = runner.ticks();
    f.overruns = runner.overruns();
    f.p50 = runner.stats().percentile(50.0);
    f.p99 = runner.stats().percentile(99.0);
    f.max = runner.stats().max();
    return f;
}

}  // namespace

ServoBesideRenderer servo_beside_renderer(bool quick) {
    ServoBesideRenderer r;
    r.seconds = quick ? 2.0 : 5.0;
    cpu_set_t saved;
    CPU_ZERO(&saved);
    if (sched_getaffinity(0, sizeof saved, &saved) != 0 || CPU_COUNT(&saved) < 2) {
        r.skipped = "needs two CPUs (one for the servo, the rest for the renderer)";
        return r;
    }
    // The editor's split (engine/editor/live_servo.cpp reserve_servo_core): the last CPU for the
    // servo, the others for this thread and every thread it starts (lavapipe's rasterisers).
    const int core = drivers::reserve_servo_core();
    try {
        r.alone = run_servo(core, 1000.0, r.seconds, r.scheduling, [](drivers::ServoRunner&) {});
        r.alone_10k = run_servo(core, 10000.0, r.seconds, r.scheduling, [](drivers::ServoRunner&) {});
        r.floor_10k = timer_floor(core, 10000.0, static_cast<std::uint64_t>(r.seconds * 10000.0), drivers::RunnerOptions{}.spin_ns);

        const render::VulkanContext ctx(render::ContextOptions{});
        r.device = ctx.device_name();
        const Scene scene = cost_scene(CostCase{SegmentKind::lines, Growth::dense, 1000});
        const Environment env = build_environment(scene);
        const ProxyDef def = proxy_def_of(scene);
        render::FrameContent content;
        content.scene = &scene;
        content.env = &env;
        content.shape = def.finger;
        content.max_force = def.max_force;
        content.finger = render::settle_proxy(env, def, render::default_finger_pose(env, def));
        content.text = true;
        const int width = 1280, height = 720;  // px, the editor's default window
        const render::View view = render::default_view(content, width, height);
        const render::Theme& theme = render::dark_theme();
        render::OffscreenTarget target(ctx, width, height);
        render::DrawList list(width, height);
        render::build_frame(content, view, theme, list);
        (void)target.render(list, theme.background);  // warm-up: pipelines, page faults

        auto draw_while = [&](drivers::ServoRunner& runner) {
            while (runner.running()) {
                render::build_frame(content, view, theme, list);
                const render::Image img = target.render(list, theme.background);
                (void)img;
                ++r.frames;
            }
        };
        const auto t0 = std::chrono::steady_clock::now();
        r.beside = run_servo(core, 1000.0, r.seconds, r.scheduling, draw_while);
        const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        r.fps = s > 0.0 ? static_cast<double>(r.frames) / s : 0.0;
        r.beside_10k = run_servo(core, 10000.0, r.seconds, r.scheduling, draw_while);
    } catch (const std::exception& e) {
        r.skipped = e.what();
    }
    sched_setaffinity(0, sizeof saved, &saved);
    return r;
}

}  // namespace contactlab::bench
