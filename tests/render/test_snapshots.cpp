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

TEST_CASE("snapshot: the wearable picture at 1280x720: zoomed on the fingertip, cables in their colour, key and contact frame") {
    // Issue 29: the platform used to be a bar a few pixels tall in the force arrow's red. Here the
    // view frames the fingertip, so the 14 mm platform spans well over 100 px; the cables and
    // their tension arrows are drawn in theme.cable, the key names both colours, the contact frame
    // is labelled (text on: stb_easy_font is deterministic).
    RenderRequest req;
    req.width = 1280;
    req.height = 720;
    req.finger = FingerPose{{0.0, 0.0245}, 0.2};  // 1.5 mm into the floor, tilted 0.2 rad
    req.wearable = true;
    req.text = true;
    const RenderResult r = render_scene(lavapipe(), load_scene("flat.json"), req);
    CHECK(r.proxy.contact);
    CHECK(0.014 * r.view.px_per_m > 250.0);  // px: the platform's 14 mm (a third of the width at least)
    const Theme& t = dark_theme();
    long cable = 0, force = 0;
    for (int y = 0; y < r.image.height; ++y)
        for (int x = 0; x < r.image.width; ++x) {
            const uint8_t* p = r.image.pixel(x, y);
            cable += p[0] == t.cable.r && p[1] == t.cable.g && p[2] == t.cable.b;
            force += p[0] == t.force.r && p[1] == t.force.g && p[2] == t.force.b;
        }
    CHECK(cable > 300);  // px: the tension arrows, the key's swatch and labels
    CHECK(force > 100);  // px: the force arrow and the key's swatch, apart from the cables
    const SnapshotResult s = check_snapshot("flat_wearable_1280", r.image);
    INFO(s.message);
    CHECK(s.ok);
    CHECK(lavapipe().validation_messages() == 0);
}
