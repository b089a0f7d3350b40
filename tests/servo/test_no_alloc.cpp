// Zero heap allocations per tick: the global operator new/delete (and mutex locks and writes) are
// counted in this executable (tests/common/side_effects.hpp). 100,000 ticks of the whole servo path —
// device read, ServoTick (proxy, roller PID, safety, snapshot seqlock), device write, SPSC
// record ring, simulated physics — run in contact on seed 000's block task.
#include "side_effects.hpp"
#include "sim_fixture.hpp"

#include <doctest/doctest.h>

#include <pthread.h>
#include <unistd.h>

using namespace contactlab;
using namespace contactlab::test;

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
    drivers::TickRecord r;
    // Warm-up tick takes the scene (allocated off-thread above); the proxy's scratch is reserved.
    loop.step(1e-3, false);
    while (ring.try_pop(r)) {}

    reset_side_effects();
    long contact = 0;
    count_all_threads(true);
    for (int k = 0; k < 100000; ++k) {
        loop.step(1e-3, false);
        while (ring.try_pop(r)) contact += r.contact ? 1 : 0;
        // A parameter edit every second, as the UI would publish it (publishing is also
        // allocation-free; applying it is part of the tick).
        if (k % 1000 == 0) {
            ServoParams p;
            p.stiffness = 800.0 + (k / 1000 % 5) * 100.0;
            servo.publish_params(p);
        }
    }
    count_all_threads(false);
    const SideEffects e = side_effects();
    CHECK(e.allocs == 0);
    CHECK(e.frees == 0);
    CHECK(e.locks == 0);
    CHECK(e.io == 0);
    CHECK(contact > 50000);  // the ticks measured were mostly in contact
    CHECK(servo.snapshot().fault_count == 0);
}
