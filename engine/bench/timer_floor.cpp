// timer_floor.cpp — a bare deadline loop's lateness (timer_floor.hpp).
#include "engine/bench/timer_floor.hpp"

#include <algorithm>
#include <cmath>
#include <ctime>
#include <pthread.h>
#include <sched.h>
#include <thread>
#include <vector>

namespace contactlab::bench {
namespace {

std::int64_t now_ns() {
    timespec t{};
    clock_gettime(CLOCK_MONOTONIC, &t);
    return static_cast<std::int64_t>(t.tv_sec) * 1000000000LL + t.tv_nsec;
}

timespec to_timespec(std::int64_t ns) {
    timespec t{};
    t.tv_sec = static_cast<time_t>(ns / 1000000000LL);
    t.tv_nsec = static_cast<long>(ns % 1000000000LL);
    return t;
}

}  // namespace

TimerFloor timer_floor(int core, double rate, std::uint64_t ticks, long spin_ns) {
    TimerFloor f;
    if (!(rate > 0.0) || ticks == 0) return f;
    std::vector<std::int64_t> late(ticks);  // ns after each deadline
    std::thread t([&] {
        // As the servo's thread asks (drivers/servo_runner.cpp): refusals leave it as it is.
        sched_param sp{};
        sp.sched_priority = 80;
        pthread_setschedparam(pthread_self(), SCHED_FIFO, &sp);
        if (core >= 0) {
            cpu_set_t set;
            CPU_ZERO(&set);
            CPU_SET(core, &set);
            pthread_setaffinity_np(pthread_self(), sizeof set, &set);
        }
        const std::int64_t period = std::llround(1e9 / rate);
        std::int64_t next = now_ns() + period;
        for (std::uint64_t k = 0; k < ticks; ++k) {
            const timespec wake = to_timespec(next - spin_ns);
            while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &wake, nullptr) != 0) {
            }
            std::int64_t t_now = now_ns();
            while (t_now < next) t_now = now_ns();
            late[k] = t_now - next;
            next += period;
            if (t_now >= next) {  // a whole period late: re-aligned, as the runner does
                ++f.missed;
                next = t_now + period;
            }
        }
    });
    t.join();
    f.ticks = ticks;
    std::sort(late.begin(), late.end());
    f.late_p50 = 1e-9 * static_cast<double>(late[ticks / 2]);
    f.late_p99 = 1e-9 * static_cast<double>(late[std::min<std::uint64_t>(ticks - 1, ticks * 99 / 100)]);
    f.late_max = 1e-9 * static_cast<double>(late.back());
    return f;
}

}  // namespace contactlab::bench
