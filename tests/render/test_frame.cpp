// test_frame.cpp — what a frame shows, checked at pixels of known world points, plus the proxy
// state it is drawn from, determinism, and a clean validation log.
#include "render_fixture.hpp"

#include "engine/render/frame.hpp"
#include "engine/render/offscreen.hpp"
#include "haptics/stimuli.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <cstring>
#include <map>

using namespace render_test;

namespace {

// The most frequent colour of the image (RGBA packed).
uint32_t dominant_color(const Image& img) {
    std::map<uint32_t, int> count;
    for (size_t i = 0; i < img.rgba.size(); i += 4) {
        uint32_t v;
        std::memcpy(&v, &img.rgba[i], 4);
        ++count[v];
    }
    return std::max_element(count.begin(), count.end(), [](auto& a, auto& b) { return a.second < b.second; })->first;
}

// Some pixel within `radius` px of px has exactly colour c.
bool near_color(const Image& img, P2 px, Color c, int radius = 1) {
    for (int dy = -radius; dy <= radius; ++dy)
        for (int dx = -radius; dx <= radius; ++dx) {
            const int x = static_cast<int>(px.x) + dx, y = static_cast<int>(px.y) + dy;
            if (x < 0 || y < 0 || x >= img.width || y >= img.height) continue;
            const uint8_t* p = img.pixel(x, y);
            if (p[0] == c.r && p[1] == c.g && p[2] == c.b) return true;
        }
    return false;
}

bool rgb_equal(const Image& img, P2 px, Color c) {
    const uint8_t* p = img.pixel(static_cast<int>(px.x), static_cast<int>(px.y));
    return p[0] == c.r && p[1] == c.g && p[2] == c.b && p[3] == 255;
}

Scene scene_of(std::vector<Contour> contours) {
    Scene s;
    s.contours = std::move(contours);
    return s;
}

}  // namespace

TEST_CASE("frame: requested size, solid below a floor is the fill colour, free space is not") {
    const Scene scene = load_scene("flat.json");
    RenderRequest req;
    req.width = 400;
    req.height = 240;
    req.finger = FingerPose{{0.1, 0.05}, 0.0};  // free, well above the floor
    const RenderResult r = render_scene(lavapipe(), scene, req);
    REQUIRE(r.image.width == 400);
    REQUIRE(r.image.height == 240);
    REQUIRE(r.image.rgba.size() == 400u * 240u * 4u);
    const Theme& t = dark_theme();
    CHECK(rgb_equal(r.image, r.view.to_px({-0.2, -0.01}), t.solid_fill));
    CHECK(rgb_equal(r.image, r.view.to_px({0.25, -0.02}), t.solid_fill));
    CHECK_FALSE(rgb_equal(r.image, r.view.to_px({-0.2, 0.01}), t.solid_fill));
    // Beyond the floor's right end (x > 0.3 m) there is no solid.
    CHECK_FALSE(rgb_equal(r.image, r.view.to_px({0.31, -0.02}), t.solid_fill));
    CHECK(lavapipe().validation_messages() == 0);
}

TEST_CASE("frame: closed clockwise contour filled inside, a ceiling drawn right to left filled above") {
    Contour square{true, {LineSegment{{-0.05, -0.05}, {-0.05, 0.0}}, LineSegment{{-0.05, 0.0}, {0.0, 0.0}},
                          LineSegment{{0.0, 0.0}, {0.0, -0.05}}, LineSegment{{0.0, -0.05}, {-0.05, -0.05}}}};
    Contour ceiling{false, {LineSegment{{0.1, 0.05}, {0.02, 0.05}}}};
    const Scene scene = scene_of({square, ceiling});
    RenderRequest req;
    req.width = 320;
    req.height = 180;
    req.finger = FingerPose{{0.06, 0.0}, 0.0};
    const RenderResult r = render_scene(lavapipe(), scene, req);
    const Theme& t = dark_theme();
    CHECK(rgb_equal(r.image, r.view.to_px({-0.025, -0.025}), t.solid_fill));  // inside the square
    CHECK_FALSE(rgb_equal(r.image, r.view.to_px({-0.025, 0.01}), t.solid_fill));
    CHECK_FALSE(rgb_equal(r.image, r.view.to_px({-0.025, -0.06}), t.solid_fill));
    CHECK(rgb_equal(r.image, r.view.to_px({0.06, 0.06}), t.solid_fill));  // above the ceiling
    CHECK_FALSE(rgb_equal(r.image, r.view.to_px({0.06, 0.04}), t.solid_fill));
    CHECK(lavapipe().validation_messages() == 0);
}

