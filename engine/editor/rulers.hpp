// rulers.hpp — millimetre rulers along the canvas's top edge (below the menu bar) and left
// edge: a tick at every grid step, a label in mm at every labelled step (1, 2 or 5 x 10^k mm, at
// least 90 px apart).
#pragma once

#include "engine/render/draw_list.hpp"
#include "engine/render/theme.hpp"
#include "engine/render/view.hpp"

namespace contactlab::editor {

inline constexpr float kRulerBand = 20.0f;  // px: thickness of each ruler

// Label step (m) for a zoom of px_per_m: the smallest 1/2/5 x 10^k mm at least `min_px` apart.
double ruler_step(double px_per_m, double min_px);

// Draws both rulers; the top one starts at `top` px (under the menu bar).
void draw_rulers(const render::View& view, float top, const render::Theme& theme, render::DrawList& out);

}  // namespace contactlab::editor
