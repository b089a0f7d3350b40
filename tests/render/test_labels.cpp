// test_labels.cpp — the canvas's labels (engine/render/label_place.hpp): the wearable's tension
// values, the contact frame's "t", "n" and name never print over each other, over a mark (finger
// outline, pad, cables, arrows, platform, contour) or under the editor's panels. Checked three
// ways: the placer's own test against a brute-force distance on seeded random cases, the boxes of
// a rendered frame against every registered mark by sampling, and the pixels: in the same frame
// drawn without text, no pixel inside a label's box has a mark's colour.
#include "render_fixture.hpp"

#include "engine/render/label_place.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <random>

using namespace render_test;

namespace {

// The least distance (px) from the box to the segment, by sampling both finely: an independent
// reference for LabelMarks::free (0.05 px steps on the segment, the box's nearest point exact).
float box_segment_distance(const LabelBox& box, P2 a, P2 b) {
    const int n = std::max(2, static_cast<int>(std::hypot(b.x - a.x, b.y - a.y) / 0.05f));
    float best = 1e30f;
    for (int i = 0; i <= n; ++i) {
        const P2 p = a + (b - a) * (static_cast<float>(i) / n);
        const P2 q(std::clamp(p.x, box.lo.x, box.hi.x), std::clamp(p.y, box.lo.y, box.hi.y));
        best = std::min(best, std::hypot(p.x - q.x, p.y - q.y));
    }
    return best;
}

// Every placed label inside the area, on no other text, clear of every stroke (sampled); the
// legend's boxes (scale and force bars, the key, the status line) clear of every stroke too.
void check_labels_clear(const LabelMarks& marks) {
    const std::size_t legend = marks.texts.size() - marks.placed.size();  // the fixed boxes come first
    for (std::size_t i = 0; i < legend; ++i) {
        CAPTURE(i);
        for (const LabelStroke& s : marks.strokes) CHECK(box_segment_distance(marks.texts[i], s.a, s.b) > s.half_width);
    }
    for (std::size_t i = legend; i < marks.texts.size(); ++i) {
        const LabelBox& b = marks.texts[i];
        CAPTURE(marks.placed[i - legend]);
        CHECK(b.lo.x >= marks.area.lo.x);
        CHECK(b.lo.y >= marks.area.lo.y);
        CHECK(b.hi.x <= marks.area.hi.x);
        CHECK(b.hi.y <= marks.area.hi.y);
        for (std::size_t j = 0; j < marks.texts.size(); ++j)
            if (j != i) CHECK_FALSE(b.intersects(marks.texts[j]));
        for (const LabelStroke& s : marks.strokes) CHECK(box_segment_distance(b, s.a, s.b) > s.half_width);
    }
}

// Pixels of a mark's exact colour inside the box (the frame drawn without text).
int mark_pixels_in(const Image& img, const LabelBox& b, const Theme& t) {
    const Color marks[] = {t.cable, t.force, t.legend, t.target, t.contact, t.pad, t.finger_outline, t.proxy, t.contour};
    int n = 0;
    for (int y = static_cast<int>(b.lo.y); y < static_cast<int>(b.hi.y); ++y)
        for (int x = static_cast<int>(b.lo.x); x < static_cast<int>(b.hi.x); ++x) {
            if (x < 0 || y < 0 || x >= img.width || y >= img.height) continue;
            const uint8_t* p = img.pixel(x, y);
            for (const Color& c : marks) n += p[0] == c.r && p[1] == c.g && p[2] == c.b;
        }
    return n;
}

// The wearable picture with text, then the same frame without text: labels checked both ways.
LabelMarks check_wearable_frame(RenderRequest req, const Scene& scene) {
    req.wearable = true;
    req.text = true;
    const RenderResult with_text = render_scene(lavapipe(), scene, req);
    check_labels_clear(with_text.labels);
    req.text = false;
    const RenderResult bare = render_scene(lavapipe(), scene, req);
    // Every label, the key and the status line (the boxes after the scale and force bars, which
    // hold the bars' own lines) cover no mark's pixel.
    for (std::size_t i = 2; i < with_text.labels.texts.size(); ++i) {
        CAPTURE(i);
        CHECK(mark_pixels_in(bare.image, with_text.labels.texts[i], req.theme) == 0);
    }
    CHECK(lavapipe().validation_messages() == 0);
    return with_text.labels;
}

}  // namespace

TEST_CASE("labels: the placer's box test agrees with a brute-force distance on 20,000 seeded random cases") {
    std::mt19937 rng(45);
    std::uniform_real_distribution<float> coord(0.0f, 100.0f), width(0.5f, 8.0f);
    int near = 0, far = 0;
    for (int k = 0; k < 20000; ++k) {
        LabelMarks marks;
        marks.area = {{0.0f, 0.0f}, {100.0f, 100.0f}};
        const P2 lo(coord(rng) * 0.8f, coord(rng) * 0.8f);
        const LabelBox box{lo, lo + P2(5.0f + coord(rng) * 0.15f, 4.0f + coord(rng) * 0.1f)};
        const P2 a(coord(rng), coord(rng));
        const P2 b = k % 10 == 0 ? a : P2(coord(rng), coord(rng));  // a tenth are discs
        const float w = width(rng);
        marks.add_stroke(a, b, w);
        const float d = box_segment_distance(box, a, b);
        const float need = 0.5f * w + kLabelClearance;
        CAPTURE(k);
        // The placer takes the grown box's corners square: it may refuse a place up to
        // (sqrt 2 - 1) need + the sampling step too close at a corner, never accept one too near.
        if (d <= need) {
            CHECK_FALSE(marks.free(box, kLabelClearance));
            ++near;
        } else if (d > need * std::sqrt(2.0f) + 0.05f) {
            CHECK(marks.free(box, kLabelClearance));
            ++far;
        }
    }
    CHECK(near > 2000);
    CHECK(far > 2000);
}

