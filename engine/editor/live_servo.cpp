// live_servo.cpp — the editor's servo thread (see live_servo.hpp).
#include "engine/editor/live_servo.hpp"

#include <algorithm>
#include <sched.h>

namespace contactlab::editor {
namespace {

constexpr int kFifoPriority = 80;
constexpr double kRingSeconds = 32.0;  // s of ticks the ring holds between UI drains

std::size_t ring_capacity(double rate) {
    // A power of two at least kRingSeconds of ticks (1 kHz: 32768), at most 2^20 (52 s at 20 kHz).
    const double want = std::min(kRingSeconds * rate, static_cast<double>(1u << 20));
    std::size_t c = 1;
    while (static_cast<double>(c) < want) c <<= 1;
    return c;
}

}  // namespace

LiveServo::LiveServo(drivers::Device& device, double rate, const ServoParams& params)
    : device_(device),
      rate_(rate),
      tick_(drivers::servo_config_for(device, rate), params),
      ring_(ring_capacity(rate)),
      loop_(device, tick_, 1.0 / rate, &ring_) {}

LiveServo::~LiveServo() { stop(); }

int reserve_servo_core() { return drivers::reserve_servo_core(); }

void LiveServo::publish_scene(const Scene& scene) {
    tick_.scenes().publish(std::make_unique<ServoScene>(scene));
}

bool LiveServo::start(int core) {
    if (runner_) return true;
    if (!loop_.start()) return false;
    drivers::RunnerOptions opt;
    opt.fifo_priority = kFifoPriority;
    opt.core = core;
    opt.zero_on_exit = true;
    opt.hook = this;
    runner_ = std::make_unique<drivers::ServoRunner>(loop_, opt);
    runner_->start();
    return true;
}

void LiveServo::stop() {
    if (!runner_ || closed_) return;
    runner_->stop();
    device_.close();
    closed_ = true;
}

void LiveServo::before_tick(drivers::ServoLoop& loop) noexcept {
    // Emergency stop at the tick boundary: disconnect (output zero) / re-arm on release.
    const bool want_stop = stop_requested_.load(std::memory_order_acquire);
    if (want_stop && !stopped_) loop.servo().disconnect();
    if (!want_stop && stopped_) {
        drivers::DeviceReading r;
        loop.device().read(r);
        loop.servo().connect(r.t);
    }
    stopped_ = want_stop;
}

}  // namespace contactlab::editor
