// live_plot.cpp — the Plots panel's plot (see live_plot.hpp).
#include "engine/editor/live_plot.hpp"

#include "engine/editor/plot_envelope.hpp"

#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace contactlab::editor {
namespace {

constexpr float kAxisWidth = 46.0f;  // px left of the frame for the y ticks' numbers
constexpr float kTitleRow = 14.0f;   // px

const ImU32 kFrame = IM_COL32(40, 44, 52, 255), kGrid = IM_COL32(70, 76, 88, 255), kTrace = IM_COL32(120, 200, 255, 255),
            kText = IM_COL32(200, 205, 215, 255), kDim = IM_COL32(140, 145, 155, 255);

void tick_label(char* buf, std::size_t n, double v) {
    const double a = std::abs(v);
    if (a != 0.0 && (a >= 1e5 || a < 1e-3)) std::snprintf(buf, n, "%.0e", v);
    else std::snprintf(buf, n, "%g", v);
}

}  // namespace

Rect draw_live_plot(const char* id, const std::vector<float>& values, double span_s, double window_s,
                    const LivePlotSpec& spec) {
    ImGui::PushID(id);
    const ImVec2 p0 = ImGui::GetCursorScreenPos();
    const float width = std::max(kAxisWidth + 20.0f, ImGui::GetContentRegionAvail().x);
    ImGui::Dummy(ImVec2(width, kLivePlotHeight));
    ImDrawList* dl = ImGui::GetWindowDrawList();

    float lo = spec.lo, hi = spec.hi;
    if (std::isnan(lo) || std::isnan(hi)) {
        float dlo = 0.0f, dhi = 1.0f;
        value_range(values, dlo, dhi);
        if (std::isnan(lo)) lo = dlo;
        if (std::isnan(hi)) hi = dhi;
        if (!(hi > lo)) hi = lo + 1.0f;
    }
    // Title row: name (unit) at the left, the newest value at the right.
    char buf[64];
    std::snprintf(buf, sizeof buf, "%s (%s)", spec.title, spec.unit);
    dl->AddText(ImVec2(p0.x, p0.y), kText, buf);
    const float now = values.empty() ? 0.0f : values.back();
    std::snprintf(buf, sizeof buf, "now %.4g %s", now, spec.unit);
    dl->AddText(ImVec2(p0.x + width - ImGui::CalcTextSize(buf).x, p0.y), kText, buf);

    // Frame, y ticks and their grid lines.
    const ImVec2 f0(p0.x + kAxisWidth, p0.y + kTitleRow), f1(p0.x + width, p0.y + kLivePlotHeight);
    dl->AddRectFilled(f0, f1, kFrame);
    const float fh = f1.y - f0.y, fw = f1.x - f0.x;
    const auto y_of = [&](double v) { return f1.y - static_cast<float>((v - lo) / (hi - lo)) * fh; };
    const float text_h = ImGui::GetTextLineHeight();
    for (double t : nice_ticks(lo, hi, 3)) {
        const float y = y_of(t);
        dl->AddLine(ImVec2(f0.x, y), ImVec2(f1.x, y), kGrid);
        dl->AddLine(ImVec2(f0.x - 4.0f, y), ImVec2(f0.x, y), kDim);
        tick_label(buf, sizeof buf, t);
        const float ty = std::clamp(y - 0.5f * text_h, f0.y - 2.0f, f1.y - text_h + 2.0f);
        dl->AddText(ImVec2(f0.x - 6.0f - ImGui::CalcTextSize(buf).x, ty), kDim, buf);
    }
    // Time axis: a mark each second back from now (the right edge).
    for (int k = 0; k <= static_cast<int>(window_s); ++k) {
        const float x = f1.x - static_cast<float>(k / window_s) * fw;
        dl->AddLine(ImVec2(x, f1.y - 4.0f), ImVec2(x, f1.y), kDim);
    }
    // The trace: each column from its min to its max (at least one pixel), clipped to the frame.
    dl->PushClipRect(f0, f1, true);
    const int columns = std::max(1, static_cast<int>(fw));
    // Values spanning less than the window (just after a start) keep their time: they fill its
    // right part, not the whole width.
    const double fill = window_s > 0.0 ? std::clamp(span_s / window_s, 0.0, 1.0) : 1.0;
    const int used = std::max(1, static_cast<int>(std::lround(columns * fill)));
    const std::vector<ColumnRange> env = column_envelope(values, used);
    for (int c = 0; c < used; ++c) {
        const ColumnRange& r = env[static_cast<std::size_t>(c)];
        if (r.empty) continue;
        const float x = f0.x + static_cast<float>(columns - used + c) + 0.5f;
        const float ya = y_of(r.hi), yb = y_of(r.lo);
        dl->AddLine(ImVec2(x, ya - 0.5f), ImVec2(x, std::max(yb, ya + 1.0f) + 0.5f), kTrace, 1.0f);
    }
    dl->PopClipRect();
    ImGui::PopID();
    return Rect{p0.x, p0.y, width, kLivePlotHeight};
}

Rect draw_time_axis(double window_s) {
    const ImVec2 p0 = ImGui::GetCursorScreenPos();
    const float width = std::max(kAxisWidth + 20.0f, ImGui::GetContentRegionAvail().x);
    ImGui::Dummy(ImVec2(width, kTimeAxisHeight));
    ImDrawList* dl = ImGui::GetWindowDrawList();
    const float x0 = p0.x + kAxisWidth, fw = width - kAxisWidth;
    char buf[32];
    for (int k = 0; k <= static_cast<int>(window_s); ++k) {
        if (k == 0) std::snprintf(buf, sizeof buf, "now");
        else std::snprintf(buf, sizeof buf, "-%d s", k);
        const float tw = ImGui::CalcTextSize(buf).x;
        const float x = std::clamp(x0 + fw - static_cast<float>(k / window_s) * fw - 0.5f * tw, p0.x, p0.x + width - tw);
        dl->AddText(ImVec2(x, p0.y), kDim, buf);
    }
    return Rect{p0.x, p0.y, width, kTimeAxisHeight};
}

}  // namespace contactlab::editor