TEST_CASE("frame: the finger pressed 2 mm into the floor: proxy on the surface, clamped force, contact drawn") {
    const Scene scene = load_scene("flat.json");
    const double R = scene.finger.radius;
    RenderRequest req;
    req.width = 641;  // odd: x = 0 falls on a pixel centre, so the thin arrow has opaque pixels
    req.height = 360;
    req.finger = FingerPose{{0.0, R - 0.002}, 0.0};
    const RenderResult r = render_scene(lavapipe(), scene, req);
    CHECK(r.proxy.contact);
    CHECK(r.proxy.proxy.x == doctest::Approx(0.0).epsilon(1e-9));
    CHECK(r.proxy.proxy.y == doctest::Approx(R).epsilon(1e-9));
    CHECK(r.proxy.force.y == doctest::Approx(1.5));  // 1000 N/m * 2 mm = 2 N, clamped to 1.5 N
    REQUIRE(r.proxy.contact_count == 1);
    CHECK(r.proxy.contacts[0].point.y == doctest::Approx(0.0).epsilon(1e-9));
    // The contact dot is drawn at the contact point, the force arrow straight above the target.
    const Theme& t = dark_theme();
    const P2 contact_px = r.view.to_px(r.proxy.contacts[0].point);
    CHECK(near_color(r.image, contact_px, t.contact));
    // The arrow: 1.5 N is the full length (metrics: 70 px at 360 px high), straight up.
    const P2 target_px = r.view.to_px({0.0, -0.002});
    CHECK(near_color(r.image, target_px + P2(0.0f, -40.0f), t.force));
    CHECK_FALSE(near_color(r.image, target_px + P2(0.0f, -90.0f), t.force));
    CHECK(lavapipe().validation_messages() == 0);
}

TEST_CASE("frame: the finger tilted on the floor touches at l = -R phi (the proxy's value, drawn at the target)") {
    const Scene scene = load_scene("flat.json");
    const double R = scene.finger.radius, phi = 0.2;
    const ProxyDef def = proxy_def_of(scene);
    const Environment env = build_environment(scene);
    const ProxyOutput o = settle_proxy(env, def, FingerPose{{0.01, R - 0.001}, phi});
    CHECK(o.contact);
    CHECK(o.l_d == doctest::Approx(-R * phi).epsilon(1e-6));
}

TEST_CASE("frame: two renders of the same scene are byte-identical (fresh targets, same context)") {
    const Scene scene = load_scene("bowl.json");
    RenderRequest req;
    req.width = 320;
    req.height = 180;
    req.overlays = {true, true};
    const RenderResult a = render_scene(lavapipe(), scene, req);
    const RenderResult b = render_scene(lavapipe(), scene, req);
    CHECK(a.image.rgba == b.image.rgba);
    // And the same draw list rendered twice on one target.
    const Environment env = build_environment(scene);
    FrameContent c;
    c.scene = &scene;
    c.env = &env;
    c.shape = finger_from_def(scene.finger);
    c.finger = settle_proxy(env, proxy_def_of(scene), default_finger_pose(env, proxy_def_of(scene)));
    DrawList list(320, 180);
    build_frame(c, default_view(c, 320, 180), dark_theme(), list);
    OffscreenTarget target(lavapipe(), 320, 180);
    const Image x = target.render(list, dark_theme().background);
    const Image y = target.render(list, dark_theme().background);
    CHECK(x.rgba == y.rgba);
    CHECK(lavapipe().validation_messages() == 0);
}

