// test_segment_index.cpp — the environment's index bounds every c-space piece it is asked about.
//
// The tree prunes a pad query by each node's offset boxes at the scene's pad radius rho
// (environment.hpp, offset_boxes; aabb_tree.hpp, query_pad_reach). These tests check the two
// facts that pruning rests on, over the contact soak's seeded random scenes (stars of lines, arcs
// and curves, thin walls, terrains): every piece a segment makes for a pad of radius rho lies in
// that segment's box for its side, and a proxy whose pad radius differs from rho (the box then
// moved by (r - rho) n over the node's cone) still gathers every piece that matters, bit for bit.
#include "haptics/cspace.hpp"
#include "haptics/environment.hpp"
#include "haptics/proxy.hpp"
#include "haptics/verify/random_contact_scenes.hpp"
#include "against_every_segment.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <random>

using namespace contactlab;
using namespace contactlab::verify;

namespace {

// Points along a piece: its ends and 15 between (a circle's along its span).
std::vector<Vec2> points_on(const CPiece& p) {
    std::vector<Vec2> out;
    for (int k = 0; k <= 16; ++k) {
        const double f = k / 16.0;
        out.push_back(piece_point(p, f * (p.kind == CPiece::Kind::line ? p.len : p.span.width)));
    }
    return out;
}

bool inner_side(CPiece::Source s) { return s == CPiece::Source::vertex_inner || s == CPiece::Source::arc_inner; }

}  // namespace

TEST_CASE("index: every piece a segment makes for a pad of the scene's radius lies in its offset box") {
    // Pad-end pieces are the segment seen from the pad's ends: the tree finds those by the ends'
    // discs, not by offset, so they are not checked here.
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> angle(-kPi, kPi);
    int checked = 0, inner_checked = 0;
    for (std::uint64_t index = 0; index < 12; ++index) {
        const ContactCase c = make_contact_case(case_seed(5, index));
        const Environment env = build_environment(c.scene);
        const FingerShape finger = finger_from_def(c.scene.finger);
        CAPTURE(c.seed);
        std::vector<CPiece> pieces;
        for (int phi_k = 0; phi_k < 4; ++phi_k) {
            const double phi = angle(rng);
            for (int id = 0; id < static_cast<int>(env.segments.size()); ++id) {
                const OffsetBoxes boxes = offset_boxes(env.segments[static_cast<std::size_t>(id)], finger.radius);
                pieces.clear();
                append_cspace_pieces(env, id, finger, phi, pieces);
                for (const CPiece& p : pieces) {
                    if (p.source == CPiece::Source::endpoint) continue;
                    const Aabb& box = inner_side(p.source) ? boxes.inner : boxes.outer;
                    for (const Vec2 q : points_on(p)) {
                        CAPTURE(id);
                        CAPTURE(static_cast<int>(p.source));
                        REQUIRE(box.contains(q));
                    }
                    ++checked;
                    inner_checked += inner_side(p.source) ? 1 : 0;
                }
            }
        }
    }
    MESSAGE(checked, " pieces checked, ", inner_checked, " of them inner");
    CHECK(checked > 1000);
    CHECK(inner_checked > 50);
}

TEST_CASE("index: a pad smaller or larger than the scene's gathers every piece that matters (bit for bit)") {
    // The index holds offset boxes at the scene's R; a device or a live edit may give the proxy
    // another radius. Against use_index = false (every segment, every tick) on the soak's scenes,
    // with the pad 0.6 and 1.5 times the scene's.
    contactlab::test::AgainstEverySegment counts;
    for (const double scale : {0.6, 1.5}) {
        for (std::uint64_t index = 0; index < 4; ++index) {
            const ContactCase c = make_contact_case(case_seed(9, index));
            const Environment env = build_environment(c.scene);
            ProxyDef def = proxy_def_of(c.scene);
            def.finger.radius *= scale;
            def.finger.length *= scale;  // the same pad angle
            CAPTURE(scale);
            CAPTURE(c.seed);
            contactlab::test::replay_against_every_segment(env, def, c.path, counts);
        }
    }
    MESSAGE(counts.rows, " rows, ", counts.contact_rows, " in contact");
    CHECK(counts.contact_rows > counts.rows / 4);
}

