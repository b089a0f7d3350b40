// stimuli.cpp — the seeds' stimuli as scenes (see stimuli.hpp).
#include "haptics/stimuli.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace contactlab {
namespace {

// splitmix64: tiny, well mixed, and identical on every platform.
struct Random {
    std::uint64_t state;
    std::uint64_t next() {
        std::uint64_t z = (state += 0x9E3779B97F4A7C15ull);
        z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
        z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
        return z ^ (z >> 31);
    }
    double uniform(double lo, double hi) {  // [lo, hi), 53 random bits
        return lo + (hi - lo) * static_cast<double>(next() >> 11) * 0x1.0p-53;
    }
};

void require(bool ok, const std::string& what) {
    if (!ok) throw std::invalid_argument(what);
}

// Bump profile at control point i of 10: a raised sine, 0 at both ends, scaled so the two middle
// control points sit at the nominal height.
double bump_profile(int i) {
    const double peak = std::pow(std::sin(kPi * 4.0 / 9.0), 2.0);
    return std::pow(std::sin(kPi * i / 9.0), 2.0) / peak;
}

Contour polyline_contour(const std::vector<Vec2>& pts) {
    Contour c;
    for (std::size_t i = 0; i + 1 < pts.size(); ++i) c.segments.push_back(LineSegment{pts[i], pts[i + 1]});
    return c;
}

}  // namespace

GeneratedScene generate_bumps(const BumpsDef& d) {
    require(d.small_bumps >= 0 && d.large_bumps >= 0 && d.small_bumps + d.large_bumps <= 16,
            "--small/--large: between 0 and 16 bumps in all");
    require(std::isfinite(d.length) && d.length >= 0.02 && d.length <= 2.0, "--length: must lie in [0.02, 2] m");
    require(std::isfinite(d.base_span) && d.base_span >= 0.0 && d.base_span <= 1.0,
            "--base-span: must lie in [0, 1] m");
    require(std::isfinite(d.sample_step) && d.sample_step >= 1e-4 && d.sample_step <= 0.01,
            "--step: must lie in [0.0001, 0.01] m");
    Random rng{d.seed};
    GeneratedScene out;

    // Base shape: sum of 20 sinusoids (seed 002 eq. 1), then shifted and scaled so that over the
    // traced length it spans base_span vertically, starting at y = 0.
    struct Wave {
        double amplitude, frequency, phase, offset;
    };
    Wave waves[20];
    for (Wave& w : waves)
        w = {rng.uniform(0.10, 0.20), rng.uniform(3.0, 6.0), rng.uniform(0.0, kTwoPi), rng.uniform(-0.20, 0.20)};
    auto raw = [&](double x) {
        double y = 0.0;
        for (const Wave& w : waves) y += w.amplitude * std::sin(kTwoPi * w.frequency * x + w.phase) + w.offset;
        return y;
    };
    const int samples = static_cast<int>(std::floor(d.length / d.sample_step + 1e-9));
    // raw() at each sample x = i * sample_step, kept: the envelope below asks for the same x
    // again (20 sines a value; the same argument gives the same bits).
    std::vector<double> raw_at(static_cast<std::size_t>(samples) + 1);
    for (int i = 0; i <= samples; ++i) raw_at[static_cast<std::size_t>(i)] = raw(i * d.sample_step);
    double lo = raw_at[0], hi = lo;  // raw(0.0): 0 * sample_step is 0.0
    for (const double y : raw_at) {
        lo = std::min(lo, y);
        hi = std::max(hi, y);
    }
    const double scale = hi > lo ? d.base_span / (hi - lo) : 0.0;
    const double y0 = (raw_at[0] - lo) * scale;
    auto base = [&](double x) { return (raw(x) - lo) * scale - y0; };
    auto base_at = [&](int i) { return (raw_at[static_cast<std::size_t>(i)] - lo) * scale - y0; };

    // Bumps: shuffled sizes, each preceded by a random gap; all must fit in the traced length.
    std::vector<bool> large(static_cast<std::size_t>(d.small_bumps), false);
    large.insert(large.end(), static_cast<std::size_t>(d.large_bumps), true);
    for (std::size_t i = large.size(); i > 1; --i) {
        const std::size_t j = static_cast<std::size_t>(rng.next() % i);
        const bool tmp = large[i - 1];
        large[i - 1] = large[j];
        large[j] = tmp;
    }
    // Gaps (seed 002: 15-57 mm) lie between consecutive bumps; the group is placed at a random
    // offset with at least 1 cm of base at both ends. Draws that do not fit are redrawn (the same
    // seed always redraws the same way), up to a limit.
    constexpr double kMargin = 0.01;  // m
    double total = 0.0;
    std::vector<double> widths, gaps;
    for (int attempt = 0; attempt < 200; ++attempt) {
        widths.clear();
        gaps.clear();
        total = 0.0;
        for (std::size_t i = 0; i < large.size(); ++i) {
            if (i > 0) gaps.push_back(rng.uniform(d.min_spacing, d.max_spacing));
            widths.push_back(rng.uniform(d.min_width, d.max_width));
            total += widths.back() + (i > 0 ? gaps.back() : 0.0);
        }
        if (total <= d.length - 2.0 * kMargin) break;
    }
    require(total <= d.length - 2.0 * kMargin,
            "bumps do not fit in --length " + std::to_string(d.length) + " m: fewer bumps or a longer stimulus");
    double x = rng.uniform(kMargin, d.length - kMargin - total);
    for (std::size_t i = 0; i < large.size(); ++i) {
        if (i > 0) x += gaps[i - 1];
        out.bumps.push_back({x, widths[i], large[i] ? d.large_height : d.small_height, static_cast<bool>(large[i])});
        x += widths[i];
    }

    // Polygonal envelope: base samples outside the bumps, 10 control points across each bump.
    std::size_t next_bump = 0;
    for (int i = 0; i <= samples; ++i) {
        const double xs = i * d.sample_step;
        while (next_bump < out.bumps.size() && xs >= out.bumps[next_bump].start) {
            const BumpPlacement& b = out.bumps[next_bump];
            for (int k = 0; k < 10; ++k) {
                const double xb = b.start + b.width * k / 9.0;
                out.envelope.push_back({xb, base(xb) + b.height * bump_profile(k)});
            }
            ++next_bump;
        }
        const bool inside = std::any_of(out.bumps.begin(), out.bumps.end(), [&](const BumpPlacement& b) {
            return xs >= b.start - 1e-12 && xs <= b.start + b.width + 1e-12;
        });
        if (!inside) out.envelope.push_back({xs, base_at(i)});
    }
    // Drop points closer than 0.1 mm to the previous one (a sample next to a bump's end point).
    std::vector<Vec2> env;
    for (const Vec2& p : out.envelope)
        if (env.empty() || p.x - env.back().x > 1e-4) env.push_back(p);
    out.envelope = env;

    // Seed 002 eq. 2: a quadratic Bezier from the midpoint of AB, pulled by B, to the midpoint
    // of BC; the chain starts and ends with half an edge as a line.
    Contour c;
    const auto& P = out.envelope;
    const Vec2 first_mid = 0.5 * (P[0] + P[1]);
    c.segments.push_back(LineSegment{P[0], first_mid});
    for (std::size_t i = 1; i + 1 < P.size(); ++i)
        c.segments.push_back(QuadSegment{0.5 * (P[i - 1] + P[i]), P[i], 0.5 * (P[i] + P[i + 1])});
    c.segments.push_back(LineSegment{0.5 * (P[P.size() - 2] + P.back()), P.back()});
    out.scene.contours.push_back(c);
    return out;
}

