// chart.cpp — chart layout (ranges from the data, room for labels and legend) and drawing into a
// DrawList: grid, reference lines, series clipped to the plot, markers, frame, ticks, legend.
#include "engine/render/chart.hpp"

#include "engine/render/text.hpp"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <string_view>

namespace contactlab::render {
namespace {

constexpr int kTextScale = 2;        // stb_easy_font units -> px: 14 px glyphs, readable in a report
constexpr float kGlyphHeight = 16.f;  // px the visible glyphs take at kTextScale (7-8 font units)
constexpr float kPad = 10.f;          // px between text blocks
constexpr float kTick = 6.f, kMinorTick = 3.f;  // px tick lengths
constexpr float kLegendSwatch = 34.f;  // px of sample line in a legend entry
constexpr float kLegendRow = 24.f;     // px per legend entry
constexpr float kMarkerRadius = 4.5f;  // px
constexpr float kDash = 9.f, kGap = 5.f;  // px dash pattern
const Color kInk{30, 30, 30, 255};
const Color kGrid{222, 222, 222, 255};
const Color kMinorGrid{240, 240, 240, 255};

// ---- ranges --------------------------------------------------------------------------------------
std::string where(const Chart& c, const char* axis) { return "chart \"" + c.title + "\", " + axis + " axis"; }

// The range of one axis: explicit limits, else the drawable data (points whose x and y are both
// drawable, and reference lines across this axis) widened to whole decades or tick steps.
std::pair<double, double> axis_range(const Chart& c, bool is_x) {
    const ChartAxis& a = is_x ? c.x : c.y;
    const char* name = is_x ? "x" : "y";
    if (!a.categories.empty()) {  // one slot per category, whatever the data
        if (a.scale != AxisScale::linear) throw ChartError(where(c, name) + ": a categorical axis cannot be logarithmic");
        return {a.min.value_or(-0.5), a.max.value_or(static_cast<double>(a.categories.size()) - 0.5)};
    }
    const AxisMap probe_x{c.x.scale}, probe_y{c.y.scale};
    const AxisMap& own = is_x ? probe_x : probe_y;
    double lo = INFINITY, hi = -INFINITY;
    for (const ChartSeries& s : c.series)
        for (std::size_t i = 0; i < s.x.size() && i < s.y.size(); ++i)
            if (probe_x.accepts(s.x[i]) && probe_y.accepts(s.y[i])) {
                const double v = is_x ? s.x[i] : s.y[i];
                lo = std::min(lo, v);
                hi = std::max(hi, v);
                // Error bars are data too: the interval must fit in the plot.
                if (!is_x && i < s.y_low.size() && probe_y.accepts(s.y_low[i])) lo = std::min(lo, s.y_low[i]);
                if (!is_x && i < s.y_high.size() && probe_y.accepts(s.y_high[i])) hi = std::max(hi, s.y_high[i]);
            }
    for (const ChartReference& r : c.references)
        if (r.vertical == is_x && own.accepts(r.value)) {
            lo = std::min(lo, r.value);
            hi = std::max(hi, r.value);
        }
    if (a.include_zero && a.scale == AxisScale::linear && lo <= hi) {
        lo = std::min(lo, 0.0);
        hi = std::max(hi, 0.0);
    }
    if (a.min) lo = *a.min;
    if (a.max) hi = *a.max;
    if (!std::isfinite(lo) || !std::isfinite(hi))
        throw ChartError(where(c, name) +
                         ": no drawable point and no explicit range (a point needs finite x and y, positive on a "
                         "log scale)");
    if (a.scale == AxisScale::log10 && (lo <= 0.0 || hi <= 0.0))
        throw ChartError(where(c, name) + ": a log scale needs positive limits");
    if (a.min && a.max) {
        if (!(lo < hi)) throw ChartError(where(c, name) + ": min must be below max");
        return {lo, hi};  // explicit: exactly as asked
    }
    if (a.scale == AxisScale::log10) {
        double l = std::pow(10.0, std::floor(std::log10(lo) + 1e-9));
        double h = std::pow(10.0, std::ceil(std::log10(hi) - 1e-9));
        if (a.min) l = lo;
        if (a.max) h = hi;
        if (!(l < h)) {  // a single decade value: one decade either side
            if (!a.min) l = lo / 10.0;
            if (!a.max) h = hi * 10.0;
        }
        if (!(l < h)) throw ChartError(where(c, name) + ": min must be below max");
        // A reference line on the frame's edge reads as the frame (the bench's 1 ms line, a whole
        // decade, sat on the top edge): out to the next minor tick (2 or 5 x 10^k) beyond it.
        for (const ChartReference& r : c.references) {
            if (r.vertical != is_x) continue;
            if (!a.max && r.value == h) h *= 2.0;
            if (!a.min && r.value == l) l /= 2.0;
        }
        return {l, h};
    }
    if (!(lo < hi)) {  // one value: a unit (or 10 %) either side
        const double d = lo == 0.0 ? 1.0 : 0.1 * std::abs(lo);
        if (!a.min) lo -= d;
        if (!a.max) hi += d;
        if (!(lo < hi)) throw ChartError(where(c, name) + ": min must be below max");
    }
    // Out to whole tick steps, so the frame ends on labelled ticks.
    const std::vector<ChartTick> ticks = axis_ticks(AxisMap{AxisScale::linear, lo, hi, 0.0, 1.0});
    const double step = ticks.size() >= 2 ? ticks[1].value - ticks[0].value : hi - lo;
    double l = a.min ? lo : std::floor(lo / step + 1e-9) * step;
    double h = a.max ? hi : std::ceil(hi / step - 1e-9) * step;
    // ... and a reference line on the frame's edge: one step beyond it (as on a log axis).
    for (const ChartReference& r : c.references) {
        if (r.vertical != is_x) continue;
        if (!a.max && r.value == h) h += step;
        if (!a.min && r.value == l && !(a.include_zero && l == 0.0)) l -= step;
    }
    return {l, h};
}

// ---- drawing helpers -----------------------------------------------------------------------------
float text_w(const std::string& s) { return text_size(s, kTextScale).x; }

void text_at(DrawList& out, P2 p, const std::string& s, Color c) { draw_text(out, p, s, c, kTextScale); }

constexpr float kDescender = 4.f;  // px below the glyphs' baseline that g, j, p, q, y and , reach

bool descends(char c) { return std::string_view("gjpqy,;").find(c) != std::string_view::npos; }

// The whole text's box, for placing it: its width, and its glyphs' height (with descenders when
// it has any).
ChartBox text_box(P2 p, const std::string& s) {
    const bool any = std::any_of(s.begin(), s.end(), descends);
    return {p, p + P2(text_w(s), kGlyphHeight + (any ? kDescender : 0.f))};
}

// Text drawn and recorded in the layout's boxes, one box per glyph (text_size's line box is a
// third taller than the glyphs, and an axis title's descender beside a tick label is not text
// on text).
void text_logged(DrawList& out, ChartLayout& l, P2 p, const std::string& s, Color c) {
    text_at(out, p, s, c);
    for (std::size_t i = 0; i < s.size(); ++i) {
        if (s[i] == ' ') continue;
        const float x0 = p.x + text_w(s.substr(0, i)), x1 = p.x + text_w(s.substr(0, i + 1)) - 1.f;
        l.text_boxes.push_back({P2(x0, p.y), P2(std::max(x1, x0 + 1.f), p.y + kGlyphHeight + (descends(s[i]) ? kDescender : 0.f))});
    }
}

// The first of `candidates` for text `s` that stays inside the plot and overlaps no text or
// mark already in the layout; false when none does.
bool place(const ChartLayout& l, const std::string& s, const std::vector<P2>& candidates, P2& at) {
    for (const P2& p : candidates) {
        const ChartBox b = text_box(p, s);
        if (b.lo.x < l.plot_lo.x || b.lo.y < l.plot_lo.y || b.hi.x > l.plot_hi.x || b.hi.y > l.plot_hi.y) continue;
        // 1 px clear of other text and marks.
        const ChartBox g{b.lo - P2(1.f), b.hi + P2(1.f)};
        auto hit = [&](const ChartBox& o) { return g.intersects(o); };
        if (std::any_of(l.text_boxes.begin(), l.text_boxes.end(), hit) || std::any_of(l.mark_boxes.begin(), l.mark_boxes.end(), hit))
            continue;
        at = p;
        return true;
    }
    return false;
}

// Liang-Barsky: clips segment a-b to the rectangle; false if nothing is left.
bool clip(P2& a, P2& b, P2 lo, P2 hi) {
    double t0 = 0.0, t1 = 1.0;
    const double dx = b.x - a.x, dy = b.y - a.y;
    const double p[4] = {-dx, dx, -dy, dy};
    const double q[4] = {a.x - lo.x, hi.x - a.x, a.y - lo.y, hi.y - a.y};
    for (int i = 0; i < 4; ++i) {
        if (p[i] == 0.0) {
            if (q[i] < 0.0) return false;
            continue;
        }
        const double t = q[i] / p[i];
        if (p[i] < 0.0) t0 = std::max(t0, t);
        else t1 = std::min(t1, t);
        if (t0 > t1) return false;
    }
    const P2 a0 = a;
    a = a0 + static_cast<float>(t0) * (b - a0);
    b = a0 + static_cast<float>(t1) * (b - a0);
    return true;
}

// A polyline stroked solid or in dashes (kDash on, kGap off, carried across corners).
void stroke_run(DrawList& out, const std::vector<P2>& run, bool dashed, float width, Color color) {
    if (run.size() < 2) return;
    if (!dashed) {
        out.stroke(run, false, width, color);
        return;
    }
    // The pattern is walked in double precision with each step at least kMinStep long: in float,
    // a dash's last sliver (phase a hair under kDash) added to a position hundreds of px along
    // rounded back to the same position, and the walk never advanced.
    constexpr double kPeriod = double(kDash) + double(kGap);  // px
    constexpr double kMinStep = 1e-3;                          // px
    double phase = 0.0;  // px into the current dash+gap period
    for (std::size_t i = 0; i + 1 < run.size(); ++i) {
        const P2 a = run[i], b = run[i + 1];
        const double len = glm::length(glm::dvec2(b) - glm::dvec2(a));
        if (!(len > 0.0)) continue;
        const glm::dvec2 dir = (glm::dvec2(b) - glm::dvec2(a)) / len;
        double s = 0.0;
        while (s < len) {
            const bool on = phase < kDash;
            const double left = std::max(kMinStep, on ? kDash - phase : kPeriod - phase);
            const double e = std::min(len, s + left);
            if (on) out.line(P2(glm::dvec2(a) + dir * s), P2(glm::dvec2(a) + dir * e), width, color);
            phase += e - s;
            if (phase >= kPeriod - kMinStep) phase = 0.0;
            s = e;
        }
    }
}

void draw_marker(DrawList& out, Marker m, P2 c, Color color) {
    const float r = kMarkerRadius;
    switch (m) {
    case Marker::none: return;
    case Marker::disc: out.fill_disc(c, r, color); return;
    case Marker::square: {
        const P2 pts[4] = {c + P2(-r, -r), c + P2(r, -r), c + P2(r, r), c + P2(-r, r)};
        out.fill_convex(pts, color);
        return;
    }
    case Marker::triangle: {
        const float s = r * 1.3f;
        const P2 pts[3] = {c + P2(0.f, -s), c + P2(s * 0.87f, s * 0.5f), c + P2(-s * 0.87f, s * 0.5f)};
        out.fill_convex(pts, color);
        return;
    }
    case Marker::diamond: {
        const float s = r * 1.3f;
        const P2 pts[4] = {c + P2(0.f, -s), c + P2(s, 0.f), c + P2(0.f, s), c + P2(-s, 0.f)};
        out.fill_convex(pts, color);
        return;
    }
    }
}

bool inside(P2 p, P2 lo, P2 hi) {
    return p.x >= lo.x - 0.5f && p.x <= hi.x + 0.5f && p.y >= lo.y - 0.5f && p.y <= hi.y + 0.5f;
}

P2 px(const ChartLayout& l, double x, double y) {
    return P2(static_cast<float>(l.x.to_px(x)), static_cast<float>(l.y.to_px(y)));
}

// The boxes of a series' markers, error bars and line segments (each segment's own bounding
// box, widened by half the line: tight for the short segments of a track or a sampled curve),
// as draw_series draws them.
void add_marks(ChartLayout& l, const ChartSeries& s) {
    constexpr float kCap = 5.f, kHalf = kMarkerRadius * 1.3f;  // the widest marker's half size
    bool have_prev = false;
    P2 prev{};
    for (std::size_t i = 0; i < s.x.size(); ++i) {
        if (!l.x.accepts(s.x[i]) || !l.y.accepts(s.y[i])) {
            have_prev = false;
            continue;
        }
        const P2 p = px(l, s.x[i], s.y[i]);
        if (s.connect && have_prev) {
            P2 a = prev, b = p;
            const float h = s.line_width / 2.f + 1.f;
            if (clip(a, b, l.plot_lo, l.plot_hi)) l.mark_boxes.push_back({glm::min(a, b) - P2(h), glm::max(a, b) + P2(h)});
        }
        prev = p;
        have_prev = true;
        if (s.marker != Marker::none && inside(p, l.plot_lo, l.plot_hi)) l.mark_boxes.push_back({p - P2(kHalf), p + P2(kHalf)});
        if (i < s.y_low.size() && l.x.accepts(s.x[i]) && l.y.accepts(s.y_low[i]) && l.y.accepts(s.y_high[i])) {
            P2 a = px(l, s.x[i], s.y_low[i]), b = px(l, s.x[i], s.y_high[i]);
            if (clip(a, b, l.plot_lo, l.plot_hi)) {
                // The bar (2 px wide) and each cap with a pixel beyond its ink: text touching a
                // cap's end read as one glyph with it ("Tn=24").
                const float y0 = std::min(a.y, b.y), y1 = std::max(a.y, b.y);
                l.mark_boxes.push_back({P2(a.x - 2.f, y0 - 1.f), P2(a.x + 2.f, y1 + 1.f)});
                for (const float y : {y0, y1}) l.mark_boxes.push_back({P2(a.x - kCap - 2.f, y - 2.f), P2(a.x + kCap + 2.f, y + 2.f)});
            }
        }
    }
}

void draw_error_bars(DrawList& out, const ChartLayout& l, const ChartSeries& s) {
    constexpr float kCap = 5.f;  // px either side of the point
    for (std::size_t i = 0; i < s.x.size() && i < s.y_low.size() && i < s.y_high.size(); ++i) {
        if (!l.x.accepts(s.x[i]) || !l.y.accepts(s.y_low[i]) || !l.y.accepts(s.y_high[i])) continue;
        P2 a = px(l, s.x[i], s.y_low[i]), b = px(l, s.x[i], s.y_high[i]);
        const P2 low = a, high = b;
        if (!clip(a, b, l.plot_lo, l.plot_hi)) continue;
        out.line(a, b, 2.f, s.color);
        // Caps only where the bar really ends (not where the plot cut it).
        if (glm::distance(a, low) < 0.5f) out.line(a - P2(kCap, 0.f), a + P2(kCap, 0.f), 2.f, s.color);
        if (glm::distance(b, high) < 0.5f) out.line(b - P2(kCap, 0.f), b + P2(kCap, 0.f), 2.f, s.color);
    }
}

void draw_series(DrawList& out, const ChartLayout& l, const ChartSeries& s) {
    draw_error_bars(out, l, s);
    // Runs of consecutive drawable points, clipped to the plot; a skipped point breaks the line.
    std::vector<P2> run;
    auto flush = [&] {
        stroke_run(out, run, s.dashed, s.line_width, s.color);
        run.clear();
    };
    bool have_prev = false;
    P2 prev{};
    for (std::size_t i = 0; i < s.x.size(); ++i) {
        if (!l.x.accepts(s.x[i]) || !l.y.accepts(s.y[i])) {
            flush();
            have_prev = false;
            continue;
        }
        const P2 p = px(l, s.x[i], s.y[i]);
        if (have_prev && s.connect) {
            P2 a = prev, b = p;
            if (clip(a, b, l.plot_lo, l.plot_hi)) {
                if (run.empty() || a != prev) {
                    flush();
                    run.push_back(a);
                }
                run.push_back(b);
                if (b != p) flush();  // left the plot
            } else {
                flush();
            }
        }
        prev = p;
        have_prev = true;
    }
    flush();
    for (std::size_t i = 0; i < s.x.size(); ++i) {
        if (!l.x.accepts(s.x[i]) || !l.y.accepts(s.y[i])) continue;
        const P2 p = px(l, s.x[i], s.y[i]);
        if (!inside(p, l.plot_lo, l.plot_hi)) continue;
        draw_marker(out, s.marker, p, s.color);
    }
}

// Each point's label in the first free place beside it (chart.hpp), or left out and counted.
void draw_point_labels(DrawList& out, ChartLayout& l, const ChartSeries& s) {
    for (std::size_t i = 0; i < s.x.size() && i < s.labels.size(); ++i) {
        if (s.labels[i].empty() || !l.x.accepts(s.x[i]) || !l.y.accepts(s.y[i])) continue;
        const P2 p = px(l, s.x[i], s.y[i]);
        if (!inside(p, l.plot_lo, l.plot_hi)) continue;
        const float w = text_w(s.labels[i]), r = kMarkerRadius + 3.f;
        P2 at;
        if (place(l, s.labels[i], {p + P2(r, -kMarkerRadius - 12.f), p + P2(-r - w, -kMarkerRadius - 12.f), p + P2(r, 1.f), p + P2(-r - w, 1.f)}, at))
            text_logged(out, l, at, s.labels[i], s.color), ++l.placed_labels;
        else
            ++l.dropped_labels;
    }
}

struct LegendEntry {
    std::string name;
    Color color;
    Marker marker;
    bool dashed;
    float width;
    bool line;  // a sample of the line; false: the marker alone (unconnected series)
};

std::vector<LegendEntry> legend_entries(const Chart& c) {
    std::vector<LegendEntry> e;
    for (const ChartSeries& s : c.series)
        if (!s.name.empty()) e.push_back({s.name, s.color, s.marker, s.dashed, s.line_width, s.connect});
    for (const ChartReference& r : c.references)
        if (!r.label.empty()) e.push_back({r.label, r.color, Marker::none, true, 2.f, true});
    return e;
}

}  // namespace

Color chart_color(int index) {
    static const Color palette[] = {
        {0, 114, 178, 255},   // blue
        {213, 94, 0, 255},    // vermillion
        {0, 158, 115, 255},   // bluish green
        {204, 121, 167, 255}, // reddish purple
        {230, 159, 0, 255},   // orange
        {86, 180, 233, 255},  // sky blue
        {0, 0, 0, 255},       // black
        {180, 160, 0, 255},   // darkened yellow (pure yellow vanishes on white)
    };
    const int n = static_cast<int>(std::size(palette));
    return palette[((index % n) + n) % n];
}

ChartLayout layout_chart(const Chart& c) {
    for (const ChartSeries& s : c.series) {
        if (s.x.size() != s.y.size())
            throw ChartError("chart \"" + c.title + "\", series \"" + s.name + "\": x and y differ in length");
        if (!s.labels.empty() && s.labels.size() != s.x.size())
            throw ChartError("chart \"" + c.title + "\", series \"" + s.name + "\": one label per point, or none");
        if (s.y_low.size() != s.y_high.size() || (!s.y_low.empty() && s.y_low.size() != s.x.size()))
            throw ChartError("chart \"" + c.title + "\", series \"" + s.name + "\": one error bar (low and high) per point, or none");
    }
    ChartLayout l;
    const auto [x0, x1] = axis_range(c, true);
    const auto [y0, y1] = axis_range(c, false);
    l.x = AxisMap{c.x.scale, x0, x1, 0.0, 1.0};
    l.y = AxisMap{c.y.scale, y0, y1, 0.0, 1.0};

    // Room: title and the y axis's title above the plot, tick labels left and below, the x axis's
    // title under those, the legend on the right.
    float y_label_w = 0.f;
    for (const ChartTick& t : axis_ticks(c.y, l.y)) y_label_w = std::max(y_label_w, text_w(t.label));
    float legend_w = 0.f;
    for (const LegendEntry& e : legend_entries(c)) legend_w = std::max(legend_w, text_w(e.name));
    const float left = kPad + std::max(y_label_w + kTick + 6.f, 20.f);
    const float top = kPad + (c.title.empty() ? 0.f : kGlyphHeight + kPad) + kGlyphHeight + kPad;
    const float bottom = kTick + 6.f + kGlyphHeight + kPad + kGlyphHeight + kPad;
    const float right = legend_w > 0.f ? 2 * kPad + kLegendSwatch + 8.f + legend_w + kPad : 2 * kPad;
    l.plot_lo = P2(std::round(left), std::round(top));
    l.plot_hi = P2(std::round(static_cast<float>(c.width) - right), std::round(static_cast<float>(c.height) - bottom));
    if (l.plot_hi.x - l.plot_lo.x < 50.f || l.plot_hi.y - l.plot_lo.y < 50.f)
        throw ChartError("chart \"" + c.title + "\": " + std::to_string(c.width) + "x" + std::to_string(c.height) +
                         " px leaves no room for the plot (labels and legend take the rest)");
    l.x.px_lo = l.plot_lo.x;
    l.x.px_hi = l.plot_hi.x;
    l.y.px_lo = l.plot_hi.y;  // pixel y grows downwards: the low value sits at the bottom
    l.y.px_hi = l.plot_lo.y;
    for (const ChartSeries& s : c.series)
        for (std::size_t i = 0; i < s.x.size(); ++i)
            if (!l.x.accepts(s.x[i]) || !l.y.accepts(s.y[i])) ++l.skipped_points;
    return l;
}

ChartLayout draw_chart(const Chart& c, DrawList& out) {
    ChartLayout l = layout_chart(c);
    const P2 lo = l.plot_lo, hi = l.plot_hi;
    const auto xt = axis_ticks(c.x, l.x), yt = axis_ticks(c.y, l.y);

    // Grid under everything: major lines at labelled ticks, minor ones fainter.
    for (const ChartTick& t : xt) {
        const float x = static_cast<float>(l.x.to_px(t.value));
        out.line(P2(x, lo.y), P2(x, hi.y), 1.f, t.label.empty() ? kMinorGrid : kGrid);
    }
    for (const ChartTick& t : yt) {
        const float y = static_cast<float>(l.y.to_px(t.value));
        out.line(P2(lo.x, y), P2(hi.x, y), 1.f, t.label.empty() ? kMinorGrid : kGrid);
    }
    // Reference lines, labelled at their far end inside the plot.
    for (const ChartReference& r : c.references) {
        const AxisMap& m = r.vertical ? l.x : l.y;
        if (!m.accepts(r.value)) continue;
        const float v = static_cast<float>(m.to_px(r.value));
        if (r.vertical ? (v < lo.x || v > hi.x) : (v < lo.y || v > hi.y)) continue;  // outside an explicit range
        const std::vector<P2> run = r.vertical ? std::vector<P2>{P2(v, hi.y), P2(v, lo.y)}
                                               : std::vector<P2>{P2(lo.x, v), P2(hi.x, v)};
        stroke_run(out, run, true, 2.f, r.color);
    }
    // Every mark first, so that no label is put on a point drawn after it; reference lines are
    // data too (a threshold, a budget).
    for (const ChartSeries& s : c.series) add_marks(l, s);
    for (const ChartReference& r : c.references) {
        const AxisMap& m = r.vertical ? l.x : l.y;
        if (!m.accepts(r.value)) continue;
        const float v = static_cast<float>(m.to_px(r.value));
        if (r.vertical ? (v < lo.x || v > hi.x) : (v < lo.y || v > hi.y)) continue;
        l.mark_boxes.push_back(r.vertical ? ChartBox{P2(v - 2.f, lo.y), P2(v + 2.f, hi.y)} : ChartBox{P2(lo.x, v - 2.f), P2(hi.x, v + 2.f)});
    }
    // Reference labels beside their lines at the top, a row lower when taken; the legend names
    // them anyway, so one with no room is left to it.
    for (const ChartReference& r : c.references) {
        const AxisMap& m = r.vertical ? l.x : l.y;
        if (r.label.empty() || !m.accepts(r.value)) continue;
        const float v = static_cast<float>(m.to_px(r.value)), w = text_w(r.label);
        if (r.vertical ? (v < lo.x || v > hi.x) : (v < lo.y || v > hi.y)) continue;
        std::vector<P2> tries;
        for (int row = 0; row < 6; ++row) {
            const float dy = static_cast<float>(row) * (kGlyphHeight + 6.f);
            if (r.vertical) tries.insert(tries.end(), {P2(v + 4.f, lo.y + 4.f + dy), P2(v - 4.f - w, lo.y + 4.f + dy)});
            else tries.insert(tries.end(), {P2(hi.x - w - 4.f - 3.f * dy, v - kGlyphHeight - 4.f), P2(hi.x - w - 4.f - 3.f * dy, v + 4.f)});
        }
        P2 at;
        if (place(l, r.label, tries, at)) text_logged(out, l, at, r.label, r.color), ++l.placed_labels;
        else ++l.dropped_labels;
    }
    for (const ChartSeries& s : c.series) draw_series(out, l, s);
    for (const ChartSeries& s : c.series) draw_point_labels(out, l, s);

    // Frame, ticks and their labels.
    const P2 frame[4] = {lo, P2(hi.x, lo.y), hi, P2(lo.x, hi.y)};
    out.stroke(frame, true, 1.5f, kInk);
    for (const ChartTick& t : xt) {
        const float x = static_cast<float>(l.x.to_px(t.value));
        out.line(P2(x, hi.y), P2(x, hi.y + (t.label.empty() ? kMinorTick : kTick)), 1.5f, kInk);
        if (!t.label.empty()) text_logged(out, l, P2(x - text_w(t.label) / 2.f, hi.y + kTick + 6.f), t.label, kInk);
    }
    for (const ChartTick& t : yt) {
        const float y = static_cast<float>(l.y.to_px(t.value));
        out.line(P2(lo.x - (t.label.empty() ? kMinorTick : kTick), y), P2(lo.x, y), 1.5f, kInk);
        if (!t.label.empty())
            text_logged(out, l, P2(lo.x - kTick - 6.f - text_w(t.label), y - kGlyphHeight / 2.f), t.label, kInk);
    }
    // Titles: the chart's centred on top, the y axis's above the plot (text does not rotate), the
    // x axis's centred under the tick labels.
    if (!c.title.empty())
        text_logged(out, l, P2((static_cast<float>(c.width) - text_w(c.title)) / 2.f, kPad), c.title, kInk);
    text_logged(out, l, P2(kPad, lo.y - kPad - kGlyphHeight), c.y.title, kInk);
    text_logged(out, l, P2((lo.x + hi.x - text_w(c.x.title)) / 2.f, hi.y + kTick + 6.f + kGlyphHeight + kPad), c.x.title, kInk);

    // Legend right of the plot: a sample of each line (and marker), then its name.
    float y = lo.y + kGlyphHeight / 2.f;
    for (const LegendEntry& e : legend_entries(c)) {
        const float x0 = hi.x + 2 * kPad;
        if (e.line) stroke_run(out, {P2(x0, y), P2(x0 + kLegendSwatch, y)}, e.dashed, e.width, e.color);
        draw_marker(out, e.marker, P2(x0 + kLegendSwatch / 2.f, y), e.color);
        text_logged(out, l, P2(x0 + kLegendSwatch + 8.f, y - kGlyphHeight / 2.f), e.name, kInk);
        y += kLegendRow;
    }
    return l;
}

}  // namespace contactlab::render
