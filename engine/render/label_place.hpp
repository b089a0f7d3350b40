// label_place.hpp — free places for the canvas's text labels (the wearable's tension values, the
// contact frame's "t", "n" and name). A label goes to the first of its candidate places that lies
// inside the visible canvas (the image less the editor's panels: FrameContent's insets) and
// covers no other text and no mark (a stroke, an arrow, a disc: anything that shows data); when
// no candidate is free it is left out and named in `dropped`, never printed over something. The
// marks are registered as they are drawn, the labels placed after every mark is known.
//
// The same rule the report charts follow (chart.hpp: labels placed, never stacked); here the marks
// run at any angle, so a box is tested against each stroke as a thick segment, not a box.
#pragma once

#include "engine/render/draw_list.hpp"

#include <string>
#include <vector>

namespace contactlab::render {

struct LabelBox {
    P2 lo{0.0f}, hi{0.0f};  // px, top-left origin
    bool intersects(const LabelBox& o) const { return lo.x < o.hi.x && o.lo.x < hi.x && lo.y < o.hi.y && o.lo.y < hi.y; }
};

// A drawn line of `half_width` px each side of a -> b (a disc: a == b, half_width its radius).
struct LabelStroke {
    P2 a{0.0f}, b{0.0f};
    float half_width = 0.0f;
};

struct LabelMarks {
    LabelBox area{{0.0f, 0.0f}, {0.0f, 0.0f}};  // where text may go (the visible canvas)
    std::vector<LabelBox> texts;      // text already there: the legend's, then each placed label
    std::vector<LabelStroke> strokes; // data marks
    std::vector<std::string> placed;  // labels drawn, in order (for tests and messages)
    std::vector<std::string> dropped; // labels left out: no free place

    void add_stroke(P2 a, P2 b, float width) { strokes.push_back({a, b, 0.5f * width}); }
    void add_polyline(const std::vector<P2>& points, bool closed, float width);
    void add_disc(P2 c, float r) { strokes.push_back({c, c, r}); }
    // Whether `box` lies in the area and clears every text box and stroke by `clearance` px.
    bool free(const LabelBox& box, float clearance) const;
};

// Clearance (px) a label keeps from marks and other text: stroke edges are antialiased over ~1 px.
inline constexpr float kLabelClearance = 2.0f;

// Top-left corners for a box of `size` px around `anchor`: first toward `toward` (any length),
// then turning away from it both ways, 16 directions, at gaps `gap`, 2, 3.5, 5.5, 8 and 12 gap
// px between the anchor and the box's nearest side.
std::vector<P2> label_candidates(P2 anchor, P2 size, P2 toward, float gap);

// Places `text` (its box `size`) at the first free candidate: records it in `marks` and returns
// true with `at` set, or records it as dropped and returns false.
bool place_label(LabelMarks& marks, const std::string& text, P2 size, const std::vector<P2>& candidates, P2& at);

}  // namespace contactlab::render
