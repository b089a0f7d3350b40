// matrix_chart.cpp — count matrices as pictures (matrix_chart.hpp).
#include "engine/render/matrix_chart.hpp"

#include "engine/render/chart.hpp"
#include "engine/render/image.hpp"
#include "engine/render/offscreen.hpp"
#include "engine/render/text.hpp"

#include <algorithm>

namespace contactlab::render {
namespace {

constexpr int kScale = 2;         // text scale (stb_easy_font units)
constexpr float kMargin = 16.0f;  // px
const Color kInk{30, 30, 30, 255};

float label_width(const std::vector<std::string>& labels) {
    float w = 0.0f;
    for (const std::string& l : labels) w = std::max(w, text_size(l, kScale).x);
    return w;
}

// px per cell side: the requested size, or wider when a column label needs it ("second" at text
// scale 2 is 56 px: two such labels side by side ran together).
float cell_of(const MatrixChart& m) { return std::max(static_cast<float>(m.cell), label_width(m.columns) + 10.0f); }

// Left and top space before the first cell.
P2 origin(const MatrixChart& m) {
    const float line = text_size("Ag", kScale).y;
    const float left = std::max(label_width(m.rows), text_size(m.row_title, kScale).x + 8.0f);  // the row title sits above the row labels
    return {kMargin + left + 8.0f, kMargin + 2.0f * (line + 8.0f) + line + 8.0f};
}

}  // namespace

P2 matrix_chart_size(const MatrixChart& m) {
    const P2 o = origin(m);
    const float w = o.x + static_cast<float>(m.columns.size()) * cell_of(m) + kMargin;
    const float h = o.y + static_cast<float>(m.rows.size()) * cell_of(m) + kMargin;
    return {std::max(w, text_size(m.title, kScale).x + 2.0f * kMargin), h};
}

void draw_matrix_chart(const MatrixChart& m, DrawList& out) {
    if (m.counts.size() != m.rows.size()) throw ChartError(m.title + ": " + std::to_string(m.counts.size()) + " rows of counts for " +
                                                           std::to_string(m.rows.size()) + " row labels");
    for (const auto& r : m.counts)
        if (r.size() != m.columns.size()) throw ChartError(m.title + ": a row of counts is not as long as the column labels");
    const P2 o = origin(m);
    const float line = text_size("Ag", kScale).y, cell = cell_of(m);
    draw_text(out, {kMargin, kMargin}, m.title, kInk, kScale);
    // Column title and labels above the cells; row title down the left, labels beside the rows.
    draw_text(out, {o.x, kMargin + line + 8.0f}, m.column_title, kInk, kScale);
    for (std::size_t c = 0; c < m.columns.size(); ++c) {
        const P2 size = text_size(m.columns[c], kScale);
        draw_text(out, {o.x + cell * (c + 0.5f) - 0.5f * size.x, o.y - line - 6.0f}, m.columns[c], kInk, kScale);
    }
    draw_text(out, {kMargin, o.y - line - 6.0f}, m.row_title, kInk, kScale);
    for (std::size_t r = 0; r < m.rows.size(); ++r) {
        const P2 size = text_size(m.rows[r], kScale);
        draw_text(out, {o.x - 8.0f - size.x, o.y + cell * (r + 0.5f) - 0.5f * size.y}, m.rows[r], kInk, kScale);
        long total = 0;
        for (long v : m.counts[r]) total += v;
        for (std::size_t c = 0; c < m.columns.size(); ++c) {
            const float share = total > 0 ? static_cast<float>(m.counts[r][c]) / static_cast<float>(total) : 0.0f;
            // White (0) to dark blue (1); the count in white on dark cells.
            const Color fill{static_cast<std::uint8_t>(255 - share * 225), static_cast<std::uint8_t>(255 - share * 175),
                             static_cast<std::uint8_t>(255 - share * 75), 255};
            const P2 lo{o.x + cell * c, o.y + cell * r};
            out.fill_rect(lo, {lo.x + cell, lo.y + cell}, fill);
            const std::string n = std::to_string(m.counts[r][c]);
            const P2 size = text_size(n, kScale);
            draw_text(out, {lo.x + 0.5f * (cell - size.x), lo.y + 0.5f * (cell - size.y)}, n,
                      share > 0.5f ? Color{255, 255, 255, 255} : kInk, kScale);
        }
    }
    // Grid lines over the cells.
    for (std::size_t c = 0; c <= m.columns.size(); ++c)
        out.line({o.x + cell * c, o.y}, {o.x + cell * c, o.y + cell * m.rows.size()}, 1.0f, Color{120, 120, 120, 255});
    for (std::size_t r = 0; r <= m.rows.size(); ++r)
        out.line({o.x, o.y + cell * r}, {o.x + cell * m.columns.size(), o.y + cell * r}, 1.0f, Color{120, 120, 120, 255});
}

void write_matrix_chart_png(const VulkanContext& ctx, const MatrixChart& m, const std::string& path) {
    const P2 size = matrix_chart_size(m);
    const int w = static_cast<int>(size.x), h = static_cast<int>(size.y);
    DrawList list(w, h);
    draw_matrix_chart(m, list);
    OffscreenTarget target(ctx, w, h);
    write_png(path, target.render(list, Color{255, 255, 255, 255}));
}

}  // namespace contactlab::render
