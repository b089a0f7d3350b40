// test_servo_no_alloc.cpp — the editor's servo thread, running for real (drivers' ServoRunner,
// the emergency-stop hook, ServoLoop, ServoTick, the tick ring) against the editor's own devices
// (sim-cld held by the cursor, the mouse), makes no heap allocation, takes no lock and writes
// nothing while it runs in contact. The global operator new/delete and pthread_mutex_lock /
// write / fwrite are replaced in this executable by counters (as tests/servo/test_no_alloc.cpp
// does), counting only while g_counting is set; the test thread only sleeps meanwhile.
#include "engine/editor/cursor_cld_device.hpp"
#include "engine/editor/live_servo.hpp"
#include "engine/editor/mouse_device.hpp"
#include "engine/editor/servo_view.hpp"

#include <doctest/doctest.h>

#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <dlfcn.h>
#include <memory>
#include <new>
#include <pthread.h>
#include <thread>
#include <unistd.h>

namespace {
std::atomic<bool> g_counting{false};
std::atomic<long> g_allocs{0};
std::atomic<long> g_locks{0};
std::atomic<long> g_io{0};
template <class F>
F next_symbol(const char* name) { return reinterpret_cast<F>(dlsym(RTLD_NEXT, name)); }
}  // namespace

extern "C" int pthread_mutex_lock(pthread_mutex_t* m) {
    if (g_counting.load(std::memory_order_relaxed)) g_locks.fetch_add(1, std::memory_order_relaxed);
    static auto real = next_symbol<int (*)(pthread_mutex_t*)>("pthread_mutex_lock");
    return real(m);
}
extern "C" ssize_t write(int fd, const void* buf, size_t n) {
    if (g_counting.load(std::memory_order_relaxed)) g_io.fetch_add(1, std::memory_order_relaxed);
    static auto real = next_symbol<ssize_t (*)(int, const void*, size_t)>("write");
    return real(fd, buf, n);
}
extern "C" size_t fwrite(const void* p, size_t size, size_t n, FILE* f) {
    if (g_counting.load(std::memory_order_relaxed)) g_io.fetch_add(1, std::memory_order_relaxed);
    static auto real = next_symbol<size_t (*)(const void*, size_t, size_t, FILE*)>("fwrite");
    return real(p, size, n, f);
}
void* operator new(std::size_t n) {
    if (g_counting.load(std::memory_order_relaxed)) g_allocs.fetch_add(1, std::memory_order_relaxed);
    if (void* p = std::malloc(n ? n : 1)) return p;
    throw std::bad_alloc();
}
void* operator new[](std::size_t n) { return operator new(n); }
void* operator new(std::size_t n, const std::nothrow_t&) noexcept {
    if (g_counting.load(std::memory_order_relaxed)) g_allocs.fetch_add(1, std::memory_order_relaxed);
    return std::malloc(n ? n : 1);
}
void* operator new[](std::size_t n, const std::nothrow_t& t) noexcept { return operator new(n, t); }
// Every operator new above allocates with malloc, so free is the matching release.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"
void operator delete(void* p) noexcept { std::free(p); }
#pragma GCC diagnostic pop
void operator delete[](void* p) noexcept { operator delete(p); }
void operator delete(void* p, std::size_t) noexcept { operator delete(p); }
void operator delete[](void* p, std::size_t) noexcept { operator delete(p); }

using namespace contactlab;
using namespace contactlab::editor;

namespace {

Scene floor_scene() {
    Scene s;
    Contour c;
    c.segments.push_back(LineSegment{{-0.1, 0.0}, {0.1, 0.0}});  // solid below y = 0
    s.contours.push_back(c);
    return s;
}

// Runs the live servo on `dev` in contact (the pose 4 mm into the floor), counting for `seconds`.
void run_counted(drivers::Device& dev, PoseInput& pose_in, double seconds) {
    const Scene scene = floor_scene();
    const double R = scene.finger.radius;  // m
    LiveServo servo(dev, 1000.0, servo_params_for(scene, RollerGains{}, kMouseWatchdog));
    servo.publish_scene(scene);
    MousePose pose;
    pose.finger = Vec2(0.0, R + 0.005);  // free space first: the gate opens
    pose_in.set_pose(pose);
    REQUIRE(servo.start());
    for (int i = 0; i < 3000 && servo.snapshot().state != ServoState::engaged; ++i)
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
    REQUIRE(servo.snapshot().state == ServoState::engaged);
    pose.finger = Vec2(0.0, R - 0.004);
    pose_in.set_pose(pose);
    for (int i = 0; i < 3000 && !servo.snapshot().contact; ++i) std::this_thread::sleep_for(std::chrono::milliseconds(1));
    REQUIRE(servo.snapshot().contact);
    const std::uint64_t before = servo.snapshot().ticks;
    g_allocs = g_locks = g_io = 0;
    g_counting = true;
    std::this_thread::sleep_for(std::chrono::duration<double>(seconds));
    g_counting = false;
    const ServoSnapshot after = servo.snapshot();
    CHECK(after.contact);
    CHECK(after.ticks - before > static_cast<std::uint64_t>(0.5 * seconds * 1000.0));  // it did run
    CHECK(g_allocs.load() == 0);
    CHECK(g_locks.load() == 0);
    CHECK(g_io.load() == 0);
    servo.stop();
}

}  // namespace

TEST_CASE("the counters see an allocation, a lock and a write (the overrides are in effect)") {
    g_allocs = g_locks = g_io = 0;
    pthread_mutex_t m = PTHREAD_MUTEX_INITIALIZER;
    g_counting = true;
    auto* p = new int(3);
    pthread_mutex_lock(&m);
    (void)!write(-1, "", 0);
    g_counting = false;
    pthread_mutex_unlock(&m);
    delete p;
    CHECK(g_allocs.load() == 1);
    CHECK(g_locks.load() == 1);
    CHECK(g_io.load() == 1);
}

TEST_CASE("editor servo thread with sim-cld in contact: no allocation, lock or write") {
    MousePose start;
    start.finger = Vec2(0.0, 0.031);
    CursorCldDevice dev(CursorCldParams{}, start);
    run_counted(dev, dev, 0.5);
}

TEST_CASE("editor servo thread with the mouse in contact: no allocation, lock or write") {
    MouseDevice dev;
    run_counted(dev, dev, 0.5);
}
