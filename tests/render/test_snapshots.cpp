// test_snapshots.cpp — golden images (320x180) of every shipped scene, each overlay, both themes
// and a pose in contact. Exact comparison on lavapipe (snapshot.hpp for tolerance and updating).
#include "render_fixture.hpp"
#include "snapshot.hpp"

#include <doctest/doctest.h>

using namespace render_test;

namespace {

void check_scenes(const std::string& suffix, const RenderRequest& base) {
    const auto scenes = shipped_scenes();
    REQUIRE(scenes.size() >= 5);
    for (const std::string& file : scenes) {
        const std::string name = file.substr(0, file.size() - 5) + suffix;
        CAPTURE(name);
        RenderRequest req = base;
        req.width = kGoldenWidth;
        req.height = kGoldenHeight;
        const RenderResult r = render_scene(lavapipe(), load_scene(file), req);
        const SnapshotResult s = check_snapshot(name, r.image);
        INFO(s.message);
        CHECK(s.ok);
    }
    CHECK(lavapipe().validation_messages() == 0);
}

}  // namespace

TEST_CASE("snapshot: every shipped scene, default finger, dark theme") { check_scenes("", RenderRequest{}); }

TEST_CASE("snapshot: every shipped scene with the c-space overlay") {
    RenderRequest req;
    req.overlays.cspace = true;
    check_scenes("_cspace", req);
}

TEST_CASE("snapshot: every shipped scene with the anticipation zones overlay") {
    RenderRequest req;
    req.overlays.zones = true;
    check_scenes("_zones", req);
}

TEST_CASE("snapshot: light theme, tilted finger pressing the block's edge, both overlays") {
    RenderRequest req;
    req.width = kGoldenWidth;
    req.height = kGoldenHeight;
    req.theme = light_theme();
    req.finger = FingerPose{{0.005, 0.022}, -0.3};
    req.overlays = {true, true};
    const RenderResult r = render_scene(lavapipe(), load_scene("block.json"), req);
    CHECK(r.proxy.contact);
    const SnapshotResult s = check_snapshot("block_edge_light", r.image);
    INFO(s.message);
    CHECK(s.ok);
    CHECK(lavapipe().validation_messages() == 0);
}

TEST_CASE("snapshot: seed 003's wearable platform under a finger tilted on the flat floor") {
    RenderRequest req;
    req.width = kGoldenWidth;
    req.height = kGoldenHeight;
    req.finger = FingerPose{{0.0, 0.0245}, 0.2};  // 1.5 mm into the floor, tilted 0.2 rad
    req.wearable = true;
    const RenderResult r = render_scene(lavapipe(), load_scene("flat.json"), req);
    CHECK(r.proxy.contact);
    const SnapshotResult s = check_snapshot("flat_wearable", r.image);
    INFO(s.message);
    CHECK(s.ok);
    CHECK(lavapipe().validation_messages() == 0);
}
