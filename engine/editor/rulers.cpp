// rulers.cpp — mm rulers (see rulers.hpp).
#include "engine/editor/rulers.hpp"

#include "engine/render/text.hpp"

#include <cmath>
#include <cstdio>

namespace contactlab::editor {

double ruler_step(double px_per_m, double min_px) {
    for (double decade = 1e-6;; decade *= 10.0)
        for (double k : {1.0, 2.0, 5.0})
            if (k * decade * px_per_m >= min_px) return k * decade;
}

namespace {

void label_of(double metres, double step, char* buf, std::size_t n) {
    // As many decimals as the step needs (a 0.5 mm step prints 0.5, 12.5, ...).
    const double mm = metres * 1e3, step_mm = step * 1e3;
    const int decimals = step_mm >= 1.0 ? 0 : static_cast<int>(std::ceil(-std::log10(step_mm) - 1e-9));
    std::snprintf(buf, n, "%.*f", decimals, std::abs(mm) < 0.5 * step_mm ? 0.0 : mm);
}

}  // namespace

void draw_rulers(const render::View& view, float top, const render::Theme& theme, render::DrawList& out) {
    const float w = static_cast<float>(view.width), h = static_cast<float>(view.height);
    const render::Color band = theme.background.with_alpha(215);
    const render::Color ink = theme.legend;
    const double label = ruler_step(view.px_per_m, 90.0);
    const double tick = label / 5.0;
    const Aabb b = view.world_bounds();
    char text[32];

    // Top ruler: x in mm.
    out.fill_rect({0.0f, top}, {w, top + kRulerBand}, band);
    for (long long i = static_cast<long long>(std::ceil(b.lo.x / tick)); i <= static_cast<long long>(std::floor(b.hi.x / tick)); ++i) {
        const float x = std::floor(view.to_px({static_cast<double>(i) * tick, 0.0}).x) + 0.5f;
        const bool major = i % 5 == 0;
        out.line({x, top + kRulerBand - (major ? 9.0f : 4.0f)}, {x, top + kRulerBand}, 1.0f, ink);
        if (major) {
            label_of(static_cast<double>(i) * tick, label, text, sizeof text);
            render::draw_text(out, {x + 3.0f, top + 3.0f}, text, ink, 1);
        }
    }
    // Left ruler: y in mm.
    out.fill_rect({0.0f, top + kRulerBand}, {kRulerBand * 2.2f, h}, band);
    for (long long j = static_cast<long long>(std::ceil(b.lo.y / tick)); j <= static_cast<long long>(std::floor(b.hi.y / tick)); ++j) {
        const float y = std::floor(view.to_px({0.0, static_cast<double>(j) * tick}).y) + 0.5f;
        if (y < top + kRulerBand) continue;
        const bool major = j % 5 == 0;
        out.line({kRulerBand * 2.2f - (major ? 9.0f : 4.0f), y}, {kRulerBand * 2.2f, y}, 1.0f, ink);
        if (major) {
            label_of(static_cast<double>(j) * tick, label, text, sizeof text);
            render::draw_text(out, {3.0f, y - 10.0f}, text, ink, 1);
        }
    }
    render::draw_text(out, {3.0f, top + 3.0f}, "mm", ink, 1);
}

}  // namespace contactlab::editor
