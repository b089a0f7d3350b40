// servo_loop.hpp — adapts a Device to the servo tick and paces it: in virtual time (no sleeping,
// deterministic) or on a real-time thread (absolute deadlines, SCHED_FIFO when granted, period
// statistics). Both run exactly the same ServoLoop::step().
#pragma once

#include "drivers/device.hpp"
#include "drivers/tick_record.hpp"
#include "haptics/servo_tick.hpp"
#include "haptics/spsc_ring.hpp"
#include "haptics/stage_clock.hpp"

#include <atomic>
#include <cstdint>
#include <string>
#include <thread>
#include <vector>

namespace contactlab::drivers {

// The servo configuration a device's declared limits imply at `rate` (Hz).
ServoConfig servo_config_for(const Device& dev, double rate);

// Wall time (ns) of a step's parts, summed over the steps while set (ServoLoop::set_profile):
// where a simulated study's time goes between the device and the tick
// (engine/experiments/base/trial_profile.hpp). Unset, a step reads no clock.
struct ServoLoopStages {
    double device = 0.0;   // read, write, engage and advance (a simulated device's dynamics)
    double tick = 0.0;     // ServoTick::tick
    double records = 0.0;  // the tick record into the ring
};

class ServoLoop {
public:
    // period: s. `ring` (optional) receives one TickRecord per tick.
    ServoLoop(Device& dev, ServoTick& tick, double period, SpscRing<TickRecord>* ring = nullptr);

    // Opens the device (off the servo thread) and tells the tick it is connected.
    bool start();
    // The same for a device the caller has opened already (to read what it declares, such as its
    // effective mass, before the tick is built): not opened a second time.
    void start_opened();
    // One tick: read -> ServoTick -> write, then (simulations) advance the device by one period.
    // `wall_period` (s) is what gets recorded as the period (virtual time: the nominal one).
    // With `wait_for_ring` a full ring is waited on (virtual time: lose nothing); otherwise the
    // record is dropped and counted (real time: never block).
    void step(double wall_period, bool wait_for_ring) noexcept;
    // Virtual time: `ticks` steps back to back.
    void run_virtual(std::uint64_t ticks) noexcept;

    std::uint64_t ticks() const { return ticks_; }
    std::uint64_t dropped_records() const { return dropped_.load(std::memory_order_relaxed); }
    double period() const { return period_; }
    Device& device() { return dev_; }
    ServoTick& servo() { return tick_; }
    // Test hook: skip the tick but let the device's physics run (a stalled servo).
    void stall(double seconds) noexcept;
    // Sum each step's parts into `stages` (null: stop); five clock reads a step (StageClock).
    void set_profile(ServoLoopStages* stages) { profile_ = stages; }
    // Virtual time on one thread: each step's record is appended to `out` (null: stop) instead of
    // going through the ring, written in place (a simulated trial copied each record three times
    // on its way to its trace). The caller reserves what the steps will append: a step never
    // allocates.
    void record_into(std::vector<TickRecord>* out) { records_ = out; }

private:
    Device& dev_;
    ServoTick& tick_;
    double period_;
    SpscRing<TickRecord>* ring_;
    std::uint64_t ticks_ = 0;
    std::atomic<std::uint64_t> dropped_{0};
    DeviceReading reading_;
    DeviceCommand command_;
    bool platform_ = false;  // the device is seed 003's platform: the force becomes a platform pose
    ServoLoopStages* profile_ = nullptr;
    std::vector<TickRecord>* records_ = nullptr;
};

// Period statistics from a fixed histogram (100 ns bins up to 20 ms): no allocation per tick.
class PeriodStats {
public:
    PeriodStats();
    void add(double seconds) noexcept;
    std::uint64_t count() const { return count_; }
    double percentile(double p) const;  // s
    double max() const { return max_; }  // s
    double mean() const { return count_ ? sum_ / count_ : 0.0; }

private:
    static constexpr double kBin = 100e-9;  // s
    std::vector<std::uint32_t> bins_;
    std::uint64_t count_ = 0;
    double max_ = 0.0, sum_ = 0.0;
};

struct RealtimeReport {
    std::string scheduling;     // what the OS granted, e.g. "SCHED_FIFO priority 80"
    std::string memory_lock;    // mlockall outcome
    std::uint64_t ticks = 0;
    std::uint64_t overruns = 0; // ticks that started after their deadline had passed + 1 period
    double rate = 0.0;          // Hz
    double p50 = 0.0, p99 = 0.0, max = 0.0, mean = 0.0;  // s, tick-start to tick-start
};

// Runs loop.step() on its own thread at the loop's period for `ticks` ticks with absolute
// deadlines (ServoRunner, servo_runner.hpp: the one deadline loop), pinned to the last CPU with
// the calling thread kept off it meanwhile (reserve_servo_core). Blocks until done.
RealtimeReport run_realtime(ServoLoop& loop, std::uint64_t ticks, int fifo_priority = 80);

}  // namespace contactlab::drivers
