// servo_beside_renderer.hpp — `contactlab bench`'s "servo beside renderer" figure (issue 15): the
// real-time servo's period at 1 kHz alone, then with the renderer drawing 1280x720 frames as fast
// as it can on the other cores, in one process, as the editor runs them.
//
// The servo is the one deadline loop (drivers/servo_runner.hpp: SCHED_FIFO when granted, pinned to
// the last CPU, the one the editor reserves) on sim-cld running seed 000's block task. The
// Both at 1 kHz and at 10 kHz. The
// renderer is the offscreen path (scene -> draw list -> lavapipe or a GPU -> read back) with its
// threads kept off the servo's CPU, as in the editor. What is left out is the editor's window:
// under Xvfb the X server's frame copies are a third party the editor moves off the servo's CPU
// itself (engine/editor/x_server_affinity.hpp); its figure is the editor's exit line.
#pragma once

#include "engine/bench/timer_floor.hpp"

#include <cstdint>
#include <string>

namespace contactlab::bench {

struct ServoPeriodFigures {
    std::uint64_t ticks = 0;
    std::uint64_t overruns = 0;             // ticks that started a period or more late
    double p50 = 0.0, p99 = 0.0, max = 0.0;  // s, tick-start to tick-start
};

struct ServoBesideRenderer {
    std::string skipped;     // why nothing was measured; empty when measured
    std::string scheduling;  // what the OS granted the servo thread
    std::string device;      // the renderer's Vulkan device
    double seconds = 0.0;    // s of each phase
    ServoPeriodFigures alone, beside;          // at 1 kHz (seed 000's rate)
    ServoPeriodFigures alone_10k, beside_10k;  // at 10 kHz: a 100 us period, where wake-up latency shows
    // A bare loop at 10 kHz on the servo's CPU, waiting as the servo waits, with nothing drawing:
    // how punctually this machine starts a period at all (timer_floor.hpp).
    TimerFloor floor_10k;
    std::uint64_t frames = 0;  // rendered during the "beside" phase
    double fps = 0.0;
};

// quick: 2 s a phase; full: 5 s (5,000 ticks, the window). Never throws: a machine
// with one CPU or no Vulkan device gets `skipped` with the reason.
ServoBesideRenderer servo_beside_renderer(bool quick);

}  // namespace contactlab::bench
