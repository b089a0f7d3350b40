// tasks.hpp — built-in scripted-hand paths.
#pragma once

#include "drivers/hand_path.hpp"
#include "haptics/scene.hpp"

namespace contactlab::drivers {

// Seed 000 Fig. 9: the block's top runs along y = 0 to its far edge at x = 0 (scenes/block.json).
// The hand descends onto the top at x = -d - 1 cm, slides along it toward the edge at `speed`,
// runs `overshoot` past the edge (the contact moves toward the back of the pad: the cue the
// subjects used), tips the finger forward around the corner until the fingertip points down
// (phi = -pi/2), and descends the far face to 6 cm below the top (the finish line). The intended
// path lies `press` inside the surface, so the hand's own stiffness presses the finger on.
struct BlockTaskParams {
    double finger_radius = 0.026;  // m, R
    double d = 0.06;               // m, start line distance from the edge (seed: 4..10 cm)
    double speed = 0.05;           // m/s, hand speed along the path (seed 001: 5 cm/s "fast")
    double press = 0.003;          // m, intended depth below the surface
    double overshoot = 0.006;      // m past the edge before tipping
    double descent = 0.06;         // m down the far face
    // m/s round the corner and down the far face: once the edge is found nothing is left to
    // look for, so a person goes at their free speed; 0: `speed`, as along the top.
    double descent_speed = 0.0;
    double sample_period = 1e-3;   // s
};

HandPath contour_block_task(const BlockTaskParams& p);

// The block the task runs on, as scenes/block.json ships it (d = 6 cm: top along y = 0 from
// x = -0.16 m to the far edge at x = 0, the far face down 10 cm to a floor to x = 0.16 m; R 2.6 cm,
// L 2.0 cm; spring 1000 N/m, 1.5 N, centroid contact rule). Built in code so the bench probes need
// no scene file at run time; a test checks it against the shipped file.
Scene block_scene();

}  // namespace contactlab::drivers