TEST_CASE("frame: themes differ, an empty scene is mostly the theme background") {
    Scene empty;
    RenderRequest req;
    req.width = 64;
    req.height = 64;
    const RenderResult dark = render_scene(lavapipe(), empty, req);
    req.theme = light_theme();
    const RenderResult light = render_scene(lavapipe(), empty, req);
    CHECK(dark.image.rgba != light.image.rgba);
    const Color bg = light_theme().background;
    const uint32_t dominant = dominant_color(light.image);
    uint32_t expected;
    const uint8_t bytes[4] = {bg.r, bg.g, bg.b, 255};
    std::memcpy(&expected, bytes, 4);
    CHECK(dominant == expected);
    CHECK(lavapipe().validation_messages() == 0);
}

TEST_CASE("frame: a chain of 100 000 segments renders and fills below") {
    Contour terrain;
    const int n = 100000;
    for (int i = 0; i < n; ++i) {
        const double x0 = -0.25 + 0.5 * i / n, x1 = -0.25 + 0.5 * (i + 1) / n;
        auto y = [](double x) { return 0.005 * std::sin(200.0 * x); };
        terrain.segments.push_back(LineSegment{{x0, y(x0)}, {x1, y(x1)}});
    }
    const Scene scene = scene_of({terrain});
    RenderRequest req;
    req.width = 320;
    req.height = 180;
    req.finger = FingerPose{{0.0, 0.04}, 0.0};
    const RenderResult r = render_scene(lavapipe(), scene, req);
    CHECK(rgb_equal(r.image, r.view.to_px({0.1, -0.03}), dark_theme().solid_fill));
    CHECK(lavapipe().validation_messages() == 0);
}

TEST_CASE("frame: labels are drawn only when asked (goldens carry no text), the roller dot sits on the pad") {
    const Scene scene = load_scene("flat.json");
    const Environment env = build_environment(scene);
    const ProxyDef def = proxy_def_of(scene);
    FrameContent c;
    c.scene = &scene;
    c.env = &env;
    c.shape = def.finger;
    c.max_force = def.max_force;
    c.finger = settle_proxy(env, def, FingerPose{{0.0, def.finger.radius - 0.001}, 0.0});
    // 641 px wide: the status line (about 420 px at this text scale) fits; in a narrower picture it
    // is left out rather than cut at the edge.
    const View view = default_view(c, 641, 181);
    OffscreenTarget target(lavapipe(), 641, 181);
    DrawList list(641, 181);
    build_frame(c, view, dark_theme(), list);
    const Image plain = target.render(list, dark_theme().background);
    c.text = true;
    build_frame(c, view, dark_theme(), list);
    const Image labelled = target.render(list, dark_theme().background);
    // The status line is in the top rows; nothing else moves.
    long long top = 0, rest = 0;
    for (int y = 0; y < plain.height; ++y)
        for (int x = 0; x < plain.width; ++x)
            if (std::memcmp(plain.pixel(x, y), labelled.pixel(x, y), 4) != 0) (y < 20 ? top : rest) += 1;
    CHECK(top > 50);
    CHECK(rest > 0);  // the bar labels at the bottom
    bool bottom_only = true;
    for (int y = 20; y < plain.height - 40; ++y)
        for (int x = 0; x < plain.width; ++x)
            bottom_only = bottom_only && std::memcmp(plain.pixel(x, y), labelled.pixel(x, y), 4) == 0;
    CHECK(bottom_only);

    c.text = false;
    c.roller_l = 0.005;  // 5 mm toward the fingertip
    build_frame(c, view, dark_theme(), list);
    const Image roller = target.render(list, dark_theme().background);
    const Vec2 pad_point = c.finger->finger + def.finger.radius * unit_at(-0.5 * kPi + 0.005 / def.finger.radius);
    CHECK(near_color(roller, view.to_px(pad_point), dark_theme().target));
    CHECK_FALSE(near_color(plain, view.to_px(pad_point), dark_theme().target));
    CHECK(lavapipe().validation_messages() == 0);
}

