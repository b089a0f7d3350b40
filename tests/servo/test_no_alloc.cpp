// Zero heap allocations per tick: the global operator new/delete (and mutex locks and writes) are
// counted in this executable (tests/common/side_effects.hpp). 100,000 ticks of the whole servo path —
// device read, ServoTick (proxy, roller PID, safety, snapshot seqlock), device write, SPSC
// record ring, simulated physics — run in contact on seed 000's block task.
#include "side_effects.hpp"
#include "sim_fixture.hpp"

#include "drivers/sim/sim_wearable_device.hpp"
#include "haptics/environment.hpp"
#include "haptics/proxy.hpp"

#include <cmath>

#include <doctest/doctest.h>

#include <pthread.h>
#include <unistd.h>

using namespace contactlab;
using namespace contactlab::test;

namespace {
struct CountedRun {
    SideEffects effects;
    long contact = 0;  // ticks whose record says contact
};
// One warm-up tick (it takes the scene, allocated off-thread; the proxy's scratch is reserved),
// then `ticks` ticks with allocations, locks and writes counted on every thread; `between(k)`
// runs after tick k, and is counted too.
template <class Between>
CountedRun run_counted(drivers::ServoLoop& loop, SpscRing<drivers::TickRecord>& ring, int ticks, Between between) {
    drivers::TickRecord r;
    loop.step(1e-3, false);
    while (ring.try_pop(r)) {}
    reset_side_effects();
    CountedRun run;
    count_all_threads(true);
    for (int k = 0; k < ticks; ++k) {
        loop.step(1e-3, false);
        while (ring.try_pop(r)) run.contact += r.contact ? 1 : 0;
        between(k);
    }
    count_all_threads(false);
    run.effects = side_effects();
    return run;
}
}  // namespace

TEST_CASE("100,000 servo ticks allocate nothing, lock nothing, write nothing") {
    // The block task repeated: descend, slide, tip over the edge, descend; loop the path so the
    // run stays in varied contact for all 100,000 ticks.
    drivers::BlockTaskParams bp;
    const drivers::HandPath one = drivers::contour_block_task(bp);
    std::vector<drivers::PathSample> samples;
    const double len = one.end() + 0.5;
    for (int rep = 0; rep * len < 101.0; ++rep)
        for (const auto& s : one.samples()) samples.push_back({s.t + rep * len, s.x, s.phi});
    SpscRing<drivers::TickRecord> ring(1024);
    Scene scene = load_shipped_scene("block.json");
    drivers::sim::SimCldDevice dev({}, drivers::HandPath(std::move(samples)));
    ServoTick servo(drivers::servo_config_for(dev, 1000.0), ServoParams{});
    servo.scenes().publish(std::make_unique<ServoScene>(scene));
    drivers::ServoLoop loop(dev, servo, 1e-3, &ring);
    REQUIRE(loop.start());
    const CountedRun run = run_counted(loop, ring, 100000, [&](int k) {
        // A parameter edit every second, as the UI would publish it (publishing is also
        // allocation-free; applying it is part of the tick).
        if (k % 1000 == 0) {
            ServoParams p;
            p.stiffness = 800.0 + (k / 1000 % 5) * 100.0;
            servo.publish_params(p);
        }
    });
    const SideEffects& e = run.effects;
    CHECK(e.allocs == 0);
    CHECK(e.frees == 0);
    CHECK(e.locks == 0);
    CHECK(e.io == 0);
    CHECK(run.contact > 50000);  // the ticks measured were mostly in contact
    CHECK(servo.snapshot().fault_count == 0);
}

TEST_CASE("20,000 servo ticks on the simulated wearable platform allocate nothing, lock nothing, write nothing") {
    // Seed 003's platform under the servo loop (drivers/servo_loop.cpp turns the contact into a
    // pose): the finger presses the block's top, tilts, and lifts, twice a second; each tick runs
    // the FSR estimation (Newton, fixed-size Eigen), the position PD and the plant's equilibrium.
    std::vector<drivers::PathSample> samples;
    for (int rep = 0; rep < 25; ++rep) {
        const double t = rep * 1.0;
        samples.push_back({t, Vec2{-0.05, 0.030}, 0.0});
        samples.push_back({t + 0.2, Vec2{-0.05, 0.0248}, 0.0});
        samples.push_back({t + 0.5, Vec2{-0.05, 0.0248}, 0.15});
        samples.push_back({t + 0.8, Vec2{-0.05, 0.030}, 0.0});
    }
    SpscRing<drivers::TickRecord> ring(1024);
    Scene scene = load_shipped_scene("block.json");
    drivers::sim::SimWearableDevice dev({}, drivers::HandPath(std::move(samples)));
    ServoTick servo(drivers::servo_config_for(dev, 1000.0), ServoParams{});
    servo.scenes().publish(std::make_unique<ServoScene>(scene));
    drivers::ServoLoop loop(dev, servo, 1e-3, &ring);
    REQUIRE(loop.start());
    const CountedRun run = run_counted(loop, ring, 20000, [](int) {});
    const SideEffects& e = run.effects;
    CHECK(e.allocs == 0);
    CHECK(e.frees == 0);
    CHECK(e.locks == 0);
    CHECK(e.io == 0);
    CHECK(run.contact > 5000);
    CHECK(dev.state() != drivers::DeviceState::fault);
}

TEST_CASE("the proxy's worst ticks on 100,000 segments allocate nothing: a press from 5 cm above, a slide over the valleys, hovering with spread anticipation, a scene edit") {
    // The scratch is reserved when the proxy is made, off the servo thread (Proxy::Proxy), for
    // the largest ticks the bench measures on this contour: the peer workload's sinusoid (0.4 m,
    // 1 cm amplitude, 10 cm wavelength) of 100,000 segments.
    Scene scene;
    Contour c;
    auto at = [](double x) { return Vec2{x, 0.01 * std::sin(2.0 * kPi * x / 0.1)}; };
    const int n = 100000;
    for (int i = 0; i < n; ++i) c.segments.push_back(LineSegment{at(0.4 * i / n), at(0.4 * (i + 1) / n)});
    scene.contours.push_back(c);
    scene.anticipation.segments_per_tick = 256;
    const Environment env = build_environment(scene);
    const ProxyDef def = proxy_def_of(scene);
    Proxy proxy(env, def), edited(env, def);
    const double R = def.finger.radius;
    auto pressed = [&](double x, double depth) {  // the finger `depth` (m) into the contour at x
        const double slope = 0.01 * 2.0 * kPi / 0.1 * std::cos(2.0 * kPi * x / 0.1);
        const Vec2 normal = Vec2{-slope, 1.0} / std::sqrt(1.0 + slope * slope);
        return at(x) + (R - depth) * normal;
    };
    reset_side_effects();
    count_this_thread(true);
    long contact = 0, free = 0;
    proxy.reset(pressed(0.0867, 0.001) + Vec2{0.0, 0.05}, 0.0);
    for (int k = 0; k < 4000; ++k) contact += proxy.update(pressed(0.0867 + 0.2 * k / 4000.0, 0.001), 0.0).contact ? 1 : 0;
    edited.place(proxy.output().proxy, 0.0, 0.002);
    edited.carry_motion(proxy.output());
    for (int k = 0; k < 4000; ++k) free += edited.update(pressed(0.2867 - 0.2 * k / 4000.0, -0.01), 0.0).contact ? 0 : 1;
    count_this_thread(false);
    const SideEffects e = side_effects();
    CHECK(contact > 3900);
    CHECK(free > 3900);
    CHECK(e.allocs == 0);
    CHECK(e.frees == 0);
}
