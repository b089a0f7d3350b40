// servo_loop.cpp — device adapter, virtual-time runner, fixed-length real-time run (see
// servo_loop.hpp; the deadline loop itself is servo_runner.cpp).
#include "drivers/servo_loop.hpp"

#include <sched.h>

#include "haptics/wearable/contact_display.hpp"
#include "drivers/servo_runner.hpp"

#include <algorithm>
#include <cmath>

namespace contactlab::drivers {

ServoConfig servo_config_for(const Device& dev, double rate) {
    const DeviceLimits lim = dev.limits();
    ServoConfig c;
    c.period = 1.0 / rate;
    c.device_max_force = lim.max_force;
    c.axis_max = lim.axis_max_force;
    c.device_damping = lim.damping;
    // N s/m: no more than the device's own damping b (the controller at most doubles it, moving the
    // sampled spring's bound from 2 b / T to about 4 b / T), and never near a sampled damper's
    // ringing bound 2 m / T. A larger cap made the controller's damper a relay on the encoders'
    // one-count steps (at 10 kHz one count per tick reads as 0.18 m/s): it faulted the block
    // task well inside the bound.
    c.max_damping = std::min(lim.mass / c.period, lim.damping);
    c.has_roller = dev.capabilities().roller;
    c.roller_travel = {lim.roller_min, lim.roller_max};
    return c;
}

ServoLoop::ServoLoop(Device& dev, ServoTick& tick, double period, SpscRing<TickRecord>* ring)
    : dev_(dev), tick_(tick), period_(period), ring_(ring) {}

bool ServoLoop::start() {
    if (!dev_.open()) return false;
    start_opened();
    return true;
}

void ServoLoop::start_opened() {
    platform_ = dev_.capabilities().platform;  // known after open (a hapio board says its model)
    DeviceReading r;
    dev_.read(r);
    tick_.connect(r.t);
}

void ServoLoop::step(double wall_period, bool wait_for_ring) noexcept {
    // Profiled stages (set_profile): off, the clock is never read and `spare` takes the laps.
    ServoLoopStages spare;
    ServoLoopStages& stages = profile_ ? *profile_ : spare;
    StageClock clock;
    clock.start(profile_ != nullptr);
    const bool ok = dev_.read(reading_);
    ServoInput in;
    in.t = reading_.t;
    in.finger = reading_.finger;
    in.phi = reading_.phi;
    in.roller_l = reading_.roller_l;
    in.device_fault = !ok || !reading_.valid || dev_.state() == DeviceState::fault;
    clock.lap(stages.device);
    const ServoCommand& c = tick_.tick(in);
    clock.lap(stages.tick);
    command_.force = c.force;
    command_.roller_drive = c.roller_drive;
    command_.roller_target = c.roller_target;
    if (platform_) {
        // Seed 003's platform renders no force on the finger: it shows the contact under the pad,
        // tilted to the surface and pressed with the force (haptics/wearable/contact_display.hpp).
        const wearable::PlatformPoseCommand p = wearable::contact_to_platform(c.force.x, c.force.y, in.phi);
        command_.platform_mode = p.contact ? DeviceCommand::PlatformMode::pose : DeviceCommand::PlatformMode::none;
        command_.platform = {p.press, p.roll, p.pitch};
    }
    dev_.write(command_);
    dev_.set_engaged(tick_.state() == ServoState::engaged || tick_.state() == ServoState::ramping);
    ++ticks_;
    clock.lap(stages.device);

    if (ring_ != nullptr || records_ != nullptr) {
        const ProxyOutput& o = tick_.proxy_output();
        TickRecord spare;
        TickRecord& rec = records_ != nullptr ? records_->emplace_back() : spare;
        rec.tick = ticks_;
        rec.t = in.t;
        rec.period = wall_period;
        rec.finger = in.finger;
        rec.phi = in.phi;
        rec.roller_l = in.roller_l;
        rec.proxy = o.proxy;
        rec.contact = o.contact;
        rec.depth = o.depth;
        rec.force = c.force;
        rec.l_d = o.l_d;
        rec.roller_target = c.roller_target;
        rec.roller_drive = c.roller_drive;
        rec.energy = tick_.energy_terms();
        rec.observer_energy = tick_.observer().energy();
        rec.observer_margin = tick_.observer().margin();
        rec.observer_used = tick_.observer().used();
        rec.state = tick_.state();
        rec.fault = tick_.fault();
        if (records_ == nullptr && !ring_->try_push(rec)) {
            if (wait_for_ring) {
                while (!ring_->try_push(rec)) std::this_thread::yield();
            } else {
                dropped_.fetch_add(1, std::memory_order_relaxed);
            }
        }
    }
    clock.lap(stages.records);
    dev_.advance(period_);
    clock.lap(stages.device);
}

void ServoLoop::run_virtual(std::uint64_t ticks) noexcept {
    for (std::uint64_t k = 0; k < ticks; ++k) step(period_, true);
}

void ServoLoop::stall(double seconds) noexcept {
    const long n = std::lround(seconds / period_);
    for (long k = 0; k < n; ++k) dev_.advance(period_);
}

PeriodStats::PeriodStats() : bins_(static_cast<std::size_t>(20e-3 / kBin) + 1, 0) {}

void PeriodStats::add(double s) noexcept {
    const std::size_t i = std::min(bins_.size() - 1, static_cast<std::size_t>(std::max(0.0, s) / kBin));
    ++bins_[i];
    ++count_;
    sum_ += s;
    max_ = std::max(max_, s);
}

double PeriodStats::percentile(double p) const {
    if (count_ == 0) return 0.0;
    const double want = p / 100.0 * static_cast<double>(count_);
    std::uint64_t acc = 0;
    for (std::size_t i = 0; i < bins_.size(); ++i) {
        acc += bins_[i];
        if (static_cast<double>(acc) >= want) return (static_cast<double>(i) + 0.5) * kBin;
    }
    return max_;
}

RealtimeReport run_realtime(ServoLoop& loop, std::uint64_t ticks, int fifo_priority) {
    // The one deadline loop (servo_runner.hpp), here for a fixed number of ticks.
    RealtimeReport rep;
    rep.rate = 1.0 / loop.period();
    RunnerOptions opt;
    opt.fifo_priority = fifo_priority;
    opt.lock_memory = true;
    opt.max_ticks = ticks;
    // The editor's split: the last CPU for the servo alone (this thread and any it starts keep
    // off it meanwhile), which also lets the runner poll the end of each wait there.
    cpu_set_t saved;
    CPU_ZERO(&saved);
    const bool have_saved = sched_getaffinity(0, sizeof saved, &saved) == 0;
    opt.core = reserve_servo_core();
    ServoRunner runner(loop, opt);
    runner.start();
    runner.join();
    if (have_saved) sched_setaffinity(0, sizeof saved, &saved);
    rep.scheduling = runner.scheduling();
    rep.memory_lock = runner.memory_lock();
    rep.overruns = runner.overruns();
    const PeriodStats& stats = runner.stats();
    rep.ticks = runner.ticks();
    rep.p50 = stats.percentile(50.0);
    rep.p99 = stats.percentile(99.0);
    rep.max = stats.max();
    rep.mean = stats.mean();
    return rep;
}

}  // namespace contactlab::drivers
