// live_servo.hpp — the haptic servo running while the editor is open: drivers' ServoLoop paced by
// drivers' ServoRunner (the one deadline loop: absolute deadlines, SCHED_FIFO when granted, pinned
// to the servo's CPU) against a device (the mouse by default). The UI publishes parameters and
// scenes and reads the lock-free snapshot; every tick is also pushed through an SPSC ring that the
// UI drains for its plots (and, when recording, forwards to the record writer's ring).
//
// Emergency stop: engage_stop() makes the servo thread disconnect the tick at its next boundary
// (output zero from that tick on, the device's drive zeroed) and stay there; release_stop()
// re-arms it (the safety gate then waits for a small force and ramps in).
// stop() ends with one disconnected tick, so the device's last command is zero force: switching
// device or rate (a new LiveServo) always goes zero force -> close -> open -> arm -> ramp in.
#pragma once

#include "drivers/servo_loop.hpp"
#include "drivers/servo_runner.hpp"
#include "drivers/tick_record.hpp"
#include "haptics/servo_params_check.hpp"
#include "haptics/servo_tick.hpp"
#include "haptics/spsc_ring.hpp"

#include <atomic>
#include <memory>
#include <string>

namespace contactlab::editor {

// Splits the CPUs between the renderer and the servo: the calling thread (and every thread it
// creates afterwards: the Vulkan driver's, the window system's) keeps all allowed CPUs but the
// last, which is returned for the servo thread. -1 (nothing changed) with fewer than two CPUs.
int reserve_servo_core();

class LiveServo final : private drivers::TickBoundaryHook {
public:
    // rate: Hz. The device must outlive the servo.
    LiveServo(drivers::Device& device, double rate, const ServoParams& params);
    ~LiveServo() override;
    LiveServo(const LiveServo&) = delete;
    LiveServo& operator=(const LiveServo&) = delete;

    // Opens the device and starts the thread (pinned to `core` when >= 0); false (with
    // device().fault()) if the device fails to open.
    bool start(int core = -1);
    // Zero force on the device (one disconnected tick), thread joined, device closed.
    void stop();
    bool running() const { return runner_ && runner_->running(); }

    // "" when published; otherwise why the servo refused them (servo_params_check.hpp).
    std::string publish_params(const ServoParams& p) { return tick_.publish_params(p); }
    // What publish_params(p) would refuse, without publishing ("" when it would be accepted).
    std::string params_problem(const ServoParams& p) const { return servo_params_problem(p, tick_.config()); }
    // Builds the servo's scene (environment, proxy) here, off the servo thread, and hands it over.
    void publish_scene(const Scene& scene);
    void reclaim() { tick_.scenes().reclaim(); }
    ServoSnapshot snapshot() const { return tick_.snapshot(); }
    void clear_fault() { tick_.request_clear_fault(); }
    // Before start(): the proxy's history from the servo this one replaces (ServoTick::seed_proxy).
    void seed_proxy(Vec2 proxy, double phi) { tick_.seed_proxy(proxy, phi); }

    void engage_stop() { stop_requested_.store(true, std::memory_order_release); }
    void release_stop() { stop_requested_.store(false, std::memory_order_release); }
    bool stopped() const { return stop_requested_.load(std::memory_order_acquire); }

    // Records of the ticks since the last call (UI thread only).
    bool pop_record(drivers::TickRecord& out) { return ring_.try_pop(out); }
    std::uint64_t dropped_records() const { return loop_.dropped_records(); }
    double rate() const { return rate_; }        // Hz
    double period() const { return 1.0 / rate_; }  // s
    // What the OS granted the servo thread, e.g. "SCHED_FIFO priority 80" (set once started).
    std::string scheduling() const { return runner_ ? runner_->scheduling() : std::string("not started"); }
    drivers::Device& device() { return device_; }
    const drivers::Device& device() const { return device_; }
    std::uint64_t overruns() const { return runner_ ? runner_->overruns() : 0; }

private:
    void before_tick(drivers::ServoLoop& loop) noexcept override;

    drivers::Device& device_;
    double rate_;
    ServoTick tick_;
    SpscRing<drivers::TickRecord> ring_;
    drivers::ServoLoop loop_;
    std::unique_ptr<drivers::ServoRunner> runner_;
    std::atomic<bool> stop_requested_{false};
    bool stopped_ = false;  // servo thread only: the stop is in effect
    bool closed_ = false;   // stop() has run (the device is closed once)
};

}  // namespace contactlab::editor
