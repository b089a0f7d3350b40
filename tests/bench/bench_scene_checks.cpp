// bench_scene_checks.cpp — cost of the checks a scene passes before the servo may use it
// (scene_io's validate_scene and its crossing search, contour_crossing.hpp), on a closed contour
// of 1,000 to 100,000 line segments.
//
// The contour is the bench's 0.4 m sinusoid (1 cm amplitude, 4 periods) in n - 3 chords, closed by
// a box 5 cm below; "found" raises the box's bottom through the sinusoid, so the search stops at
// the first chord the raised side crosses, near the contour's start. A user feels
// this cost once, when a scene is opened or an edit is applied: the crossing search is a tree of
// boxes, O(n log n), where testing all pairs took minutes at 100,000 segments.
#include "haptics/contour_crossing.hpp"
#include "haptics/scene.hpp"
#include "haptics/scene_io.hpp"

#include <benchmark/benchmark.h>

#include <cmath>
#include <vector>

namespace {

using namespace contactlab;

LineSegment line(Vec2 a, Vec2 b) { return LineSegment{a, b}; }

// n line segments closed (see the file's comment); `found` makes it cross itself.
Scene closed_sinusoid(int n, bool found) {
    constexpr double kWidth = 0.4, kAmplitude = 0.01, kPeriods = 4.0;  // m, m, -
    Contour c;
    const int chords = n - 3;
    auto at = [&](int i) {
        const double x = -0.5 * kWidth + kWidth * i / chords;
        return Vec2{x, kAmplitude * std::sin(2.0 * kPi * kPeriods * (x + 0.5 * kWidth) / kWidth)};
    };
    for (int i = 0; i < chords; ++i) c.segments.push_back(line(at(i), at(i + 1)));
    const Vec2 start = at(0), end = at(chords);
    const double bottom = found ? -0.005 : -0.05;  // m: -5 mm lies inside the sinusoid's swing
    c.segments.push_back(line(end, {end.x, bottom}));
    c.segments.push_back(line({end.x, bottom}, {start.x, bottom}));
    c.segments.push_back(line({start.x, bottom}, start));
    c.closed = true;
    Scene scene;
    scene.contours.push_back(c);
    return scene;
}

void BM_ContourCrossing(benchmark::State& state) {
    const Scene scene = closed_sinusoid(static_cast<int>(state.range(0)), state.range(1) != 0);
    for (auto _ : state) {
        auto crossing = find_contour_crossing(scene.contours);
        benchmark::DoNotOptimize(crossing);
    }
    state.SetLabel(state.range(1) != 0 ? "crossing found" : "no crossing");
}
BENCHMARK(BM_ContourCrossing)
    ->ArgsProduct({{1000, 10000, 100000}, {0, 1}})
    ->Unit(benchmark::kMillisecond);

// Everything scene_io checks before a scene is used, the crossing search included.
void BM_ValidateScene(benchmark::State& state) {
    const Scene scene = closed_sinusoid(static_cast<int>(state.range(0)), false);
    for (auto _ : state) validate_scene(scene);
}
BENCHMARK(BM_ValidateScene)->Arg(1000)->Arg(100000)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
