// servo_runner.cpp — the real-time deadline loop (see servo_runner.hpp).
#include "drivers/servo_runner.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <ctime>
#include <pthread.h>
#include <sched.h>
#include <sys/mman.h>

namespace contactlab::drivers {
namespace {

double to_seconds(const timespec& t) { return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec); }

void add_ns(timespec& t, long ns) {
    t.tv_nsec += ns;
    while (t.tv_nsec >= 1000000000L) {
        t.tv_nsec -= 1000000000L;
        ++t.tv_sec;
    }
    while (t.tv_nsec < 0) {
        t.tv_nsec += 1000000000L;
        --t.tv_sec;
    }
}

bool later(const timespec& a, const timespec& b) {
    return a.tv_sec > b.tv_sec || (a.tv_sec == b.tv_sec && a.tv_nsec > b.tv_nsec);
}

}  // namespace

ServoRunner::ServoRunner(ServoLoop& loop, const RunnerOptions& options) : loop_(loop), opt_(options) {}

ServoRunner::~ServoRunner() { stop(); }

void ServoRunner::start() {
    if (thread_.joinable()) return;
    quit_.store(false);
    done_.store(false);
    thread_ = std::thread([this] { run(); });
}

void ServoRunner::stop() {
    quit_.store(true, std::memory_order_release);
    join();
}

void ServoRunner::join() {
    if (thread_.joinable()) thread_.join();
    if (opt_.lock_memory) ::munlockall();
}

std::string ServoRunner::scheduling() const {
    return sched_ready_.load(std::memory_order_acquire) ? scheduling_ : std::string("starting");
}

std::string ServoRunner::memory_lock() const {
    return sched_ready_.load(std::memory_order_acquire) ? memory_lock_ : std::string("starting");
}

void ServoRunner::run() noexcept {
    // Set-up (allocates: before the first tick). SCHED_FIFO usually needs CAP_SYS_NICE or rtprio.
    sched_param sp{};
    sp.sched_priority = opt_.fifo_priority;
    const int err = pthread_setschedparam(pthread_self(), SCHED_FIFO, &sp);
    scheduling_ = err == 0 ? "SCHED_FIFO priority " + std::to_string(opt_.fifo_priority)
                           : std::string("SCHED_OTHER (SCHED_FIFO refused: ") + std::strerror(err) + ")";
    if (opt_.core >= 0) {
        cpu_set_t set;
        CPU_ZERO(&set);
        CPU_SET(opt_.core, &set);
        const int aerr = pthread_setaffinity_np(pthread_self(), sizeof set, &set);
        scheduling_ += aerr == 0 ? ", pinned to CPU " + std::to_string(opt_.core)
                                 : std::string(", not pinned: ") + std::strerror(aerr);
    }
    if (opt_.lock_memory) {
        memory_lock_ = ::mlockall(MCL_CURRENT | MCL_FUTURE) == 0 ? "mlockall ok"
                                                                 : std::string("mlockall refused: ") + std::strerror(errno);
    } else {
        memory_lock_ = "memory not locked";
    }
    const long spin_ns = opt_.core >= 0 ? std::clamp(opt_.spin_ns, 0L, std::lround(loop_.period() * 1e9) / 2) : 0;  // ns
    if (spin_ns > 0) scheduling_ += ", the last " + std::to_string(spin_ns / 1000) + " us of each wait polled";
    sched_ready_.store(true, std::memory_order_release);

    const double nominal = loop_.period();  // s
    const long period_ns = std::lround(nominal * 1e9);
    timespec next{}, prev{};
    clock_gettime(CLOCK_MONOTONIC, &next);
    prev = next;
    for (std::uint64_t k = 0; !quit_.load(std::memory_order_acquire) && (opt_.max_ticks == 0 || k < opt_.max_ticks); ++k) {
        timespec now{};
        clock_gettime(CLOCK_MONOTONIC, &now);
        const double period = k == 0 ? nominal : to_seconds(now) - to_seconds(prev);  // s
        prev = now;
        if (k > 0) stats_.add(period);
        if (opt_.hook) opt_.hook->before_tick(loop_);
        loop_.step(period, false);
        ticks_.fetch_add(1, std::memory_order_relaxed);

        // Absolute deadline; a missed one is counted and the schedule re-aligned instead of
        // bursting ticks to catch up (a burst would integrate the device's physics unevenly).
        add_ns(next, period_ns);
        timespec after{};
        clock_gettime(CLOCK_MONOTONIC, &after);
        if (later(after, next)) {
            overruns_.fetch_add(1, std::memory_order_relaxed);
            next = after;
        }
        if (spin_ns > 0) {
            // Asleep to spin_ns before the deadline, then the clock polled up to it.
            timespec wake = next;
            add_ns(wake, -spin_ns);
            while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &wake, nullptr) == EINTR) {
            }
            timespec t{};
            do clock_gettime(CLOCK_MONOTONIC, &t);
            while (later(next, t));
        } else {
            while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &next, nullptr) == EINTR) {
            }
        }
    }
    if (opt_.zero_on_exit) {
        // The safety path on the way out: disconnected, the tick commands zero force and drive.
        loop_.servo().disconnect();
        loop_.step(nominal, false);
    }
    done_.store(true, std::memory_order_release);
}

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

}  // namespace contactlab::drivers
