// render_frames.hpp — the renderer's offscreen frame time inside `contactlab bench` (issue 8:
// "Render frame time"): the whole frame as the editor pays for it, scene -> draw list -> upload,
// record, submit, wait, read back, at 1280x720, for scenes of 10, 1,000 and 100,000 segments.
//
// The scene is the density case's lines (cost_scenes.hpp: one 0.4 m sinusoid cut into N
// segments) with the finger pressed onto it, so the picture and the proxy table show the same
// contour. Device: the context's choice (a GPU if there is one, else lavapipe); its name is
// reported, since a CPU rasteriser's time is not a GPU's.
#pragma once

#include "engine/bench/tick_stats.hpp"

#include <string>
#include <vector>

namespace contactlab::bench {

struct RenderFrameRow {
    int segments = 0;
    TickStats frame;           // ns per whole frame (median, p99, max over `frame.ticks` frames)
    std::size_t triangles = 0;  // in the draw list
};

struct RenderFrameResults {
    std::string device;   // Vulkan device name; empty when skipped
    std::string skipped;  // why nothing was measured (no Vulkan device, ...); empty when measured
    int width = 1280, height = 720;  // px
    std::vector<RenderFrameRow> rows;
};

// quick: 8 frames per size (after one warm-up frame); full: 60. Never throws for a missing or
// failing Vulkan device: the reason goes into `skipped`.
RenderFrameResults render_frame_suite(bool quick);

}  // namespace contactlab::bench
