// surface_profile.cpp — resting heights of a circle on a sampled contour (surface_profile.hpp).
#include "engine/experiments/protocol/surface_profile.hpp"

#include <algorithm>
#include <cmath>

namespace contactlab::experiments {

namespace {

// The line no point of pts[a, b) rises above (SurfaceProfile::BlockLine): their chord, lifted by
// the most any of them rises over it.
SurfaceProfile::BlockLine line_over(const std::vector<Vec2>& pts, std::size_t a, std::size_t b) {
    SurfaceProfile::BlockLine l;
    l.x0 = pts[a].x;
    l.x1 = pts[b - 1].x;
    l.y0 = pts[a].y;
    const double run = l.x1 - l.x0;  // m
    const double slope = run > 0.0 ? (pts[b - 1].y - l.y0) / run : 0.0;
    l.slope = std::isfinite(slope) && std::abs(slope) <= 1e3 ? slope : 0.0;  // a vertical span: its top
    double above = 0.0;
    for (std::size_t i = a; i < b; ++i) above = std::max(above, pts[i].y - (l.y0 + l.slope * (pts[i].x - l.x0)));
    // The roundings of the line's value at a point are ~1e-17 m at these sizes: far inside this.
    l.above = above + 1e-12 * (1.0 + std::abs(l.y0) + std::abs(l.slope) * run + above);
    l.root = std::sqrt(1.0 + l.slope * l.slope);
    l.lean = l.slope / l.root;
    return l;
}

}  // namespace

SurfaceProfile profile_of(std::vector<Vec2> pts) {
    std::sort(pts.begin(), pts.end(), [](const Vec2& a, const Vec2& b) { return a.x < b.x; });
    SurfaceProfile p;
    constexpr std::size_t B = SurfaceProfile::kBlock;
    p.block_top.assign((pts.size() + B - 1) / B, -1e300);
    for (std::size_t i = 0; i < pts.size(); ++i) p.block_top[i / B] = std::max(p.block_top[i / B], pts[i].y);
    p.run_top.assign((p.block_top.size() + SurfaceProfile::kRun - 1) / SurfaceProfile::kRun, -1e300);
    for (std::size_t k = 0; k < p.block_top.size(); ++k)
        p.run_top[k / SurfaceProfile::kRun] = std::max(p.run_top[k / SurfaceProfile::kRun], p.block_top[k]);
    p.block_line.resize(p.block_top.size());
    for (std::size_t k = 0; k < p.block_line.size(); ++k) p.block_line[k] = line_over(pts, k * B, std::min(pts.size(), (k + 1) * B));
    constexpr std::size_t R = B * SurfaceProfile::kRun;
    p.run_line.resize(p.run_top.size());
    for (std::size_t k = 0; k < p.run_line.size(); ++k) p.run_line[k] = line_over(pts, k * R, std::min(pts.size(), (k + 1) * R));
    p.pts = std::move(pts);
    return p;
}

namespace {

// True when a point at height y (m), whose reach is sqrt(t) with t = r^2 - dx^2 (m^2, as the
// caller computed it), certainly rises no higher than `best` (m): y + sqrt(t) would not exceed it.
// With D = best - y > 0 (d is its rounding), t < d^2 (1 - 1e-9) gives sqrt(t) < D (1 - 0.5e-9 +
// 4 ulp) even after every rounding of d, d^2, the product and the square root itself, so
// y + sqrt(t) < best exactly, and the rounded sum, rounding monotonically toward a double no
// larger than best, is no larger than best either. One multiply instead of a square root: most
// points under a resting pad lie well below the circle through the one it rests on. (d above a
// picometre keeps d^2 clear of subnormals, where the relative bound would fail.)
bool certainly_below(double y, double t, double best) {
    const double d = best - y;  // m
    return d > 1e-12 && t < d * d * (1.0 - 1e-9);
}

// True when no point of a block (or run) whose line is `l` (SurfaceProfile::BlockLine) can hold
// a circle of radius r at x higher than `best` (m), as resting_height computes a point's height:
// when the largest height the circle can rest at on the line within r of x, plus an allowance
// for every rounding, is no more than best. On the line y = y0 + slope (x' - x0) + above the circle rests
// highest where it touches it, at x' = x + r slope / sqrt(1 + slope^2); over the block's points'
// span the height along the line, y(x') + sqrt(r^2 - (x' - x)^2), is concave in x', so its most
// there is at that x' held inside [x0, x1]. The allowance: a point's computed sqrt(r^2 - dx^2)
// exceeds the exact one by at most sqrt(6.7e-16 r^2) + rounding = 2.6e-8 r (r^2 - dx^2 loses
// ~6 ulps of r^2, and the square root of an error near 0 is its largest), and the line's own
// rounding is ~1e-17 m: 1e-7 r + 1e-12 (1 + |y|) covers both by a wide margin, and is still
// nothing beside the micrometres by which the line clears the circle where it rules a block out.
[[gnu::always_inline]] inline bool line_rules_out(const SurfaceProfile::BlockLine& l, double x, double r, double best) {
    const double at = std::clamp(x + r * l.lean, l.x0, l.x1);  // m
    const double d = at - x;
    const double t = r * r - d * d;  // m^2
    const double y = l.y0 + l.slope * (at - l.x0) + l.above;
    // y + sqrt(t) + allowance <= best, the square root spared as in certainly_below: with
    // D = best - allowance - y, t < D^2 (1 - 1e-9) puts sqrt(t) below D by far more than the
    // roundings of D, D^2 and the product.
    const double room = best - (1e-7 * r + 1e-12 * (1.0 + std::abs(y))) - y;  // m
    return room > 1e-12 && t < room * room * (1.0 - 1e-9);
}

// The first point at or after `key` by x (lower_bound), stepping from `at`: a hand a few um on
// from its last sample finds it a step or two away.
std::size_t first_not_before(const std::vector<Vec2>& pts, double key, std::size_t at) {
    at = std::min(at, pts.size());
    while (at > 0 && pts[at - 1].x >= key) --at;
    while (at < pts.size() && pts[at].x < key) ++at;
    return at;
}
// The first point after `key` by x (upper_bound), the same way.
std::size_t first_after(const std::vector<Vec2>& pts, double key, std::size_t at) {
    at = std::min(at, pts.size());
    while (at > 0 && pts[at - 1].x > key) --at;
    while (at < pts.size() && pts[at].x <= key) ++at;
    return at;
}

}  // namespace

// The maximum is taken without scanning every point (that scan, O(points) a sample, was half of
// a simulated trial's time), and it is the same maximum: only points within r of x (+ 1 nm; the
// |dx| <= r test decides) are looked at, the block of the last answer (`hint`) first, and a block
// is skipped when no point of it can beat the best so far. Three bounds rule a block out, each
// an upper bound on every point's computed height: its highest point plus the whole radius
// (sqrt(r * r - d * d) <= sqrt(r * r) = `reach_max` for every point's d, rounding being
// monotone; a run of blocks goes the same way in one test), the circle resting on the block's
// line (line_bound, with its allowance for rounding), and its highest point plus the reach at
// its nearest point (`gap`: each step a monotone rounded operation on inputs no smaller than a
// point's own). A maximum does not depend on the order it is taken in, nor on which points were
// skipped for being no higher than it. On seed 002's sloping base most blocks within r lie on
// the lower side, or rise along it under the circle: the line rules those out without a square
// root a point, and the cursor's points within reach are found a step from the last sample's
// instead of by two binary searches (together a fifth of a hand path's time before).
double resting_height(const SurfaceProfile& s, double x, double r, RestingCursor& c) {
    constexpr std::size_t B = SurfaceProfile::kBlock;
    const double margin = 1e-9;  // m
    const double lo_key = x - r - margin, hi_key = x + r + margin;
    std::size_t lo, hi;
    if (c.span_valid) {
        lo = first_not_before(s.pts, lo_key, c.lo);
        hi = first_after(s.pts, hi_key, std::max(c.hi, lo));
    } else {
        const auto by_x = [](const Vec2& q, double v) { return q.x < v; };
        lo = std::lower_bound(s.pts.begin(), s.pts.end(), lo_key, by_x) - s.pts.begin();
        hi = std::upper_bound(s.pts.begin() + lo, s.pts.end(), hi_key, [](double v, const Vec2& q) { return v < q.x; }) -
             s.pts.begin();  // one past the last point with q.x <= x + r + margin
    }
    c.lo = lo, c.hi = hi, c.span_valid = true;
    double best = -1e9;
    std::size_t best_at = c.hint;
    const double reach_max = std::sqrt(r * r);  // m, no smaller than any point's reach
    auto scan = [&](std::size_t a, std::size_t b) {
        for (std::size_t i = a; i < b; ++i) {
            const double dx = s.pts[i].x - x;
            if (std::abs(dx) <= r) {
                const double t = r * r - dx * dx;  // m^2
                if (certainly_below(s.pts[i].y, t, best)) continue;
                const double h = s.pts[i].y + std::sqrt(t);
                if (h > best) best = h, best_at = i;
            }
        }
    };
    if (lo >= hi) return best;
    // First the block that held the last sample's highest point (the hand moves a few um a
    // sample, so it is usually the answer, and the bounds below then skip most blocks).
    const std::size_t hinted = std::clamp(c.hint, lo, hi - 1), first = hinted / B;
    scan(hinted, hinted + 1);  // the last answer's point first: the rest of its block mostly falls below it
    scan(std::max(lo, first * B), std::min(hi, (first + 1) * B));
    // A run's bounds hold for all its points, so they rule out the first run too, though it starts
    // before the points within reach (its blocks, one by one, were a third of the tests).
    for (std::size_t k = lo / B; k * B < hi; ++k) {
        if ((k % SurfaceProfile::kRun == 0 || k == lo / B) &&
            (s.run_top[k / SurfaceProfile::kRun] + reach_max <= best || line_rules_out(s.run_line[k / SurfaceProfile::kRun], x, r, best))) {
            k = (k / SurfaceProfile::kRun + 1) * SurfaceProfile::kRun - 1;  // the whole run is too low (the hint's block included: it was scanned)
            continue;
        }
        if (k == first || s.block_top[k] + reach_max <= best) continue;
        const std::size_t a = std::max(lo, k * B), b = std::min(hi, (k + 1) * B);
        // Every point of a block is at least `gap` from x (the same rounded subtraction as its dx), so
        // none rises above the block's top + sqrt(r^2 - gap^2).
        const double gap = s.pts[b - 1].x < x ? x - s.pts[b - 1].x : s.pts[a].x > x ? s.pts[a].x - x : 0.0;  // m
        if (gap > r) continue;  // every point of the block fails the scan's |dx| <= r
        if (line_rules_out(s.block_line[k], x, r, best)) continue;
        const double t = r * r - gap * gap;  // m^2
        if (certainly_below(s.block_top[k], t, best) || s.block_top[k] + std::sqrt(t) <= best) continue;
        scan(a, b);
    }
    c.hint = best_at;
    return best;
}

double resting_height(const SurfaceProfile& s, double x, double r, std::size_t& hint) {
    RestingCursor c;
    c.hint = hint;
    const double h = resting_height(s, x, r, c);
    hint = c.hint;
    return h;
}

}  // namespace contactlab::experiments