TEST_CASE("frame: open chains fill straight down from the surface, whatever their ends do (seed 002's bumps, a V)") {
    const Theme& t = dark_theme();
    // A surface point p with unit tangent `along` and the solid below it: 6 px below is fill, 6 px
    // above is not (6 px from the surface across it: clear of the stroke and its fringe).
    auto check_below = [&](const RenderResult& r, Vec2 p, Vec2 along = {1.0, 0.0}) {
        CAPTURE(p.x);
        CAPTURE(p.y);
        if (std::abs(along.x) < 0.2) return;  // a near-vertical flank: straight down runs along it
        const double off = 6.0 / r.view.px_per_m / std::abs(along.x);  // m
        // The anticipation line (finger to its anticipated contact) is drawn over the fill: a
        // probe within 4 px of it says nothing about the fill.
        if (r.proxy.anticipating) {
            const Vec2 a = r.proxy.finger, b = r.proxy.anticipated_point, q = p + Vec2{0.0, -off};
            const double s = std::clamp(glm::dot(q - a, b - a) / glm::dot(b - a, b - a), 0.0, 1.0);
            if (glm::length(q - (a + s * (b - a))) * r.view.px_per_m < 4.0) return;
        }
        CHECK(rgb_equal(r.image, r.view.to_px(p + Vec2{0.0, -off}), t.solid_fill));
        CHECK_FALSE(rgb_equal(r.image, r.view.to_px(p + Vec2{0.0, off}), t.solid_fill));
    };
    SUBCASE("bumps, seeds 7, 3 and 11: a profile that rises overall and ends on falling slopes") {
        for (const std::uint64_t seed : {7ull, 3ull, 11ull}) {
            CAPTURE(seed);
            BumpsDef def;
            def.seed = seed;
            const Scene scene = generate_bumps(def).scene;
            RenderRequest req;
            req.width = 640;
            req.height = 480;
            req.finger = FingerPose{{0.09, 0.3}, 0.0};  // far above, out of the way
            const RenderResult r = render_scene(lavapipe(), scene, req);
            const Contour& chain = scene.contours.front();
            REQUIRE_FALSE(chain.closed);
            // Every 8th segment's end, away from the chain's two ends.
            for (std::size_t i = 4; i + 4 < chain.segments.size(); i += 8)
                check_below(r, segment_end(chain.segments[i]), segment_end_tangent(chain.segments[i]));
        }
    }
    SUBCASE("a V whose arms end above the view") {
        Contour v{false, {LineSegment{{-0.3, 0.4}, {0.0, -0.02}}, LineSegment{{0.0, -0.02}, {0.3, 0.4}}}};
        RenderRequest req;
        req.width = 400;
        req.height = 300;
        req.finger = FingerPose{{0.0, 0.05}, 0.0};
        const RenderResult r = render_scene(lavapipe(), scene_of({v}), req);
        check_below(r, {0.0, -0.02});
        check_below(r, {-0.02, -0.02 + 0.42 * 0.02 / 0.3}, glm::normalize(Vec2{0.3, -0.42}));
        check_below(r, {0.02, -0.02 + 0.42 * 0.02 / 0.3}, glm::normalize(Vec2{0.3, 0.42}));
    }
    CHECK(lavapipe().validation_messages() == 0);
}

