// test_validation.cpp — the validation switch (haptics/validation.hpp) checks what it claims.
//
// With CONTACTLAB_VALIDATION on (scripts/test's sanitizer build) every proxy tick is also moved
// the slow way and the shortcuts are held to it, anticipation is held to a search of every
// segment, and a scene's index is checked when it is built. Off (the product), nothing runs.
// These tests see, in either build, that the switch does exactly that: a failed check reaches the
// handler only when on, a stroke over a dense contour runs the checks every tick (and none fail)
// only when on, and the index's own consistency check catches a tree that does not bound its
// items.
#include "haptics/aabb_tree.hpp"
#include "haptics/environment.hpp"
#include "haptics/proxy.hpp"
#include "haptics/validation.hpp"
#include "scene_builders.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <string>

using namespace contactlab;
using namespace contactlab::test;

namespace {

// What the handler under test saw (one test at a time: doctest runs cases in sequence).
int g_failures = 0;
std::string g_what;
std::string g_file;
void record_failure(const char* what, const char* file, int) {
    ++g_failures;
    g_what = what;
    g_file = file;
}

// Installs record_failure for one scope, and puts the previous handler back.
struct RecordingHandler {
    ValidationHandler previous;
    RecordingHandler() : previous(set_validation_handler(&record_failure)) {
        g_failures = 0;
        g_what.clear();
        g_file.clear();
    }
    ~RecordingHandler() { set_validation_handler(previous); }
};

}  // namespace

TEST_CASE("validation: a failed check reaches the handler when the switch is on, and costs nothing when off") {
    RecordingHandler handler;
    const long long before = validation_checks();
    CONTACTLAB_VALIDATE(1 + 1 == 3, "a deliberately false invariant");
    if constexpr (kValidation) {
        CHECK(g_failures == 1);
        CHECK(g_what == "a deliberately false invariant");
        CHECK(g_file.find("test_validation.cpp") != std::string::npos);
        CHECK(validation_checks() == before + 1);
    } else {
        CHECK(g_failures == 0);
        CHECK(validation_checks() == before);
    }
}

TEST_CASE("validation: a stroke over a dense contour checks the proxy's shortcuts every tick, and none fail") {
    // 2,000 chords of 0.2 mm on 0.4 m (few enough for anticipation's every-segment check): hover
    // 5 mm above for 200 ticks (anticipation), press 1 mm in, and slide 10 cm in 2,000 ticks
    // (5 cm/s at 1 kHz: the warm start and the walk's local scans, its first move's and the chain
    // walk's among them, on nearly every tick).
    RecordingHandler handler;
    const long long before_scene = validation_checks();
    const Scene scene = scene_of({sinusoid_contour(2000, 0.01, 4.0)});
    const Environment env = build_environment(scene);
    const long long scene_checks = validation_checks() - before_scene;

    Proxy proxy(env, proxy_def_of(scene));
    const double R = scene.finger.radius;  // m
    auto surface_y = [](double x) { return 0.01 * std::sin(2.0 * kPi * 4.0 * (x + 0.2) / 0.4); };
    const long long before = validation_checks();
    int anticipating = 0, warm = 0, contact = 0, near_start = 0, chain_scans = 0, full_scans = 0;
    for (int k = 0; k < 200; ++k) {
        const double x = -0.05 + 1e-5 * k;  // m
        anticipating += proxy.update({x, surface_y(x) + R + 0.005}, 0.0).anticipating ? 1 : 0;
    }
    for (int k = 0; k < 2000; ++k) {
        const double x = -0.05 + 5e-5 * k;  // m
        const ProxyOutput& out = proxy.update({x, surface_y(x) + R - 0.001}, 0.0);
        contact += out.contact ? 1 : 0;
        warm += out.work.warm_start ? 1 : 0;
        near_start += out.work.near_start ? 1 : 0;
        chain_scans += out.work.chain_scans;
        full_scans += out.work.full_scans;
    }
    const long long checks = validation_checks() - before;
    CHECK(anticipating == 200);
    CHECK(contact > 1900);
    CHECK(warm > 1500);  // the warm start was taken, so it was checked
    CHECK(near_start > 1500);  // ... and the walk's first move answered near the proxy
    CAPTURE(chain_scans);
    CAPTURE(full_scans);
    CHECK(chain_scans > full_scans);  // ... and most of its scans from a neighbourhood kept
    CHECK(g_failures == 0);
    CAPTURE(g_what);
    if constexpr (kValidation) {
        CHECK(scene_checks >= 2);  // the index's consistency and its offset boxes
        // Per tick: the reference proxy, finite, step caps, outputs, contact count; and
        // anticipation's every-segment search on each hovering tick.
        CHECK(checks >= 5 * 2200 + 200);
    } else {
        CHECK(scene_checks == 0);
        CHECK(checks == 0);
    }
}

TEST_CASE("validation: the index's consistency check catches a tree that does not bound its items") {
    // A row of unit boxes; the tree built on them is consistent with them, and not with the same
    // boxes after one moved far away (no node bounds it) or one went missing.
    std::vector<Aabb> boxes;
    std::vector<NormalCone> normals;
    std::vector<OffsetBoxes> offsets;
    for (int i = 0; i < 64; ++i) {
        Aabb b;
        b.grow(Vec2{1.0 * i, 0.0});
        b.grow(Vec2{1.0 * i + 1.0, 1.0});
        boxes.push_back(b);
        normals.push_back({0.5 * kPi, 0.0});
        offsets.push_back({b.grown(0.1), b.grown(0.1)});
    }
    const AabbTree plain(boxes);
    const AabbTree full(boxes, normals, offsets, 0.1);
    CHECK(plain.consistent(boxes));
    CHECK(full.consistent(boxes));
    std::vector<Aabb> moved = boxes;
    moved[37] = moved[37].grown(0.0);
    moved[37].lo += Vec2{0.0, 50.0};
    moved[37].hi += Vec2{0.0, 50.0};
    CHECK_FALSE(plain.consistent(moved));
    CHECK_FALSE(full.consistent(moved));
    std::vector<Aabb> fewer(boxes.begin(), boxes.end() - 1);
    CHECK_FALSE(plain.consistent(fewer));
}
