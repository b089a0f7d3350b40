// bench_render.cpp — offscreen frame time at 1280x720 for scenes of 10, 1 000 and 100 000 line
// segments (a sinusoidal terrain 0.5 m long, the finger pressing it, c-space overlay off).
//
//   BM_DrawList/N  CPU only: scene -> draw list (flattening, strokes, fills, finger)
//   BM_Frame/N     the whole frame: draw list, upload, record, submit, wait, read back 1280x720
//
// Device: a GPU if there is one; --software forces lavapipe. Run:
//   build/tests/render/bench_render [--software] --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
#include "engine/render/context.hpp"
#include "engine/render/finger_state.hpp"
#include "engine/render/frame.hpp"
#include "engine/render/offscreen.hpp"

#include <benchmark/benchmark.h>

#include <cmath>
#include <cstring>
#include <map>
#include <memory>
#include <vector>

using namespace contactlab;
using namespace contactlab::render;

namespace {

bool g_software = false;
constexpr int kWidth = 1280, kHeight = 720;

// A terrain chain of n line segments over x in [-0.25, 0.25] m, 5 mm amplitude.
Scene terrain_scene(int n) {
    Scene s;
    Contour c;
    auto y = [](double x) { return 0.005 * std::sin(60.0 * x) + 0.002 * std::sin(370.0 * x); };
    for (int i = 0; i < n; ++i) {
        const double x0 = -0.25 + 0.5 * i / n, x1 = -0.25 + 0.5 * (i + 1) / n;
        c.segments.push_back(LineSegment{{x0, y(x0)}, {x1, y(x1)}});
    }
    s.contours.push_back(std::move(c));
    return s;
}

struct Fixture {
    Scene scene;
    Environment env;
    FrameContent content;
    View view;
    explicit Fixture(int n) : scene(terrain_scene(n)), env(build_environment(scene)) {
        const ProxyDef def = proxy_def_of(scene);
        content.scene = &scene;
        content.env = &env;
        content.shape = def.finger;
        content.max_force = def.max_force;
        content.finger = settle_proxy(env, def, FingerPose{{0.0, def.finger.radius + 0.004}, 0.0});
        view = default_view(content, kWidth, kHeight);
    }
};

Fixture& fixture(int n) {
    static std::map<int, std::unique_ptr<Fixture>> cache;
    auto& f = cache[n];
    if (!f) f = std::make_unique<Fixture>(n);
    return *f;
}

const VulkanContext& context() {
    static const VulkanContext ctx(ContextOptions{.software = g_software, .validation = false});
    return ctx;
}

void BM_DrawList(benchmark::State& state) {
    Fixture& f = fixture(static_cast<int>(state.range(0)));
    DrawList list(kWidth, kHeight);
    for (auto _ : state) {
        build_frame(f.content, f.view, dark_theme(), list);
        benchmark::DoNotOptimize(list.indices().data());
    }
    state.counters["triangles"] = static_cast<double>(list.indices().size() / 3);
}

void BM_Frame(benchmark::State& state) {
    Fixture& f = fixture(static_cast<int>(state.range(0)));
    OffscreenTarget target(context(), kWidth, kHeight);
    DrawList list(kWidth, kHeight);
    for (auto _ : state) {
        build_frame(f.content, f.view, dark_theme(), list);
        Image img = target.render(list, dark_theme().background);
        benchmark::DoNotOptimize(img.rgba.data());
    }
    state.SetLabel(context().device_name());
}

BENCHMARK(BM_DrawList)->Arg(10)->Arg(1000)->Arg(100000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Frame)->Arg(10)->Arg(1000)->Arg(100000)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

int main(int argc, char** argv) {
    std::vector<char*> args;
    for (int i = 0; i < argc; ++i) {
        if (std::strcmp(argv[i], "--software") == 0) g_software = true;
        else args.push_back(argv[i]);
    }
    int n = static_cast<int>(args.size());
    benchmark::Initialize(&n, args.data());
    if (benchmark::ReportUnrecognizedArguments(n, args.data())) return 1;
    benchmark::RunSpecifiedBenchmarks();
    benchmark::Shutdown();
    return 0;
}