TEST_CASE("frame: an open chain that crosses itself is filled by the nonzero rule, checked against a winding count") {
    // Left to right overall, with a loop: the fourth segment runs down through the first. The
    // scene is valid (chains may cross themselves: the proxy touches each segment as it is). The
    // chord's right normal points down, so the fill polygon is the chain, then straight down from
    // its end past the view, across, and up to its start (frame_contours.cpp). The reference is
    // a winding number of that polygon computed here; every probe away from the strokes, the
    // finger and the anticipation line must be fill exactly where the winding is not zero.
    const std::vector<Vec2> pts = {{-0.08, 0.0}, {0.04, 0.0}, {0.04, 0.03}, {-0.02, 0.03}, {-0.02, -0.03}, {0.08, -0.03}};
    Contour chain{false, {}};
    for (std::size_t i = 0; i + 1 < pts.size(); ++i) chain.segments.push_back(LineSegment{pts[i], pts[i + 1]});
    RenderRequest req;
    req.width = 480;
    req.height = 360;
    req.finger = FingerPose{{0.0, 0.12}, 0.0};
    const RenderResult r = render_scene(lavapipe(), scene_of({chain}), req);
    const Theme& t = dark_theme();

    std::vector<Vec2> poly = pts;
    const double far = 100.0;  // m below: past any view
    poly.push_back({pts.back().x, pts.back().y - far});
    poly.push_back({pts.front().x, pts.back().y - far});
    auto winding = [&](Vec2 q) {
        int w = 0;
        for (std::size_t i = 0; i < poly.size(); ++i) {
            const Vec2 a = poly[i], b = poly[(i + 1) % poly.size()];
            const double side = (b.x - a.x) * (q.y - a.y) - (q.x - a.x) * (b.y - a.y);
            if (a.y <= q.y && b.y > q.y && side > 0) ++w;
            if (a.y > q.y && b.y <= q.y && side < 0) --w;
        }
        return w;
    };
    auto px_distance_to_chain = [&](Vec2 q) {
        double d = 1e30;
        for (std::size_t i = 0; i + 1 < pts.size(); ++i) {
            const Vec2 a = pts[i], b = pts[i + 1];
            const double s = std::clamp(glm::dot(q - a, b - a) / glm::dot(b - a, b - a), 0.0, 1.0);
            d = std::min(d, glm::length(q - (a + s * (b - a))));
        }
        return d * r.view.px_per_m;
    };
    int filled = 0, empty = 0, positive = 0, negative = 0;
    for (double x = -0.07; x <= 0.07; x += 0.0025)
        for (double y = -0.06; y <= 0.05; y += 0.0025) {
            const Vec2 q{x, y};
            const P2 at = r.view.to_px(q);
            if (at.x < 1 || at.y < 1 || at.x >= req.width - 1 || at.y >= req.height - 1) continue;  // outside the view
            if (px_distance_to_chain(q) < 5.0) continue;
            if (glm::length(q - r.proxy.finger) < 0.03) continue;  // the finger's body and pad
            if (r.proxy.anticipating) {
                const Vec2 a = r.proxy.finger, b = r.proxy.anticipated_point;
                const double s = std::clamp(glm::dot(q - a, b - a) / glm::dot(b - a, b - a), 0.0, 1.0);
                if (glm::length(q - (a + s * (b - a))) * r.view.px_per_m < 4.0) continue;
            }
            const int w = winding(q);
            CAPTURE(x);
            CAPTURE(y);
            CAPTURE(w);
            CHECK(rgb_equal(r.image, at, t.solid_fill) == (w != 0));
            (w != 0 ? filled : empty) += 1;
            positive += w > 0;
            negative += w < 0;
        }
    // The probes saw all three kinds of region: outside, the body (wound clockwise, -1) and the
    // loop, wound the other way (+1): filled too, as the nonzero rule says.
    CHECK(filled > 50);
    CHECK(empty > 50);
    CHECK(positive > 5);
    CHECK(negative > 5);
    CHECK(lavapipe().validation_messages() == 0);
}