Scene generate_block(double d, double drop, double floor) {
    require(std::isfinite(d) && d >= 0.01 && d <= 0.5, "--d: must lie in [0.01, 0.5] m (seed 000: 0.04 to 0.10)");
    require(std::isfinite(drop) && drop > 0.0 && drop <= 1.0, "--drop: must lie in (0, 1] m");
    Scene s;
    s.contours.push_back(polyline_contour({{-(d + 0.10), 0.0}, {0.0, 0.0}, {0.0, -drop}, {floor, -drop}}));
    return s;
}

Scene generate_arc(double chord, double height, double margin) {
    require(std::isfinite(chord) && chord >= 0.01 && chord <= 1.0, "--chord: must lie in [0.01, 1] m");
    require(std::isfinite(height) && height > 0.0 && height <= 0.5 * chord,
            "--height: must lie in (0, chord / 2] m");
    // Circle through (-c/2, 0), (0, h), (c/2, 0): radius r, centre (0, h - r).
    const double r = arc_cap_radius(chord, height);
    const double half = std::asin(std::clamp(0.5 * chord / r, -1.0, 1.0));
    const double a0 = 0.5 * kPi + half, a1 = 0.5 * kPi - half;  // clockwise over the top: convex
    const Vec2 center{0.0, height - r};
    Scene s;
    Contour c;
    const Vec2 left = center + r * unit_at(a0), right = center + r * unit_at(a1);
    c.segments.push_back(LineSegment{{left.x - margin, left.y}, left});
    c.segments.push_back(ArcSegment{center, r, a0, a1});
    c.segments.push_back(LineSegment{right, {right.x + margin, right.y}});
    s.contours.push_back(c);
    return s;
}

}  // namespace contactlab
