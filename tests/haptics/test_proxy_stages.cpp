// test_proxy_stages.cpp — ProxyDef::profile: a tick's named stages (proxy.hpp, ProxyStages).
//
// No speed is asserted (the machines are shared; figures live in `contactlab bench`). What is
// checked is that the measurement means what it says: profiling changes no output, a proxy that
// does not profile reads no clock (every stage exactly 0), the stages are disjoint parts of the
// update (their sum never exceeds the update's own wall time, read around it), and each stage is
// charged where its work happens (anticipation only in free space, contacts and the walk only in
// contact).
#include "haptics/environment.hpp"
#include "haptics/proxy.hpp"
#include "scene_builders.hpp"

#include <doctest/doctest.h>

#include <chrono>
#include <cmath>

using namespace contactlab;
using namespace contactlab::test;

TEST_CASE("profile: stages are timed only when asked, change nothing, and fit inside the tick") {
    // 2,000 chords on a 0.4 m sinusoid; hover 5 mm above for 200 ticks, then press 1 mm in and
    // slide 10 cm in 2,000 ticks (5 cm/s at 1 kHz), the finger rocking by 0.1 rad.
    const Scene scene = scene_of({sinusoid_contour(2000, 0.01, 4.0)});
    const Environment env = build_environment(scene);
    ProxyDef plain_def = proxy_def_of(scene);
    ProxyDef profiled_def = plain_def;
    profiled_def.profile = true;
    Proxy plain(env, plain_def), profiled(env, profiled_def);
    const double R = scene.finger.radius;  // m
    auto surface_y = [](double x) { return 0.01 * std::sin(2.0 * kPi * 4.0 * (x + 0.2) / 0.4); };

    ProxyStages free_sum, contact_sum;
    int free_ticks = 0, contact_ticks = 0, over_wall = 0;
    double plain_nonzero = 0.0;
    for (int k = 0; k < 2200; ++k) {
        const bool hover = k < 200;
        const double x = -0.05 + (hover ? 1e-5 * k : 2e-3 + 5e-5 * (k - 200));  // m
        const Vec2 finger{x, surface_y(x) + R + (hover ? 0.005 : -0.001)};
        const double phi = 0.1 * std::sin(k * 0.01);  // rad
        const ProxyOutput a = plain.update(finger, phi);
        const auto t0 = std::chrono::steady_clock::now();
        const ProxyOutput& b = profiled.update(finger, phi);
        const auto t1 = std::chrono::steady_clock::now();
        const double wall = std::chrono::duration<double, std::nano>(t1 - t0).count();  // ns
        // Profiling is a measurement: the same proxy, force and l_d, bit for bit.
        REQUIRE(a.contact == b.contact);
        CHECK(a.proxy == b.proxy);
        CHECK(a.force == b.force);
        CHECK(a.l_d == b.l_d);
        plain_nonzero += a.stages.total();
        // Consecutive laps of one clock inside the update: their sum is at most its wall time.
        over_wall += b.stages.total() > wall ? 1 : 0;
        ProxyStages& sum = b.contact ? contact_sum : free_sum;
        (b.contact ? contact_ticks : free_ticks) += 1;
        sum += b.stages;
    }
    CHECK(free_ticks == 200);
    CHECK(contact_ticks == 2000);
    CHECK(plain_nonzero == 0.0);  // off: no clock read, nothing charged
    CHECK(over_wall == 0);
    // Free space: the motion's stages run (the proxy follows the finger), anticipation is charged,
    // and no contact work is.
    CHECK(free_sum.anticipate > 0.0);
    CHECK(free_sum.contact == 0.0);
    // Contact: every motion stage and the contact stage are charged, anticipation never.
    CHECK(contact_sum.gather > 0.0);
    CHECK(contact_sum.pieces > 0.0);
    CHECK(contact_sum.walk > 0.0);
    CHECK(contact_sum.contact > 0.0);
    CHECK(contact_sum.anticipate == 0.0);
}