TEST_CASE("labels: outside the area or on other text is never free, the first free candidate is taken, else dropped") {
    LabelMarks marks;
    marks.area = {{10.0f, 10.0f}, {200.0f, 100.0f}};
    CHECK_FALSE(marks.free({{5.0f, 20.0f}, {30.0f, 30.0f}}, 0.0f));   // crosses the left edge
    CHECK_FALSE(marks.free({{180.0f, 20.0f}, {210.0f, 30.0f}}, 0.0f)); // crosses the right edge (a panel)
    CHECK(marks.free({{20.0f, 20.0f}, {40.0f, 30.0f}}, 0.0f));
    marks.texts.push_back({{20.0f, 20.0f}, {40.0f, 30.0f}});
    CHECK_FALSE(marks.free({{35.0f, 25.0f}, {60.0f, 35.0f}}, 0.0f));
    CHECK_FALSE(marks.free({{41.0f, 20.0f}, {60.0f, 30.0f}}, kLabelClearance));  // 1 px from it
    P2 at;
    REQUIRE(place_label(marks, "a", {10.0f, 8.0f}, {{25.0f, 22.0f}, {100.0f, 50.0f}}, at));
    CHECK(at.x == 100.0f);
    CHECK(at.y == 50.0f);
    CHECK_FALSE(place_label(marks, "b", {10.0f, 8.0f}, {{25.0f, 22.0f}, {195.0f, 50.0f}}, at));
    REQUIRE(marks.dropped.size() == 1);
    CHECK(marks.dropped[0] == "b");
    // Candidates start toward the given direction: the first lies right of an anchor for +x.
    const std::vector<P2> c = label_candidates({50.0f, 50.0f}, {20.0f, 10.0f}, {1.0f, 0.0f}, 4.0f);
    REQUIRE(c.size() == 96);
    CHECK(c[0].x == doctest::Approx(54.0f));
    CHECK(c[0].y == doctest::Approx(45.0f));
}

TEST_CASE("labels: the wearable at 1280x720 zoomed: tensions, t, n and 'contact frame' on nothing, all placed") {
    RenderRequest req;
    req.finger = FingerPose{{0.0, 0.0245}, 0.2};  // 1.5 mm into the floor, tilted 0.2 rad
    const LabelMarks m = check_wearable_frame(req, load_scene("flat.json"));
    CHECK(m.dropped.empty());
    CHECK(m.placed.size() == 5);  // two tensions, n, t, the frame's name
}

TEST_CASE("labels: the editor's view (whole scene, panels over both sides) keeps labels off marks and panels") {
    // The editor at 1280x720 with sim-wearable, not zoomed: the finger ~100 px long, its labels
    // crowd the pad; the Tuning panel covers the left 428 px, the right column from 908 px.
    for (const double phi : {-0.4, 0.0, 0.2, 0.6}) {
        CAPTURE(phi);
        RenderRequest req;
        req.finger = FingerPose{{0.0, 0.0245}, phi};
        req.view_box = Aabb{{-0.16, -0.12}, {0.16, 0.15}};
        req.left_inset_px = 428.0f;
        req.right_inset_px = 372.0f;
        req.top_inset_px = 58.0f;
        req.bottom_inset_px = 19.0f;
        req.status_line = false;  // the editor shows the proxy's state in a row of its own
        const LabelMarks m = check_wearable_frame(req, load_scene("flat.json"));
        // n, t, the frame's name and one label per cable pulling (at phi 0.6 the distal one is slack).
        CHECK(m.placed.size() + m.dropped.size() >= 4 - (phi > 0.5));
        CHECK(m.dropped.empty());
    }
}

TEST_CASE("labels: zoomed under the editor's right column, the distal tension label moves left of the panel") {
    // Zoomed on the fingertip (Z), the distal cable's arrow tip lies near the right column: its
    // label used to be cut by the Haptics panel.
    RenderRequest req;
    req.finger = FingerPose{{0.0, 0.0245}, 0.2};
    req.left_inset_px = 428.0f;
    req.right_inset_px = 372.0f;
    req.top_inset_px = 58.0f;
    req.bottom_inset_px = 19.0f;
    req.status_line = false;
    const LabelMarks m = check_wearable_frame(req, load_scene("flat.json"));
    CHECK(m.dropped.empty());
    CHECK(m.placed.size() == 5);
}

TEST_CASE("labels: pressing the block's edge, the contour beside the pad is a mark too") {
    for (const double phi : {-0.3, 0.0, 0.3}) {
        CAPTURE(phi);
        RenderRequest req;
        req.finger = FingerPose{{0.005, 0.022}, phi};
        req.width = 640;
        req.height = 360;
        check_wearable_frame(req, load_scene("block.json"));
    }
}

TEST_CASE("labels: a status line wider than the picture is left out and named, not cut at the edge") {
    RenderRequest req;
    req.width = 321;
    req.height = 181;
    req.text = true;
    const RenderResult r = render_scene(lavapipe(), load_scene("flat.json"), req);
    REQUIRE(r.labels.dropped.size() == 1);
    CHECK(r.labels.dropped[0] == "status line");
    req.width = 641;
    const RenderResult wide = render_scene(lavapipe(), load_scene("flat.json"), req);
    CHECK(wide.labels.dropped.empty());
    CHECK(lavapipe().validation_messages() == 0);
}
