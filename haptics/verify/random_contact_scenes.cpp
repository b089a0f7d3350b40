// random_contact_scenes.cpp — the generator behind the contact property test and soak (see the
// header for what is generated and why).
#include "haptics/verify/random_contact_scenes.hpp"

#include "haptics/scene_io.hpp"
#include "haptics/verify/solid_reference.hpp"

#include <algorithm>
#include <cmath>
#include <random>

namespace contactlab::verify {
namespace {

constexpr double kTerrainHalfWidth = 0.25;   // m: the terrain runs over x in [-0.25, 0.25]
constexpr double kHandHalfWidth = 0.15;      // m: hands keep |x| <= this (pad >= 7 cm from its ends)
constexpr double kOverlapTolerance = 2e-5;   // m: chords used to check that contours do not cross
// m: chords used to check that two neighbouring segments do not cross each other. Where a contour
// turns back on itself at a vertex (a turn within a few degrees of pi), the two segments leave the
// vertex almost along each other and, if they bend toward each other, cross again a few
// micrometres to a millimetre away, enclosing a sliver 20 nm to 40 um wide: far inside one chord
// at kOverlapTolerance, and the check above skips neighbouring chords anyway. Such a contour is
// not simple: read by its crossings (the reference) the sliver flips sides, and the true tip of
// the spike or crevice is the crossing, not the vertex, whose tangents say the opposite corner
// (fuzz-contact: case seeds 4317594715245305465 and 568609179976502558, a convex tip read as a
// concave corner, so the pad had no vertex piece there and dropped over it by up to 1.7 mm).
// At 1e-10 m a crossing is seen unless it lies within one chord (a few micrometres) of the
// vertex, where the sides meet within ~3e-4 rad of a full reversal.
constexpr double kNeighbourOverlapTolerance = 1e-10;

std::uint64_t splitmix(std::uint64_t x) {
    x += 0x9e3779b97f4a7c15ull;
    x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
    x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
    return x ^ (x >> 31);
}

// Uniform numbers from a 64-bit engine, the same on every standard library.
struct Rng {
    std::mt19937_64 engine;
    explicit Rng(std::uint64_t seed) : engine(seed) {}
    double unit() { return static_cast<double>(engine() >> 11) * 0x1.0p-53; }  // [0, 1)
    double uniform(double a, double b) { return a + (b - a) * unit(); }
    int integer(int lo, int hi) { return lo + static_cast<int>(unit() * (hi - lo + 1)); }  // [lo, hi]
    bool chance(double p) { return unit() < p; }
};

// A segment from a to b (m) of a random kind; `bulge` scales how far it departs from the chord.
Segment random_edge(Rng& rng, Vec2 a, Vec2 b, double bulge, std::string& kinds) {
    const Vec2 d = b - a;
    const double c = glm::length(d);  // m
    const Vec2 nl = perp_left(d / c);
    const Vec2 m = 0.5 * (a + b);
    const double pick = rng.unit();
    if (pick < 0.4 || c < 1e-3) return LineSegment{a, b};
    if (pick < 0.6) {
        // The circle through a, b and the sagitta point m + sag nl; a minor arc (|sag| <= c / 2).
        double sag = rng.uniform(-bulge, bulge) * c;
        if (std::abs(sag) < 0.02 * c) sag = std::copysign(0.02 * c, sag);
        const double r = (0.25 * c * c + sag * sag) / (2.0 * std::abs(sag));  // m
        const Vec2 centre = m + (sag - std::copysign(r, sag)) * nl;
        const double start = angle_of(a - centre);
        const double sweep = 2.0 * std::asin(std::min(1.0, 0.5 * c / r));
        // Bulging to the left of travel (sag > 0) goes round the centre clockwise.
        kinds += "arc ";
        return ArcSegment{centre, r, start, sag > 0.0 ? start - sweep : start + sweep};
    }
    if (pick < 0.8) {
        kinds += "quad ";
        return QuadSegment{a, m + rng.uniform(-bulge, bulge) * c * nl + rng.uniform(-0.2, 0.2) * d, b};
    }
    kinds += "cubic ";
    return CubicSegment{a, a + d / 3.0 + rng.uniform(-bulge, bulge) * c * nl,
                        a + 2.0 * d / 3.0 + rng.uniform(-bulge, bulge) * c * nl, b};
}

Contour star(Rng& rng, Vec2 centre, std::string& kinds) {
    const int n = rng.integer(4, 10);
    const double r0 = rng.uniform(0.02, 0.06);  // m
    std::vector<Vec2> v;
    for (int i = 0; i < n; ++i) {
        // Clockwise (decreasing angle): solid inside.
        const double angle = -kTwoPi * (i + rng.uniform(-0.3, 0.3)) / n;
        v.push_back(centre + r0 * rng.uniform(0.45, 1.0) * unit_at(angle));
    }
    Contour c;
    c.closed = true;
    for (int i = 0; i < n; ++i) c.segments.push_back(random_edge(rng, v[i], v[(i + 1) % n], 0.3, kinds));
    return c;
}

Contour thin_wall(Rng& rng, Vec2 base) {
    const double w = rng.uniform(2e-4, 1e-3);   // m
    const double h = rng.uniform(0.02, 0.06);   // m
    const double tilt = rng.uniform(-0.8, 0.8); // rad from vertical
    const Vec2 up = unit_at(0.5 * kPi + tilt), across = -perp_left(up);  // across: to the right
    const Vec2 p0 = base, p1 = base + h * up, p2 = p1 + w * across, p3 = base + w * across;
    // p0 -> p1 -> p2 -> p3 goes up the left face, across the top, down the right: clockwise.
    Contour c;
    c.closed = true;
    c.segments = {LineSegment{p0, p1}, LineSegment{p1, p2}, LineSegment{p2, p3}, LineSegment{p3, p0}};
    return c;
}

Contour terrain(Rng& rng, double y0, std::string& kinds) {
    const int n = rng.integer(5, 12);
    std::vector<double> xs{-kTerrainHalfWidth, kTerrainHalfWidth};
    for (int i = 0; i < n - 1; ++i) xs.push_back(rng.uniform(-kTerrainHalfWidth + 0.01, kTerrainHalfWidth - 0.01));
    std::sort(xs.begin(), xs.end());
    Contour c;
    Vec2 prev{xs[0], y0 + rng.uniform(-0.02, 0.02)};
    for (std::size_t i = 1; i < xs.size(); ++i) {
        if (xs[i] - prev.x < 2e-3) continue;
        const Vec2 next{xs[i], y0 + rng.uniform(-0.02, 0.02)};
        c.segments.push_back(random_edge(rng, prev, next, 0.25, kinds));
        prev = next;
    }
    return c;
}

// Chords of a contour within kOverlapTolerance (closed contours end where they start).
std::vector<Vec2> chords(const Contour& c) {
    std::vector<Vec2> pts{segment_start(c.segments.front())};
    for (const Segment& s : c.segments) flatten_segment(s, kOverlapTolerance, pts);
    return pts;
}

bool edges_cross(Vec2 a, Vec2 b, Vec2 p, Vec2 q) {
    const double d1 = cross(b - a, p - a), d2 = cross(b - a, q - a);
    const double d3 = cross(q - p, a - p), d4 = cross(q - p, b - p);
    return ((d1 > 0.0) != (d2 > 0.0)) && ((d3 > 0.0) != (d4 > 0.0));
}

// True when two polylines (or one with itself, skipping neighbouring edges) cross anywhere. Edges
// are compared only within pairs of 32-edge runs whose boxes overlap.
bool polylines_cross(const std::vector<Vec2>& u, const std::vector<Vec2>& v, bool same, bool closed) {
    constexpr std::size_t kRun = 32;
    struct Box { Vec2 lo, hi; };
    auto boxes = [](const std::vector<Vec2>& p) {
        std::vector<Box> out;
        for (std::size_t i = 0; i + 1 < p.size(); i += kRun) {
            Box b{p[i], p[i]};
            for (std::size_t k = i + 1; k <= std::min(i + kRun, p.size() - 1); ++k) {
                b.lo = glm::min(b.lo, p[k]);
                b.hi = glm::max(b.hi, p[k]);
            }
            out.push_back(b);
        }
        return out;
    };
    const std::vector<Box> bu = boxes(u), bv = same ? bu : boxes(v);
    for (std::size_t a = 0; a < bu.size(); ++a) {
        for (std::size_t b = same ? a : 0; b < bv.size(); ++b) {
            if (bu[a].lo.x > bv[b].hi.x || bv[b].lo.x > bu[a].hi.x || bu[a].lo.y > bv[b].hi.y || bv[b].lo.y > bu[a].hi.y)
                continue;
            const std::size_t i_end = std::min((a + 1) * kRun, u.size() - 1), j_end = std::min((b + 1) * kRun, v.size() - 1);
            for (std::size_t i = a * kRun; i < i_end; ++i) {
                for (std::size_t j = b * kRun; j < j_end; ++j) {
                    if (same && j <= i + 1) continue;                         // itself and its neighbour
                    if (same && closed && i == 0 && j + 2 == v.size()) continue;  // the closing neighbours
                    if (edges_cross(u[i], u[i + 1], v[j], v[j + 1])) return true;
                }
            }
        }
    }
    return false;
}

bool point_in_polyline(const std::vector<Vec2>& poly, Vec2 p) {
    bool in = false;
    for (std::size_t i = 0; i + 1 < poly.size(); ++i) {
        const Vec2 a = poly[i], b = poly[i + 1];
        if ((a.y > p.y) == (b.y > p.y)) continue;
        if (a.x + (p.y - a.y) * (b.x - a.x) / (b.y - a.y) > p.x) in = !in;
    }
    return in;
}

// True when segments a and b (b starting where a ends) cross each other, or either crosses
// itself, anywhere but at their shared vertex: on fine chords (kNeighbourOverlapTolerance), as
// one polyline whose only skipped pair is the two chords meeting at that vertex (and, when b also
// ends where a starts, a closed contour of just these two, the two meeting there).
bool neighbours_cross(const Segment& a, const Segment& b, bool loop) {
    std::vector<Vec2> pts{segment_start(a)};
    flatten_segment(a, kNeighbourOverlapTolerance, pts);
    flatten_segment(b, kNeighbourOverlapTolerance, pts);
    return polylines_cross(pts, pts, true, loop);
}

}  // namespace

bool contours_well_formed(const Scene& scene) {
    std::vector<std::vector<Vec2>> polys;
    for (const Contour& c : scene.contours) polys.push_back(chords(c));
    for (std::size_t i = 0; i < polys.size(); ++i) {
        if (polylines_cross(polys[i], polys[i], true, scene.contours[i].closed)) return false;
        const std::vector<Segment>& segs = scene.contours[i].segments;
        const bool closed = scene.contours[i].closed;
        const bool two = closed && segs.size() == 2;  // each pair is then the whole loop
        for (std::size_t k = 0; k + 1 < segs.size(); ++k)
            if (neighbours_cross(segs[k], segs[k + 1], two)) return false;
        if (closed && segs.size() > 2 && neighbours_cross(segs.back(), segs.front(), false)) return false;
        for (std::size_t j = i + 1; j < polys.size(); ++j) {
            if (polylines_cross(polys[i], polys[j], false, false)) return false;
            if (scene.contours[i].closed && point_in_polyline(polys[i], polys[j].front())) return false;
            if (scene.contours[j].closed && point_in_polyline(polys[j], polys[i].front())) return false;
        }
    }
    try {
        validate_scene(scene);
    } catch (const SceneError&) {
        return false;
    }
    return true;
}

namespace {

Scene random_scene(Rng& rng, std::string& summary) {
    for (;;) {
        Scene scene;
        scene.finger.radius = rng.uniform(0.005, 0.03);                         // m
        scene.finger.length = scene.finger.radius * rng.uniform(0.2, 2.0);      // m
        scene.force.stiffness = 1000.0;                                         // N/m
        scene.force.max_force = 1e4;  // N: the largest allowed, far above Ke d here (d < 5 cm), so F = Ke d is checkable
        std::string kinds;
        const bool has_terrain = rng.chance(0.6);
        const int closed = rng.integer(has_terrain ? 0 : 1, 3);
        int stars = 0, walls = 0;
        double floor_top = -1.0;  // m: closed shapes stay above the terrain
        if (has_terrain) {
            scene.contours.push_back(terrain(rng, -0.06, kinds));
            floor_top = -0.06 + 0.025;  // y0 + 2 cm of relief + bulges, generously
        }
        for (int i = 0; i < closed; ++i) {
            if (rng.chance(0.3)) {
                scene.contours.push_back(thin_wall(rng, {rng.uniform(-0.1, 0.1), std::max(floor_top + 0.002, rng.uniform(-0.04, 0.02))}));
                ++walls;
            } else {
                const Vec2 c{rng.uniform(-0.1, 0.1), std::max(floor_top + 0.07, rng.uniform(-0.02, 0.08))};
                scene.contours.push_back(star(rng, c, kinds));
                ++stars;
            }
        }
        // A draw that is not well-formed is skipped and drawn again from the same engine, so a
        // case stays a function of its seed. validate_scene (in contours_well_formed) also refuses
        // closed contours that cross (contour_crossing.hpp); the checks above already skip every
        // such draw (the first 5,000 cases of soak seeds 1 and 3: none of them crosses by its test).
        if (!contours_well_formed(scene)) continue;
        char buf[160];
        std::snprintf(buf, sizeof buf, "%d star(s), %d thin wall(s)%s; R %.1f mm, L %.1f mm; curves: ", stars, walls,
                      has_terrain ? ", terrain" : "", scene.finger.radius * 1e3, scene.finger.length * 1e3);
        summary = buf + (kinds.empty() ? std::string("none") : kinds);
        return scene;
    }
}

// A random point on the scene's contours (m), from chords of the segments.
Vec2 random_surface_point(Rng& rng, const Scene& scene) {
    const Contour& c = scene.contours[static_cast<std::size_t>(rng.integer(0, static_cast<int>(scene.contours.size()) - 1))];
    const Segment& s = c.segments[static_cast<std::size_t>(rng.integer(0, static_cast<int>(c.segments.size()) - 1))];
    std::vector<Vec2> pts{segment_start(s)};
    flatten_segment(s, 1e-4, pts);
    const std::size_t i = static_cast<std::size_t>(rng.integer(0, static_cast<int>(pts.size()) - 2));
    return glm::mix(pts[i], pts[i + 1], rng.unit());
}

Vec2 keep_in_hand_box(Vec2 p) {
    return {std::clamp(p.x, -kHandHalfWidth, kHandHalfWidth), std::clamp(p.y, -0.12, 0.16)};
}

}  // namespace

std::uint64_t case_seed(std::uint64_t seed, std::uint64_t index) { return splitmix(splitmix(seed) ^ index); }

int case_rows(std::uint64_t seed) { return 300 + static_cast<int>(splitmix(seed ^ 0x5eedull) % 601); }

ContactCase make_contact_case(std::uint64_t seed) {
    ContactCase out;
    out.seed = seed;
    Rng rng(seed);
    out.scene = random_scene(rng, out.summary);
    const SolidReference ref(out.scene);
    const double R = out.scene.finger.radius, L = out.scene.finger.length;

    // A start with the pad clear of every solid by at least 0.1 mm.
    HandSample hand;
    for (int attempt = 0;; ++attempt) {
        hand.finger = {rng.uniform(-0.12, 0.12), rng.uniform(-0.05, 0.14)};
        hand.phi = rng.uniform(-1.3, 1.3);
        if (ref.pad_depth(hand.finger, hand.phi, R, L, 1e-6).depth < -1e-4 || attempt > 1000) break;
    }
    const int rows = case_rows(seed);
    out.path.reserve(static_cast<std::size_t>(rows));
    auto push = [&] { if (static_cast<int>(out.path.size()) < rows) out.path.push_back(hand); };
    // Moves the hand to (goal, phi_goal) in rows of at most `step` (m) and `turn` (rad).
    auto move_to = [&](Vec2 goal, double phi_goal, double step, double turn, int max_rows) {
        goal = keep_in_hand_box(goal);
        for (int k = 0; k < max_rows && static_cast<int>(out.path.size()) < rows; ++k) {
            const Vec2 to_goal = goal - hand.finger;
            const double dist = glm::length(to_goal);
            if (dist > step) hand.finger += to_goal * (step / dist);
            else hand.finger = goal;
            hand.phi += std::clamp(phi_goal - hand.phi, -turn, turn);
            push();
            if (dist <= step && hand.phi == phi_goal) break;
        }
    };
    push();  // row 0: the clear start, where the proxy begins
    while (static_cast<int>(out.path.size()) < rows) {
        const double step = std::exp(rng.uniform(std::log(1e-5), std::log(5e-4)));  // m per row
        const double turn = rng.uniform(1e-4, 4e-3);                                 // rad per row
        if (rng.unit() < 0.75) {
            // A press: approach fast (the proxy sweeps, so big steps are fair) to a point 0-3 mm
            // clear of a surface point, pad middle first; press in small steps up to 3 cm past it
            // (as a hand does when the device's force saturates); then hold, slide or tilt.
            const double phi_goal = std::clamp(hand.phi + rng.uniform(-0.8, 0.8), -1.4, 1.4);
            const Vec2 facing = unit_at(phi_goal - 0.5 * kPi);
            const Vec2 surface = random_surface_point(rng, out.scene);
            const Vec2 clear = surface - (R + rng.uniform(0.0, 0.003)) * facing;
            move_to(clear, phi_goal, std::max(2e-3, glm::length(clear - hand.finger) / 30.0), 0.05, 40);
            const double depth = std::exp(rng.uniform(std::log(2e-5), std::log(0.03)));  // m
            move_to(surface - R * facing + depth * facing, phi_goal, step, turn, 400);
            const double after = rng.unit();
            const Vec2 along = unit_at(phi_goal);
            if (after < 0.4) {
                move_to(hand.finger + rng.uniform(-0.03, 0.03) * along, phi_goal, step, turn, rng.integer(20, 400));
            } else if (after < 0.8) {
                const double tilt = rng.uniform(-1.2, 1.2) * L / R;  // rad: enough to roll onto a pad end
                move_to(hand.finger, std::clamp(phi_goal + tilt, -1.5, 1.5), step, turn, rng.integer(20, 400));
            } else {
                move_to(hand.finger + rng.uniform(-0.02, 0.02) * along, std::clamp(phi_goal + rng.uniform(-0.5, 0.5), -1.5, 1.5),
                        step, turn, rng.integer(20, 400));
            }
        } else {
            // A wander: anywhere nearby, small steps, maybe through thin walls.
            move_to(hand.finger + Vec2{rng.uniform(-0.03, 0.03), rng.uniform(-0.03, 0.03)},
                    std::clamp(hand.phi + rng.uniform(-0.5, 0.5), -1.5, 1.5), step, turn, rng.integer(20, 400));
        }
    }
    return out;
}

}  // namespace contactlab::verify
