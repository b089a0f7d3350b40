// live_servo.cpp — the editor's servo thread (see live_servo.hpp).
#include "engine/editor/live_servo.hpp"

#include <cerrno>
#include <cmath>
#include <cstring>
#include <ctime>
#include <pthread.h>
#include <sched.h>

namespace contactlab::editor {
namespace {

constexpr int kFifoPriority = 80;
constexpr std::size_t kRingCapacity = 1u << 15;  // ticks: 32 s at 1 kHz between UI drains

void add_ns(timespec& t, long ns) {
    t.tv_nsec += ns;
    while (t.tv_nsec >= 1000000000L) {
        t.tv_nsec -= 1000000000L;
        ++t.tv_sec;
    }
}

bool later(const timespec& a, const timespec& b) {
    return a.tv_sec > b.tv_sec || (a.tv_sec == b.tv_sec && a.tv_nsec > b.tv_nsec);
}

double seconds(const timespec& t) { return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec); }

}  // namespace

LiveServo::LiveServo(drivers::Device& device, double rate, const ServoParams& params)
    : device_(device),
      rate_(rate),
      tick_(drivers::servo_config_for(device, rate), params),
      ring_(kRingCapacity),
      loop_(device, tick_, 1.0 / rate, &ring_) {}

LiveServo::~LiveServo() { stop(); }

int reserve_servo_core() {
    cpu_set_t set;
    CPU_ZERO(&set);
    if (sched_getaffinity(0, sizeof set, &set) != 0 || CPU_COUNT(&set) < 2) return -1;
    int last = -1;
    for (int c = 0; c < CPU_SETSIZE; ++c)
        if (CPU_ISSET(c, &set)) last = c;
    CPU_CLR(last, &set);
    if (sched_setaffinity(0, sizeof set, &set) != 0) return -1;
    return last;
}

void LiveServo::publish_scene(const Scene& scene) {
    tick_.scenes().publish(std::make_unique<ServoScene>(scene));
}

bool LiveServo::start(int core) {
    if (running()) return true;
    core_ = core;
    if (!loop_.start()) return false;
    quit_.store(false);
    thread_ = std::thread([this] { run(); });
    return true;
}

void LiveServo::stop() {
    if (!thread_.joinable()) return;
    quit_.store(true, std::memory_order_release);
    thread_.join();
    device_.close();
}

std::string LiveServo::scheduling() const {
    return sched_ready_.load(std::memory_order_acquire) ? scheduling_ : std::string("starting");
}

void LiveServo::run() noexcept {
    // Scheduling: SCHED_FIFO if the system grants it (it usually needs CAP_SYS_NICE or rtprio).
    sched_param sp{};
    sp.sched_priority = kFifoPriority;
    const int err = pthread_setschedparam(pthread_self(), SCHED_FIFO, &sp);
    scheduling_ = err == 0 ? "SCHED_FIFO priority " + std::to_string(kFifoPriority)
                           : std::string("SCHED_OTHER (SCHED_FIFO refused: ") + std::strerror(err) + ")";
    // A core of its own when asked (the renderer keeps to the others: reserve_servo_core()).
    if (core_ >= 0) {
        cpu_set_t set;
        CPU_ZERO(&set);
        CPU_SET(core_, &set);
        const int aerr = pthread_setaffinity_np(pthread_self(), sizeof set, &set);
        scheduling_ += aerr == 0 ? ", pinned to CPU " + std::to_string(core_)
                                 : std::string(", not pinned: ") + std::strerror(aerr);
    }
    sched_ready_.store(true, std::memory_order_release);

    const long period_ns = std::lround(1e9 / rate_);
    timespec next{}, prev{};
    clock_gettime(CLOCK_MONOTONIC, &next);
    prev = next;
    bool stopped = false;
    bool first = true;
    while (!quit_.load(std::memory_order_acquire)) {
        timespec now{};
        clock_gettime(CLOCK_MONOTONIC, &now);
        const double wall = first ? 1.0 / rate_ : seconds(now) - seconds(prev);
        prev = now;
        first = false;

        // Emergency stop at the tick boundary: disconnect (output zero) / re-arm on release.
        const bool want_stop = stop_requested_.load(std::memory_order_acquire);
        if (want_stop && !stopped) tick_.disconnect();
        if (!want_stop && stopped) {
            drivers::DeviceReading r;
            device_.read(r);
            tick_.connect(r.t);
        }
        stopped = want_stop;
        loop_.step(wall, false);  // idle while stopped: zero force, zero roller drive

        // Absolute deadline; a missed one is counted and the schedule re-aligned (no bursts).
        add_ns(next, period_ns);
        timespec after{};
        clock_gettime(CLOCK_MONOTONIC, &after);
        if (later(after, next)) {
            overruns_.fetch_add(1, std::memory_order_relaxed);
            next = after;
        }
        while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &next, nullptr) == EINTR) {
        }
    }
}

}  // namespace contactlab::editor
