// bench_proxy.cpp — cost of one proxy tick (Proxy::update) against scenes of 10, 1,000 and
// 100,000 line segments.
//
// The scene is a terrain of N segments, each 5 mm wide, with a height profile of two sinusoids
// (amplitude 8 mm), so longer scenes add content, not density: with a working spatial index the
// tick cost stays flat as N grows. The finger slides along the middle of the terrain at 1 mm per
// tick pressing ~1 mm in, with a swinging finger angle, so most ticks are in contact and many
// cross vertices. One benchmark iteration = one tick; the path is precomputed.
#include "haptics/environment.hpp"
#include "haptics/proxy.hpp"
#include "haptics/servo_scene.hpp"
#include "haptics/servo_tick.hpp"
#include "haptics/stimuli.hpp"

#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

namespace {

using namespace contactlab;

constexpr double kSegmentWidth = 0.005;  // m

double terrain_height(double x) { return 0.005 * std::sin(60.0 * x) + 0.003 * std::sin(170.0 * x + 1.0); }

Scene terrain_scene(int segments) {
    Scene scene;
    Contour c;
    for (int i = 0; i < segments; ++i) {
        const double x0 = i * kSegmentWidth, x1 = (i + 1) * kSegmentWidth;
        c.segments.push_back(LineSegment{{x0, terrain_height(x0)}, {x1, terrain_height(x1)}});
    }
    scene.contours.push_back(c);
    return scene;
}

struct Sample {
    Vec2 x;
    double phi;
};

// 4000 ticks along the middle of the terrain, as in a slow contour-following stroke.
std::vector<Sample> stroke(int segments) {
    const double mid = 0.5 * segments * kSegmentWidth;
    const double span = std::min(2.0, 0.4 * segments * kSegmentWidth);  // m travelled
    std::vector<Sample> path;
    const int n = 4000;
    for (int k = 0; k < n; ++k) {
        const double x = mid - 0.5 * span + span * k / n;
        const double phi = 0.3 * std::sin(7.0 * x);
        path.push_back({{x, terrain_height(x) + 0.026 - 0.001}, phi});
    }
    return path;
}

void BM_ProxyTick(benchmark::State& state) {
    const int segments = static_cast<int>(state.range(0));
    const Scene scene = terrain_scene(segments);
    const Environment env = build_environment(scene);
    Proxy proxy(env, ProxyDef{});
    const auto path = stroke(segments);
    proxy.reset(path[0].x + Vec2{0.0, 0.05}, path[0].phi);
    std::size_t k = 0, contacts = 0, ticks = 0;
    for (auto _ : state) {
        const Sample& s = path[k];
        const ProxyOutput& o = proxy.update(s.x, s.phi);
        benchmark::DoNotOptimize(o.force);
        contacts += o.contact ? 1 : 0;
        ++ticks;
        if (++k == path.size()) {  // back to the start from above, as a user lifting the finger
            k = 0;
            proxy.reset(path[0].x + Vec2{0.0, 0.05}, path[0].phi);
        }
    }
    state.counters["contact_fraction"] = ticks ? static_cast<double>(contacts) / ticks : 0.0;
    state.SetLabel(std::to_string(segments) + " line segments");
}
BENCHMARK(BM_ProxyTick)->Arg(10)->Arg(1000)->Arg(100000);

// Density: the same 0.4 m sinusoid (amplitude 1 cm, wavelength 10 cm) refined into N line
// segments, so at N = 100,000 thousands of 4 um segments lie under the pad. The finger slides
// 1 mm deep along the curve's normal, pad facing down, over the middle 0.2 m in the second
// argument's number of ticks.
double dense_height(double x) { return 0.01 * std::sin(2.0 * 3.141592653589793 * x / 0.1); }
double dense_slope(double x) { return 0.01 * 2.0 * 3.141592653589793 / 0.1 * std::cos(2.0 * 3.141592653589793 * x / 0.1); }

// The sinusoid over 0.4 m in `segments` lines.
Scene dense_scene(int segments) {
    Scene scene;
    Contour c;
    for (int i = 0; i < segments; ++i) {
        const double x0 = 0.4 * i / segments, x1 = 0.4 * (i + 1) / segments;
        c.segments.push_back(LineSegment{{x0, dense_height(x0)}, {x1, dense_height(x1)}});
    }
    scene.contours.push_back(c);
    return scene;
}

// The finger centre 1 mm deep (R = 2.6 cm) along the profile's normal over its middle 0.2 m, in
// `ticks` samples.
std::vector<Vec2> dense_stroke(int ticks) {
    std::vector<Vec2> path;
    for (int k = 0; k < ticks; ++k) {
        const double x = 0.1 + 0.2 * k / ticks;
        const Vec2 n = glm::normalize(Vec2{-dense_slope(x), 1.0});
        path.push_back(Vec2{x, dense_height(x)} + (0.026 - 0.001) * n);
    }
    return path;
}

void BM_ProxyTickDense(benchmark::State& state) {
    const int segments = static_cast<int>(state.range(0));
    const Environment env = build_environment(dense_scene(segments));
    Proxy proxy(env, ProxyDef{});
    const int stroke_ticks = static_cast<int>(state.range(1));  // over the 0.2 m stroke
    const std::vector<Vec2> path = dense_stroke(stroke_ticks);
    proxy.reset(path[0] + Vec2{0.0, 0.05}, 0.0);
    std::size_t k = 0;
    double kept = 0.0, near = 0.0, chain = 0.0, full = 0.0, warm = 0.0, gathered = 0.0, pieces = 0.0, steps = 0.0, ticks = 0.0;
    for (auto _ : state) {
        const ProxyOutput& out = proxy.update(path[k], 0.0);
        benchmark::DoNotOptimize(out.force);
        warm += out.work.warm_start;
        kept += out.work.kept_gather;
        near += out.work.near_start;
        chain += out.work.chain_scans;
        full += out.work.full_scans;
        gathered += out.work.segments;
        pieces += out.work.pieces;
        steps += out.work.walk_steps;
        ticks += 1.0;
        if (++k == path.size()) {
            k = 0;
            proxy.reset(path[0] + Vec2{0.0, 0.05}, 0.0);
        }
    }
    // The work behind the time: how often the warm-start gather sufficed, and what a tick built.
    state.counters["warm"] = warm / ticks;
    state.counters["kept"] = kept / ticks;
    state.counters["near"] = near / ticks;
    state.counters["chain"] = chain / ticks;  // the walk's scans answered from a kept neighbourhood
    state.counters["full"] = full / ticks;    // ... and those that asked every piece's box
    state.counters["segs"] = gathered / ticks;
    state.counters["pieces"] = pieces / ticks;
    state.counters["steps"] = steps / ticks;
    state.SetLabel(std::to_string(segments) + " segments on 0.4 m, " + std::to_string(200000 / stroke_ticks) + " um per tick");
}
// 4000 ticks: 5 cm/s at 1 kHz; 1000 ticks: 20 cm/s, the stroke `contactlab bench` times.
BENCHMARK(BM_ProxyTickDense)
    ->Args({10, 4000})->Args({100, 4000})->Args({1000, 4000})->Args({10000, 4000})->Args({100000, 4000})
    ->Args({10, 1000})->Args({100000, 1000});

// The same stroke through the whole servo tick (ServoTick: parameter slew, proxy, safety, roller
// PID, snapshot), as the live loop runs it at 1 kHz: what a user's servo spends, next to the
// proxy's own cost above. (The servo hands the proxy its slewed Ke every tick; that used to drop
// the proxy's pieces each time.)
void BM_ServoTickDense(benchmark::State& state) {
    const int segments = static_cast<int>(state.range(0));
    ServoTick servo(ServoConfig{}, ServoParams{});
    servo.scenes().publish(std::make_unique<ServoScene>(dense_scene(segments)));
    const std::vector<Vec2> path = dense_stroke(4000);  // 5 cm/s
    ServoInput in;
    in.finger = path[0] + Vec2{0.0, 0.05};
    servo.connect(0.0);
    for (int k = 0; k < 300; ++k) {  // engage in free space, then past the force ramp-in
        in.t += 1e-3;
        if (k == 10) in.finger = path[0];
        servo.tick(in);
    }
    std::size_t k = 0;
    double contact = 0.0, ticks = 0.0;
    for (auto _ : state) {
        in.t += 1e-3;
        in.finger = path[k];
        const ServoCommand& cmd = servo.tick(in);
        benchmark::DoNotOptimize(cmd.force);
        contact += servo.proxy_output().contact ? 1.0 : 0.0;
        ticks += 1.0;
        if (++k == path.size()) {
            // Lift, move back over the start and press again, untimed (as BM_ProxyTickDense's
            // reset: sliding 0.2 m back in one tick would cost a long walk once per stroke).
            state.PauseTiming();
            k = 0;
            for (const Vec2 at : {path.back() + Vec2{0.0, 0.05}, path[0] + Vec2{0.0, 0.05}, path[0]}) {
                in.t += 1e-3;
                in.finger = at;
                servo.tick(in);
            }
            state.ResumeTiming();
        }
    }
    state.counters["contact"] = contact / ticks;
    state.counters["engaged"] = servo.state() == ServoState::engaged ? 1.0 : 0.0;
    state.SetLabel(std::to_string(segments) + " segments on 0.4 m, whole servo tick, 50 um per tick");
}
BENCHMARK(BM_ServoTickDense)->Arg(10)->Arg(1000)->Arg(100000);

// Curves: a generated seed 002 stimulus (seed 1: 2 small bumps, 1 large, 89 quads + 2 lines),
// traced left to right 1 mm under its envelope at 0.035 mm per tick, in exact mode and flattened
// at 1e-4 and 1e-5 m. Counters `err_*_um`: the distance (micrometres) of the mode's proxy from
// exact mode's over the stroke (the accuracy the speed buys); `depth_err_*_um`: the same for the
// penetration depth, i.e. the force error divided by Ke.
struct BumpsStroke {
    GeneratedScene g = generate_bumps(BumpsDef{});
    std::vector<Sample> path;
    std::vector<Vec2> exact_proxy;
    std::vector<double> exact_depth;  // m
    BumpsStroke() {
        const auto& env = g.envelope;
        std::size_t j = 0;
        for (double x = 0.005; x <= 0.175; x += 3.5e-5) {
            while (j + 2 < env.size() && env[j + 1].x < x) ++j;
            const double t = (x - env[j].x) / (env[j + 1].x - env[j].x);
            path.push_back({{x, env[j].y + t * (env[j + 1].y - env[j].y) + 0.026 - 0.001}, 0.0});
        }
        const Environment e = build_environment(g.scene);
        Proxy p(e, ProxyDef{});
        p.reset(path[0].x + Vec2{0.0, 0.05}, 0.0);
        for (const Sample& s : path) {
            const ProxyOutput& o = p.update(s.x, s.phi);
            exact_proxy.push_back(o.proxy);
            exact_depth.push_back(o.depth);
        }
    }
};

void BM_ProxyTickBumps(benchmark::State& state) {
    static const BumpsStroke stroke;
    Scene scene = stroke.g.scene;
    const int mode = static_cast<int>(state.range(0));
    if (mode > 0) scene.curves = {CurveMode::flatten, mode == 1 ? 1e-4 : 1e-5};
    const Environment env = build_environment(scene);
    Proxy proxy(env, ProxyDef{});
    std::vector<double> err;        // proxy position, m
    std::vector<double> depth_err;  // penetration depth (so force / Ke), m
    proxy.reset(stroke.path[0].x + Vec2{0.0, 0.05}, 0.0);
    for (std::size_t k = 0; k < stroke.path.size(); ++k) {
        const ProxyOutput& o = proxy.update(stroke.path[k].x, 0.0);
        err.push_back(glm::length(o.proxy - stroke.exact_proxy[k]));
        depth_err.push_back(std::abs(o.depth - stroke.exact_depth[k]));
    }
    std::sort(err.begin(), err.end());
    std::sort(depth_err.begin(), depth_err.end());
    std::size_t k = 0;
    proxy.reset(stroke.path[0].x + Vec2{0.0, 0.05}, 0.0);
    for (auto _ : state) {
        benchmark::DoNotOptimize(proxy.update(stroke.path[k].x, 0.0).force);
        if (++k == stroke.path.size()) {
            k = 0;
            proxy.reset(stroke.path[0].x + Vec2{0.0, 0.05}, 0.0);
        }
    }
    // Median and 99th percentile describe the mode; the maximum is dominated by the tick or two
    // where the contact leaves the pad's end and the proxy jumps, which the modes reach a tick apart.
    state.counters["err_p50_um"] = 1e6 * err[err.size() / 2];
    state.counters["err_p99_um"] = 1e6 * err[err.size() * 99 / 100];
    state.counters["err_max_um"] = 1e6 * err.back();
    state.counters["depth_err_p99_um"] = 1e6 * depth_err[depth_err.size() * 99 / 100];
    state.counters["depth_err_max_um"] = 1e6 * depth_err.back();
    state.counters["env_segments"] = static_cast<double>(env.segments.size());
    state.SetLabel(mode == 0 ? "exact" : mode == 1 ? "flatten 1e-4 m" : "flatten 1e-5 m");
}
BENCHMARK(BM_ProxyTickBumps)->Arg(0)->Arg(1)->Arg(2);

}  // namespace

BENCHMARK_MAIN();
