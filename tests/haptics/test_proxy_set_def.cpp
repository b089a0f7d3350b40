// test_proxy_set_def.cpp — Proxy::set_def while pressing: what it keeps and what it drops.
//
// The servo hands the proxy its slewed stiffness and force clamp every tick (servo_tick.cpp).
// The c-space pieces depend only on the finger's shape and angle, so such a change must keep
// them (it used to drop them, tripling a small scene's servo tick), change nothing but the force,
// and a new pad must still rebuild them. Checked by the proxy's own work counter
// (ProxyWork::built_segments), never by timing.
#include "haptics/environment.hpp"
#include "haptics/proxy.hpp"
#include "scene_builders.hpp"

#include <doctest/doctest.h>

#include <cmath>

using namespace contactlab;
using namespace contactlab::test;

TEST_CASE("set_def: a new stiffness every tick keeps the pieces and the proxy, a new pad rebuilds them") {
    // The block (a small scene: every segment gathered) and a 2,000-chord sinusoid (the index and
    // the warm start), the finger pressed 1 mm in and sliding 2 cm at 2 cm/s.
    for (const Scene& scene : {block_scene(), scene_of({sinusoid_contour(2000, 0.01, 4.0)})}) {
        const Environment env = build_environment(scene);
        const ProxyDef def = proxy_def_of(scene);
        Proxy plain(env, def), servoed(env, def);
        const double R = scene.finger.radius;  // m
        auto surface_y = [&](double x) {
            return scene.contours[0].segments.size() > 100 ? 0.01 * std::sin(2.0 * kPi * 4.0 * (x + 0.2) / 0.4) : 0.06;
        };
        const Vec2 start{-0.03, surface_y(-0.03) + R + 0.005};
        plain.reset(start, 0.0);
        servoed.reset(start, 0.0);
        int contact = 0, plain_built = 0, servoed_built = 0;
        for (int k = 0; k < 1000; ++k) {
            const double x = -0.03 + 2e-5 * k;  // m
            const Vec2 finger{x, surface_y(x) + R - (k < 10 ? 0.0001 * k : 0.001)};
            ProxyDef d = def;
            d.stiffness = 1000.0 + (k % 7) * 50.0;  // N/m, as a slewing Ke would
            d.max_force = 1.5 - (k % 3) * 0.1;      // N
            servoed.set_def(d);
            const ProxyOutput a = plain.update(finger, 0.0);
            const ProxyOutput& b = servoed.update(finger, 0.0);
            REQUIRE(a.contact == b.contact);
            CHECK(a.proxy == b.proxy);  // the motion does not depend on Ke or the clamp
            CHECK(a.l_d == b.l_d);
            CHECK(a.work.built_segments == b.work.built_segments);
            contact += a.contact ? 1 : 0;
            plain_built += a.work.built_segments;
            servoed_built += b.work.built_segments;
        }
        CHECK(contact > 950);
        CHECK(servoed_built == plain_built);
        // Held still, a tick builds nothing: every piece is kept.
        const double x = -0.03 + 2e-5 * 1000;
        const Vec2 held{x, surface_y(x) + R - 0.001};
        ProxyDef d = def;
        d.stiffness = 700.0;
        plain.update(held, 0.0);
        servoed.update(held, 0.0);
        servoed.set_def(d);
        const int plain_held = plain.update(held, 0.0).work.built_segments;
        const int servoed_held = servoed.update(held, 0.0).work.built_segments;
        CHECK(servoed_held == plain_held);
        // (With validation on, each tick's reference run gathers more than the warm start and
        // rebuilds what the warm start's build left out: its own work, counted.)
        if constexpr (!kValidation) CHECK(servoed_held == 0);
        // A new pad radius (0.5 mm smaller: the proxy, outside, moves onto the new boundary)
        // rebuilds them, and the force follows the new stiffness. On the block's flat top the pad
        // is then 0.5 mm deep; in the sinusoid's valley (curvature radius 2.53 cm, under the
        // pad's) its sides hold the pad up, deeper.
        d.finger.radius = R - 0.0005;
        servoed.set_def(d);
        const ProxyOutput& smaller = servoed.update(held, 0.0);
        CAPTURE(smaller.depth);
        CHECK(smaller.work.built_segments > 0);
        REQUIRE(smaller.contact);
        if (env.segments.size() < 100) CHECK(std::abs(smaller.depth - 0.0005) < 1e-9);
        CHECK(glm::length(smaller.force) == doctest::Approx(std::min(700.0 * smaller.depth, d.max_force)).epsilon(1e-9));
    }
}
