// solid.vert — every ContactLab primitive: 2-D positions in pixels (origin top-left, y down) with a
// straight-alpha RGBA8 colour per vertex. Anti-aliasing is in the geometry (alpha fringes), so the
// shaders only transform and pass the colour through.
#version 450

layout(location = 0) in vec2 in_pos;    // px
layout(location = 1) in vec4 in_color;  // R8G8B8A8_UNORM, straight alpha

layout(push_constant) uniform Push {
    vec2 px_to_ndc;  // (2 / width, 2 / height)
} push;

layout(location = 0) out vec4 out_color;

void main() {
    gl_Position = vec4(in_pos * push.px_to_ndc - vec2(1.0), 0.0, 1.0);
    out_color = in_color;
}