TEST_CASE("index: a small scene at an unchanged angle gathers every segment, a turning finger only those near") {
    // kProxySmallScene: below it the tree costs more than it saves while the pieces are kept
    // from tick to tick; while the finger turns every piece is rebuilt, and the index's few are
    // cheaper. A 10-segment floor, the pad 1 mm in, sliding 0.1 mm a tick.
    std::vector<Vec2> pts;
    for (int i = 0; i <= 10; ++i) pts.push_back({-0.25 + 0.05 * i, 0.0});
    Scene scene;
    Contour floor;
    for (int i = 0; i < 10; ++i) floor.segments.push_back(LineSegment{pts[i], pts[i + 1]});
    scene.contours.push_back(floor);
    const Environment env = build_environment(scene);
    REQUIRE(static_cast<int>(env.segments.size()) <= kProxySmallScene);
    Proxy proxy(env, proxy_def_of(scene));
    proxy.reset({0.0, 0.03}, 0.0);
    int all = 0, fewer = 0;
    for (int k = 0; k < 200; ++k) {
        const double phi = k < 100 ? 0.0 : 0.002 * (k - 99);  // still, then turning
        const ProxyOutput& o = proxy.update({0.0001 * k, 0.025}, phi);
        REQUIRE(o.contact);
        CHECK(std::abs(o.proxy.y - 0.026) < 1e-12);  // on the floor's offset, R = 26 mm above it
        if (k < 2) continue;
        if (k < 100) all += o.work.segments == 10 ? 1 : 0;
        else fewer += o.work.segments < 10 ? 1 : 0;
    }
    CHECK(all == 98);
    CHECK(fewer == 100);
}

TEST_CASE("index: a bowl tighter than the pad is asked for by the pad's ends only, and nothing is lost (bit for bit)") {
    // A parabolic valley y = h (x / w)^2 (one quadratic curve, exact mode: a G1 chain of arcs),
    // curvature radius w^2 / (2 h) = 25 mm at its bottom, the pad's 26 mm: the arcs within ~4 mm
    // of the bottom are bowls tighter than the pad, which touch only its ends (cspace.cpp), and
    // their offsets by R all crowd about the point 26 mm above the bottom, where the pad rests.
    const double w = 0.025, h = 0.0125;  // m
    Scene scene;
    Contour valley;
    valley.segments.push_back(QuadSegment{{-w, h}, {0.0, -h}, {w, h}});
    scene.contours.push_back(valley);
    const Environment env = build_environment(scene);
    const double R = scene.finger.radius;
    std::vector<int> tight;  // bowl arcs tighter than the pad, no vertex pieces
    for (int i = 0; i < static_cast<int>(env.segments.size()); ++i) {
        const EnvSegment& e = env.segments[static_cast<std::size_t>(i)];
        if (e.kind == EnvSegment::Kind::arc && !e.free_outside && e.radius <= R && e.end_cone.width <= 0.0 &&
            e.start_cone.width <= 0.0)
            tight.push_back(i);
    }
    MESSAGE(env.segments.size(), " arcs, ", tight.size(), " of them tighter than the pad");
    REQUIRE(tight.size() >= 2);
    // Above the bottom, 1 mm round the point their offsets crowd to, no pad ends asked: the outer
    // side's query holds none of them for the scene's pad, every one for a pad tighter than they are.
    const Vec2 above{0.0, R};
    const NormalCone every{0.0, kTwoPi};
    auto gathered_tight = [&](double r) {
        std::vector<int> out;
        env.tree.query_pad_reach(above, r, 1e-3, false, nullptr, 0, 0.0, every, out);
        int n = 0;
        for (const int id : out) n += std::find(tight.begin(), tight.end(), id) != tight.end() ? 1 : 0;
        return n;
    };
    CHECK(gathered_tight(R) == 0);
    std::vector<int> all;
    env.tree.query_pad_reach(Vec2{0.0, 0.02}, 0.02, 2e-3, false, nullptr, 0, 0.0, every, all);
    int tighter_pad = 0;
    for (const int id : tight)
        if (env.segments[static_cast<std::size_t>(id)].radius > 0.02) ++tighter_pad;
    int found = 0;
    for (const int id : tight)
        if (env.segments[static_cast<std::size_t>(id)].radius > 0.02 && std::find(all.begin(), all.end(), id) != all.end()) ++found;
    CHECK(found == tighter_pad);
    // Lowered from 5 mm above onto the walls, then sliding across the bottom 0.5 mm deep, the
    // pad's ends on the walls: the same proxy, force and l_d as a proxy building every segment
    // every tick.
    std::vector<verify::HandSample> path;
    for (int k = 0; k < 100; ++k) path.push_back({Vec2{-0.003, R + 0.005 - 5.5e-5 * k}, 0.0});
    for (int k = 0; k <= 600; ++k) path.push_back({Vec2{-0.003 + 1e-5 * k, R - 0.0005}, 0.0});
    contactlab::test::AgainstEverySegment counts;
    contactlab::test::replay_against_every_segment(env, proxy_def_of(scene), path, counts);
    CHECK(counts.contact_rows >= 601);
}

