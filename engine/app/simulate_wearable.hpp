// simulate_wearable.hpp — `contactlab simulate --device sim-wearable --task wearable-step |
// wearable-bandwidth | curvature-arc`: seed 003's experiments on the simulated wearable platform
// (drivers/sim/wearable_tasks.hpp), in virtual time, with a CSV and optionally a JSON summary.
#pragma once

#include "engine/app/simulate_command.hpp"

#include <string>

namespace contactlab::app {

// True for the task names this runs.
bool is_wearable_task(const std::string& task);

// Runs it; prints a summary to stderr. Throws BadInput for bad options or a scene without an arc.
int run_wearable_task(const SimulateOptions& o);

}  // namespace contactlab::app
