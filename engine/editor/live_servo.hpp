// live_servo.hpp — the haptic servo running while the editor is open: drivers' ServoLoop on its
// own thread at a fixed rate (absolute deadlines, SCHED_FIFO when granted), against a device
// (the mouse by default). The UI publishes parameters and scenes and reads the lock-free
// snapshot; every tick is also pushed through an SPSC ring that the UI drains for its plots.
//
// Emergency stop: engage_stop() makes the servo thread disconnect the tick at its next boundary
// (output zero from that tick on, the device's drive zeroed) and stay there; release_stop()
// re-arms it (the safety gate then waits for a small force and ramps in).
#pragma once

#include "drivers/servo_loop.hpp"
#include "drivers/tick_record.hpp"
#include "haptics/servo_tick.hpp"
#include "haptics/spsc_ring.hpp"

#include <atomic>
#include <memory>
#include <string>
#include <thread>

namespace contactlab::editor {

// Splits the CPUs between the renderer and the servo: the calling thread (and every thread it
// creates afterwards: the Vulkan driver's, the window system's) keeps all allowed CPUs but the
// last, which is returned for the servo thread. -1 (nothing changed) with fewer than two CPUs.
int reserve_servo_core();

class LiveServo {
public:
    // rate: Hz. The device must outlive the servo.
    LiveServo(drivers::Device& device, double rate, const ServoParams& params);
    ~LiveServo();
    LiveServo(const LiveServo&) = delete;
    LiveServo& operator=(const LiveServo&) = delete;

    // Opens the device and starts the thread (pinned to `core` when >= 0); false (with
    // device().fault()) if the device fails to open.
    bool start(int core = -1);
    void stop();
    bool running() const { return thread_.joinable(); }

    void publish_params(const ServoParams& p) { tick_.publish_params(p); }
    // Builds the servo's scene (environment, proxy) here, off the servo thread, and hands it over.
    void publish_scene(const Scene& scene);
    void reclaim() { tick_.scenes().reclaim(); }
    ServoSnapshot snapshot() const { return tick_.snapshot(); }
    void clear_fault() { tick_.request_clear_fault(); }

    void engage_stop() { stop_requested_.store(true, std::memory_order_release); }
    void release_stop() { stop_requested_.store(false, std::memory_order_release); }
    bool stopped() const { return stop_requested_.load(std::memory_order_acquire); }

    // Records of the ticks since the last call (UI thread only).
    bool pop_record(drivers::TickRecord& out) { return ring_.try_pop(out); }
    std::uint64_t dropped_records() const { return loop_.dropped_records(); }
    double period() const { return 1.0 / rate_; }
    // What the OS granted the servo thread, e.g. "SCHED_FIFO priority 80" (set once started).
    std::string scheduling() const;
    drivers::Device& device() { return device_; }
    std::uint64_t overruns() const { return overruns_.load(std::memory_order_relaxed); }

private:
    void run() noexcept;

    drivers::Device& device_;
    double rate_;
    ServoTick tick_;
    SpscRing<drivers::TickRecord> ring_;
    drivers::ServoLoop loop_;
    std::thread thread_;
    std::atomic<bool> quit_{false};
    std::atomic<bool> stop_requested_{false};
    std::atomic<bool> sched_ready_{false};
    std::atomic<std::uint64_t> overruns_{0};
    std::string scheduling_;  // written by the thread before sched_ready_
    int core_ = -1;
};

}  // namespace contactlab::editor
