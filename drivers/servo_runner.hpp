// servo_runner.hpp — the one real-time deadline loop: runs ServoLoop::step() on its own thread
// at the loop's period with absolute deadlines (clock_nanosleep TIMER_ABSTIME on
// CLOCK_MONOTONIC), SCHED_FIFO when the system grants it, optionally pinned to one CPU, with
// period statistics and overrun counting. `contactlab simulate --realtime` (run_realtime) and the
// editor's live servo both use it, so there is one definition of "a tick on time".
//
// The thread never allocates, locks or logs per tick: the statistics histogram is allocated by
// the constructor and the scheduling report is written once, before the first tick.
#pragma once

#include "drivers/servo_loop.hpp"

#include <atomic>
#include <cstdint>
#include <string>
#include <thread>

namespace contactlab::drivers {

// Called on the servo thread at every tick boundary, before the step (e.g. the editor's emergency
// stop disconnects or re-arms the tick here). Must not allocate, lock or log.
class TickBoundaryHook {
public:
    virtual ~TickBoundaryHook() = default;
    virtual void before_tick(ServoLoop& loop) noexcept = 0;
};

struct RunnerOptions {
    int fifo_priority = 80;       // SCHED_FIFO priority asked for (refusal is reported, not fatal)
    int core = -1;                // CPU to pin the thread to; -1: leave the affinity alone
    bool lock_memory = false;     // mlockall(MCL_CURRENT | MCL_FUTURE) before the first tick
    std::uint64_t max_ticks = 0;  // stop by itself after this many ticks; 0: until stop()
    // Before the thread exits (stop() or max_ticks), one last tick with the servo disconnected, so
    // the device's last command is zero force and zero roller drive (a stopped runner never leaves
    // a force held on the device).
    bool zero_on_exit = false;
    TickBoundaryHook* hook = nullptr;
    // The last part of each wait (ns) is spent polling the clock instead of asleep. A timer
    // wake-up on the development VM comes 24 us late at the median even for a SCHED_FIFO thread
    // pinned to its own CPU (a bare loop, `contactlab bench`'s "timer floor"), and tens of us
    // more now and then: at 10 kHz that is a quarter of the period gone before the tick starts.
    // Waking 40 us early and polling puts the median start on the deadline (measured: 0.01 us
    // late, p99 8-14 us, against 24 and 50-80 us asleep). Used only on a pinned thread (`core` >=
    // 0: the CPU is the servo's own, so the polling takes nothing from anyone; 4 % of it at
    // 1 kHz), and at most half the period.
    long spin_ns = 40000;
};

// Splits the process's CPUs: removes the last one from the calling thread's affinity (so every
// thread it starts later, a Vulkan driver's included, stays off it) and returns it for
// RunnerOptions::core. -1 (and nothing changed) with fewer than two CPUs.
int reserve_servo_core();

class ServoRunner {
public:
    ServoRunner(ServoLoop& loop, const RunnerOptions& options);
    ~ServoRunner();  // stop()
    ServoRunner(const ServoRunner&) = delete;
    ServoRunner& operator=(const ServoRunner&) = delete;

    // Starts the thread (the loop's device must already be open: ServoLoop::start()).
    void start();
    // Asks the thread to finish after the current tick and joins it.
    void stop();
    // Waits for a max_ticks run to end.
    void join();
    bool running() const { return thread_.joinable() && !done_.load(std::memory_order_acquire); }

    // What the OS granted, e.g. "SCHED_FIFO priority 80, pinned to CPU 1"; "starting" until the
    // thread has set itself up.
    std::string scheduling() const;
    std::string memory_lock() const;
    // Ticks whose next deadline had already passed when they finished (any thread, any time).
    std::uint64_t overruns() const { return overruns_.load(std::memory_order_relaxed); }
    std::uint64_t ticks() const { return ticks_.load(std::memory_order_relaxed); }
    // Tick-start to tick-start periods. Read only once the thread has been joined.
    const PeriodStats& stats() const { return stats_; }

private:
    void run() noexcept;

    ServoLoop& loop_;
    RunnerOptions opt_;
    PeriodStats stats_;
    std::thread thread_;
    std::atomic<bool> quit_{false};
    std::atomic<bool> done_{false};
    std::atomic<bool> sched_ready_{false};
    std::atomic<std::uint64_t> overruns_{0};
    std::atomic<std::uint64_t> ticks_{0};
    std::string scheduling_, memory_lock_;  // written by the thread before sched_ready_
};

}  // namespace contactlab::drivers
