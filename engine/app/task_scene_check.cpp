// task_scene_check.cpp — see task_scene_check.hpp.
#include "engine/app/task_scene_check.hpp"

#include "engine/app/subcommands.hpp"
#include "haptics/verify/solid_reference.hpp"

#include <cstdio>

namespace contactlab::app {

void check_block_task_scene(const Scene& scene, const drivers::BlockTaskParams& task) {
    const verify::SolidReference ref(scene);
    constexpr double kSide = 1e-3;  // m: probes this far inside and outside each surface
    auto expect = [&](Vec2 p, bool solid, const char* what) {
        if (ref.inside(p) == solid) return;
        char buf[400];
        std::snprintf(buf, sizeof buf,
                      "--task contour-block: the scene is not seed 000's block (scenes/block.json, `contactlab generate "
                      "block`): %s, but (%.3f, %.3f) m is %s",
                      what, p.x, p.y, solid ? "free space" : "inside a solid");
        throw BadInput(buf);
    };
    const double start = -task.d - 0.01;  // m: where the hand comes down
    for (const double x : {start, 0.5 * start, -2.0 * kSide}) {
        expect({x, -kSide}, true, "the task presses on a top along y = 0 with solid below, from x = -d - 1 cm to the edge at x = 0");
        expect({x, kSide}, false, "the task comes down onto a top along y = 0 from free space above");
    }
    for (const double y : {-0.01, -0.5 * task.descent, -task.descent}) {
        expect({-kSide, y}, true, "the task follows a far face at x = 0 down 6 cm with solid on its left");
        expect({kSide, y}, false, "the task follows a far face at x = 0 with free space on its right");
    }
}

}  // namespace contactlab::app
