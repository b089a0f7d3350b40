// surface_profile.cpp — resting heights of a circle on a sampled contour (surface_profile.hpp).
#include "engine/experiments/protocol/surface_profile.hpp"

#include <algorithm>
#include <cmath>

namespace contactlab::experiments {

SurfaceProfile profile_of(std::vector<Vec2> pts) {
    std::sort(pts.begin(), pts.end(), [](const Vec2& a, const Vec2& b) { return a.x < b.x; });
    SurfaceProfile p;
    p.block_top.assign((pts.size() + SurfaceProfile::kBlock - 1) / SurfaceProfile::kBlock, -1e300);
    for (std::size_t i = 0; i < pts.size(); ++i)
        p.block_top[i / SurfaceProfile::kBlock] = std::max(p.block_top[i / SurfaceProfile::kBlock], pts[i].y);
    p.run_top.assign((p.block_top.size() + SurfaceProfile::kRun - 1) / SurfaceProfile::kRun, -1e300);
    for (std::size_t k = 0; k < p.block_top.size(); ++k)
        p.run_top[k / SurfaceProfile::kRun] = std::max(p.run_top[k / SurfaceProfile::kRun], p.block_top[k]);
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

}  // namespace

// The maximum is taken without scanning every point (that scan, O(points) a sample, was half of
// a simulated trial's time), and it is the same maximum: only points within r of x (+ 1 nm; the
// |dx| <= r test decides) are looked at, the block of the last answer (`hint`) first, and a block
// is skipped when its highest point plus its nearest reach cannot beat the best so far. Rounding
// cannot break that bound: each step of it is a monotone rounded operation on inputs no smaller
// than a point's own. A maximum does not depend on the order it is taken in. Before that, a run
// of blocks (and then a block) whose top plus the whole radius cannot beat the best is passed
// over without a square root: sqrt(r * r - d * d) <= sqrt(r * r) = `reach_max` for every point's
// d, by the same monotonicity. On seed 002's steep base shape most blocks within r lie on the
// lower side and go this way (the square roots had been most of a hand path's time).
double resting_height(const SurfaceProfile& s, double x, double r, std::size_t& hint) {
    constexpr std::size_t B = SurfaceProfile::kBlock;
    const double margin = 1e-9;  // m
    const auto by_x = [](const Vec2& q, double v) { return q.x < v; };
    const std::size_t lo = std::lower_bound(s.pts.begin(), s.pts.end(), x - r - margin, by_x) - s.pts.begin();
    const std::size_t hi = std::lower_bound(s.pts.begin() + lo, s.pts.end(), std::nextafter(x + r + margin, 1e300), by_x) -
                           s.pts.begin();  // one past the last point with q.x <= x + r + margin
    double best = -1e9;
    std::size_t best_at = hint;
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
    // sample, so it is usually the answer, and the bound below then skips most blocks).
    const std::size_t first = std::clamp(hint, lo, hi - 1) / B;
    scan(std::max(lo, first * B), std::min(hi, (first + 1) * B));
    // Every point of a block is at least `gap` from x (the same rounded subtraction as its dx), so
    // none rises above the block's top + sqrt(r^2 - gap^2).
    for (std::size_t k = lo / B; k * B < hi; ++k) {
        if (k % SurfaceProfile::kRun == 0 && s.run_top[k / SurfaceProfile::kRun] + reach_max <= best) {
            k += SurfaceProfile::kRun - 1;  // the whole run is too low (the hint's block included: it was scanned)
            continue;
        }
        if (k == first || s.block_top[k] + reach_max <= best) continue;
        const std::size_t a = std::max(lo, k * B), b = std::min(hi, (k + 1) * B);
        const double gap = s.pts[b - 1].x < x ? x - s.pts[b - 1].x : s.pts[a].x > x ? s.pts[a].x - x : 0.0;  // m
        if (gap > r) continue;  // every point of the block fails the scan's |dx| <= r
        const double t = r * r - gap * gap;  // m^2
        if (certainly_below(s.block_top[k], t, best) || s.block_top[k] + std::sqrt(t) <= best) continue;
        scan(a, b);
    }
    hint = best_at;
    return best;
}

}  // namespace contactlab::experiments
