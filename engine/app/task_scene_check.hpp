// task_scene_check.hpp — `simulate --task contour-block` refuses a scene that is not seed 000's
// block: the task's hand path is drawn for the block's geometry (drivers/tasks.hpp), and on any
// other scene it runs through empty space or solid and prints figures that mean nothing.
#pragma once

#include "drivers/tasks.hpp"
#include "haptics/scene.hpp"

namespace contactlab::app {

// Throws BadInput naming the first probe the scene fails: the block's top along y = 0 from the
// start line (x = -d - 1 cm) to the edge at x = 0 with solid below, and its far face at x = 0
// down past the finish line (6 cm below the top) with solid on the left. Probes sit 1 mm either
// side of each surface, so the block may be wider, deeper or longer than scenes/block.json.
void check_block_task_scene(const Scene& scene, const drivers::BlockTaskParams& task);

}  // namespace contactlab::app
