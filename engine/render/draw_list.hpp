// draw_list.hpp — the CPU side of the one drawing path: triangles with per-vertex colour in pixel
// coordinates (origin top-left, y down), grouped into commands the recorder replays in order.
//
// Anti-aliasing is done here, in geometry: every stroke and convex fill gets a 1 px fringe whose
// alpha falls from the shape's alpha to 0, so 1x sampling gives smooth edges and the output is
// bit-stable on lavapipe. Arbitrary (concave, self-overlapping) polygons are filled with the
// stencil: a fan marks the nonzero-winding interior, then a cover quad paints it and clears the
// stencil. Their edges are aliased; the drawer strokes the outline on top.
#pragma once

#include <glm/vec2.hpp>

#include <cstdint>
#include <span>
#include <vector>

namespace contactlab::render {

using P2 = glm::vec2;  // px

// Straight (not premultiplied) alpha, 8 bits per channel.
struct Color {
    uint8_t r = 0, g = 0, b = 0, a = 255;
    Color with_alpha(uint8_t alpha) const { return {r, g, b, alpha}; }
    bool operator==(const Color&) const = default;
};

// Matches the pipeline's vertex input: R32G32_SFLOAT position, R8G8B8A8_UNORM colour (12 bytes).
struct Vertex {
    float x = 0.0f, y = 0.0f;  // px
    Color color;
};
static_assert(sizeof(Vertex) == 12);

enum class DrawKind : uint8_t {
    triangles,     // blended colour
    stencil_mark,  // no colour; stencil += 1 on front faces, -= 1 on back faces
    stencil_cover, // blended colour where stencil != 0, and stencil reset to 0
};

struct DrawCommand {
    DrawKind kind = DrawKind::triangles;
    uint32_t first_index = 0;
    uint32_t index_count = 0;
};

class DrawList {
public:
    DrawList(int width, int height) : width_(width), height_(height) {}

    int width() const { return width_; }
    int height() const { return height_; }
    const std::vector<Vertex>& vertices() const { return vertices_; }
    const std::vector<uint32_t>& indices() const { return indices_; }
    const std::vector<DrawCommand>& commands() const { return commands_; }
    void clear();

    // A polyline `width` px wide (its full visible width, fringe included), miter joins (the
    // miter length is limited to 4 half-widths). Points closer than 1e-3 px are merged.
    void stroke(std::span<const P2> points, bool closed, float width, Color color);
    void line(P2 a, P2 b, float width, Color color);
    // A convex polygon (either orientation) with a 1 px anti-aliased edge.
    void fill_convex(std::span<const P2> points, Color color);
    // A disc of radius r px, its rim flattened to `tolerance_px`.
    void fill_disc(P2 center, float r, Color color, float tolerance_px = 0.1f);
    void stroke_circle(P2 center, float r, float width, Color color, float tolerance_px = 0.1f);
    // An axis-aligned rectangle with hard edges (for pixel-aligned cells; no fringe).
    void fill_rect(P2 lo, P2 hi, Color color);
    // Any polygon, filled by the nonzero rule through the stencil (aliased edges).
    void fill_polygon(std::span<const P2> points, Color color);

private:
    void emit(DrawKind kind, uint32_t first_index);
    uint32_t add_vertex(P2 p, Color c);

    int width_, height_;
    std::vector<Vertex> vertices_;
    std::vector<uint32_t> indices_;
    std::vector<DrawCommand> commands_;
    std::vector<P2> scratch_points_, scratch_normals_;
};

// Drops points of an open polyline (px) while every dropped point stays within `tolerance_px` of
// the chord that replaces it (sleeve fitting, O(n)); the first and last points are kept. Dense
// chains (many segments per pixel) shrink to what the pixels can show.
void simplify_polyline(std::vector<P2>& points, float tolerance_px);

// Points of a circular arc around `center` (px) of radius r (px) from angle a0 to a1 (rad, in the
// pixel frame), chord error at most `tolerance_px`; both ends included.
void arc_points(P2 center, double r, double a0, double a1, double tolerance_px, std::vector<P2>& out);
// The number of chords that keep a circle of radius r px within `tolerance_px` over `sweep` rad.
int arc_chord_count(double r, double sweep, double tolerance_px);

}  // namespace contactlab::render
