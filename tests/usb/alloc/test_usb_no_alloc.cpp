// test_usb_no_alloc.cpp — the servo tick against a real USB device (hapio through libusb, board
// emulated with umockdev) allocates nothing, takes no lock and does no I/O: the USB work stays on
// the transport thread. Allocation, mutex, write(2) and ioctl(2) calls are counted only on the
// servo thread (thread_local flag), since the event thread and umockdev legitimately do all four.
#include "hapio_emulator.hpp"
#include "sim_fixture.hpp"
#include "usb_fixture.hpp"

#include "drivers/servo_loop.hpp"
#include "drivers/usb/hapio_device.hpp"

#include <doctest/doctest.h>

#include <atomic>
#include <cstdarg>
#include <cstdlib>
#include <dlfcn.h>
#include <new>
#include <pthread.h>
#include <thread>

namespace {
thread_local bool t_counting = false;
std::atomic<long> g_allocs{0}, g_locks{0}, g_io{0};
template <class F>
F next_symbol(const char* name) { return reinterpret_cast<F>(dlsym(RTLD_NEXT, name)); }
}  // namespace

extern "C" int pthread_mutex_lock(pthread_mutex_t* m) {
    if (t_counting) g_locks.fetch_add(1);
    static auto real = next_symbol<int (*)(pthread_mutex_t*)>("pthread_mutex_lock");
    return real(m);
}
extern "C" ssize_t write(int fd, const void* buf, size_t n) {
    if (t_counting) g_io.fetch_add(1);
    static auto real = next_symbol<ssize_t (*)(int, const void*, size_t)>("write");
    return real(fd, buf, n);
}
extern "C" int ioctl(int fd, unsigned long request, ...) {
    if (t_counting) g_io.fetch_add(1);
    va_list ap;
    va_start(ap, request);
    void* arg = va_arg(ap, void*);
    va_end(ap);
    static auto real = next_symbol<int (*)(int, unsigned long, void*)>("ioctl");
    return real(fd, request, arg);
}
void* operator new(std::size_t n) {
    if (t_counting) g_allocs.fetch_add(1);
    if (void* p = std::malloc(n ? n : 1)) return p;
    throw std::bad_alloc();
}
void* operator new[](std::size_t n) { return operator new(n); }
// GCC 12 sees free() in operator delete and warns of a new/free mismatch; here every operator new
// is malloc, so free is the match.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"
void operator delete(void* p) noexcept { std::free(p); }
#pragma GCC diagnostic pop
void operator delete[](void* p) noexcept { operator delete(p); }
void operator delete(void* p, std::size_t) noexcept { operator delete(p); }
void operator delete[](void* p, std::size_t) noexcept { operator delete(p); }

using namespace contactlab;
using namespace contactlab::drivers;
using namespace contactlab::test;

TEST_CASE("servo ticks against a USB device allocate nothing, lock nothing and do no I/O") {
    HapioEmulator emu;
    hapio::HapioOptions o;
    o.stale_after = 0.2;
    hapio::HapioDevice dev(o);
    ServoParams p;
    p.safety.watchdog_timeout = 0.2;
    ServoTick servo(servo_config_for(dev, 1000.0), p);
    servo.scenes().publish(std::make_unique<ServoScene>(floor_scene(1000.0)));
    ServoLoop loop(dev, servo, 1e-3);
    const double R = Scene{}.finger.radius;
    emu.set_encoders(counts_at(o.calibration, Vec2{0.0, 0.05}));
    REQUIRE(loop.start());
    auto step_until = [&](auto done) {
        for (int i = 0; i < 5000 && !done(); ++i) {
            loop.step(1e-3, false);
            std::this_thread::sleep_for(std::chrono::microseconds(900));
        }
        return done();
    };
    REQUIRE(step_until([&] { return servo.state() == ServoState::engaged; }));
    emu.set_encoders(counts_at(o.calibration, Vec2{0.0, R - 0.001}));
    REQUIRE(step_until([&] { return servo.snapshot().force.y > 0.9; }));

    const std::uint64_t frames0 = dev.stats().frames;
    for (int i = 0; i < 2000; ++i) {
        t_counting = true;
        loop.step(1e-3, false);
        t_counting = false;
        std::this_thread::sleep_for(std::chrono::microseconds(500));
    }
    CHECK(g_allocs.load() == 0);
    CHECK(g_locks.load() == 0);
    CHECK(g_io.load() == 0);
    CHECK(dev.stats().frames > frames0 + 500);  // the transport kept streaming meanwhile
    CHECK(servo.snapshot().force.y > 0.9);       // and the ticks were real ones, in contact
}
