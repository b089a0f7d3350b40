// stage_clock.hpp — named stages of a hot path, timed only when asked.
//
// Why: "where does a tick's time go" must be answerable where it is spent (as Box2D's b2Profile
// names the stages of a step), without costing anything when nobody asks. A StageClock that is
// off reads no clock; one that is on reads the monotonic clock once per lap (a vDSO call, no
// lock, no allocation, no system call: allowed in the servo tick) and charges the time since the
// last lap to the named stage.
#pragma once

#include <chrono>

namespace contactlab {

class StageClock {
public:
    // Starts the clock (when `on`).
    void start(bool on) {
        on_ = on;
        if (on_) last_ = std::chrono::steady_clock::now();
    }
    // Adds the time since the last lap (or start) to `stage`, in ns, and starts the next lap.
    void lap(double& stage) {
        if (!on_) return;
        const auto now = std::chrono::steady_clock::now();
        stage += std::chrono::duration<double, std::nano>(now - last_).count();
        last_ = now;
    }
    // Starts the next lap without charging the time since the last one to any stage (work that
    // is not the path's own, such as validation's reference run).
    void skip() {
        if (on_) last_ = std::chrono::steady_clock::now();
    }
    bool on() const { return on_; }

private:
    bool on_ = false;
    std::chrono::steady_clock::time_point last_{};
};

}  // namespace contactlab
