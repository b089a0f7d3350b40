// text.hpp — small labels drawn as pixel-aligned rectangles from stb_easy_font's built-in stroke
// font (Debian libstb-dev): no font file, no texture, deterministic. Kept out of golden images.
#pragma once

#include "engine/render/draw_list.hpp"

#include <string>

namespace contactlab::render {

// Draws `text` with its top-left corner at `origin` (px, rounded to whole pixels), each font unit
// `scale` px (an integer keeps edges crisp). The font is about 7 units tall, 6 wide per character.
void draw_text(DrawList& out, P2 origin, const std::string& text, Color color, int scale = 1);
// Width and height (px) the text would take at `scale`.
P2 text_size(const std::string& text, int scale = 1);

}  // namespace contactlab::render