TEST_CASE("index: a pad query made in parts finds what the whole query does, in the same order") {
    // Proxy::prefetch_gather makes a gather ahead a share a tick (AabbTree::continue_pad_reach);
    // the tick that takes it must walk on the whole query's segments in the whole query's order.
    // Over the soak's seeded random scenes and a dense valley, at random points, reaches, pad
    // radii, normal cones and pad ends, with budgets from 1 visit to 16: the parts' items,
    // concatenated, are the whole query's.
    std::mt19937_64 rng(11);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    std::vector<Environment> envs;
    for (std::uint64_t index = 0; index < 8; ++index) envs.push_back(build_environment(make_contact_case(case_seed(9, index)).scene));
    Scene valley;  // 4,000 lines of 10 um on a sinusoid of 10 mm amplitude and 0.1 m period
    Contour c;
    for (int i = 0; i < 4000; ++i) {
        auto y = [](double x) { return 0.01 * std::sin(2.0 * kPi * x / 0.1); };
        const double x0 = -0.045 + 1e-5 * i, x1 = x0 + 1e-5;  // m
        c.segments.push_back(LineSegment{{x0, y(x0)}, {x1, y(x1)}});
    }
    valley.contours.push_back(c);
    envs.push_back(build_environment(valley));
    int queries = 0, split = 0;
    std::size_t items = 0;
    for (const Environment& env : envs) {
        for (int q = 0; q < 40; ++q) {
            // About a pad's radius from a random segment, where pad queries are asked.
            const EnvSegment& near = env.segments[static_cast<std::size_t>(unit(rng) * static_cast<double>(env.segments.size()))];
            const double r = 0.005 + 0.03 * unit(rng);  // m
            const double a = kTwoPi * unit(rng);         // rad
            const Vec2 p = 0.5 * (near.box.lo + near.box.hi) + (0.8 + 0.4 * unit(rng)) * r * Vec2{std::cos(a), std::sin(a)};  // m
            const double reach = 1e-5 * std::pow(1e3, unit(rng));                // m: 10 um to 1 cm
            const bool inner = unit(rng) < 0.5;
            const Vec2 ends[2] = {p + Vec2{-r, 0.0}, p + Vec2{r, 0.0}};
            const int end_count = unit(rng) < 0.5 ? 2 : 0;
            const NormalCone cone = unit(rng) < 0.3 ? NormalCone{0.0, kTwoPi} : NormalCone{kTwoPi * unit(rng), kPi * unit(rng)};
            std::vector<int> whole, parts;
            env.tree.query_pad_reach(p, r, reach, inner, ends, end_count, reach, cone, whole);
            AabbTree::PadReach query;
            env.tree.start_pad_reach(query, p, r, reach, inner, ends, end_count, reach, cone);
            const int budget = 1 + static_cast<int>(unit(rng) * 16.0);
            int calls = 0;
            while (!env.tree.continue_pad_reach(query, budget, parts)) {
                ++calls;
                REQUIRE(calls < 1000000);
            }
            CHECK_FALSE(query.active);
            CHECK(parts == whole);
            ++queries;
            split += calls > 0 ? 1 : 0;
            items += whole.size();
        }
    }
    MESSAGE(queries, " queries, ", split, " of them in more than one part, ", items, " items found");
    CHECK(split > queries / 2);
    CHECK(items > 2000);
}

TEST_CASE("angles: wrap_2pi's shortcuts give fmod's bits") {
    // Building a vertex piece wraps its span's start (the pad's span turned by pi): wrap_2pi skips
    // fmod where the answer is exact without it. Independent reference: the plain fmod rule.
    auto reference = [](double a) {
        a = std::fmod(a, kTwoPi);
        if (a < 0.0) a += kTwoPi;
        return a >= kTwoPi ? 0.0 : a;
    };
    std::mt19937_64 rng(3);
    std::uniform_real_distribution<double> angle(-3.0 * kTwoPi, 3.0 * kTwoPi);
    std::vector<double> cases = {0.0, kPi, kTwoPi, std::nextafter(kTwoPi, 0.0), std::nextafter(kTwoPi, 10.0), 2.0 * kTwoPi,
                                 std::nextafter(2.0 * kTwoPi, 0.0), std::nextafter(2.0 * kTwoPi, 100.0), 1.5 * kTwoPi, 7.0 * kTwoPi};
    for (int k = 0; k < 100000; ++k) cases.push_back(angle(rng));
    for (const double a : cases) {
        CAPTURE(a);
        if (a < 0.0) continue;  // (negative angles take a + 2 pi, not fmod's bits: not this shortcut)
        CHECK(wrap_2pi(a) == reference(a));
    }
}
