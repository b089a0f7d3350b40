// timer_floor.hpp — what the machine itself allows a deadline loop: a bare loop with no work,
// waiting as the servo waits (SCHED_FIFO when granted, pinned to the servo's CPU, asleep to
// `spin_ns` before each deadline, then polling the clock), and how late it starts each period.
// The servo cannot start its ticks more punctually than this; on the shared development VM the
// floor is the cause of most of the 10 kHz overruns (`contactlab bench`, "servo beside renderer").
#pragma once

#include <cstdint>

namespace contactlab::bench {

struct TimerFloor {
    std::uint64_t ticks = 0;
    std::uint64_t missed = 0;  // periods it started a whole period or more late: an overrun with no work
    double late_p50 = 0.0, late_p99 = 0.0, late_max = 0.0;  // s after the deadline
};

// `ticks` periods at `rate` (Hz) on `core` (-1: wherever), polling the last `spin_ns` (ns) of each
// wait (0: asleep to the deadline). Allocates before its first period only.
TimerFloor timer_floor(int core, double rate, std::uint64_t ticks, long spin_ns);

}  // namespace contactlab::bench
