// Zero heap allocations per tick: the global operator new/delete are replaced in this executable
// by counters that count only while `g_counting` is set. 100,000 ticks of the whole servo path —
// device read, ServoTick (proxy, roller PID, safety, snapshot seqlock), device write, SPSC
// record ring, simulated physics — run in contact on seed 000's block task.
#include "sim_fixture.hpp"

#include <doctest/doctest.h>

#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <dlfcn.h>
#include <new>
#include <pthread.h>
#include <unistd.h>

namespace {
std::atomic<bool> g_counting{false};
std::atomic<long> g_allocs{0};
std::atomic<long> g_frees{0};
std::atomic<long> g_locks{0};  // pthread mutex locks (std::mutex goes through these)
std::atomic<long> g_io{0};     // write(2) / fwrite(3) calls
template <class F>
F next_symbol(const char* name) { return reinterpret_cast<F>(dlsym(RTLD_NEXT, name)); }
}  // namespace

// Interposed: calls from this executable's code (the servo path is linked in statically) land
// here first; counted while g_counting is set, then forwarded to libc.
extern "C" int pthread_mutex_lock(pthread_mutex_t* m) {
    if (g_counting.load(std::memory_order_relaxed)) g_locks.fetch_add(1, std::memory_order_relaxed);
    static auto real = next_symbol<int (*)(pthread_mutex_t*)>("pthread_mutex_lock");
    return real(m);
}
extern "C" int pthread_mutex_trylock(pthread_mutex_t* m) {
    if (g_counting.load(std::memory_order_relaxed)) g_locks.fetch_add(1, std::memory_order_relaxed);
    static auto real = next_symbol<int (*)(pthread_mutex_t*)>("pthread_mutex_trylock");
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
// GCC 12 sees free() inside operator delete and warns of a new/free mismatch; here every operator
// new above allocates with malloc, so free is the matching release.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"
void operator delete(void* p) noexcept {
    if (p && g_counting.load(std::memory_order_relaxed)) g_frees.fetch_add(1, std::memory_order_relaxed);
    std::free(p);
}
#pragma GCC diagnostic pop
void operator delete[](void* p) noexcept { operator delete(p); }
void operator delete(void* p, std::size_t) noexcept { operator delete(p); }
void operator delete[](void* p, std::size_t) noexcept { operator delete(p); }

using namespace contactlab;
using namespace contactlab::test;

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

TEST_CASE("100,000 servo ticks allocate nothing, lock nothing, write nothing") {
    // The block task repeated: descend, slide, tip over the edge, descend; loop the path so the
    // run stays in varied contact for all 100,000 ticks.
    drivers::BlockTaskParams bp;
    const drivers::HandPath one = drivers::contour_block_task(bp);
    std::vector<drivers::PathSample> samples;
    const double len = one.end() + 0.5;
    for (int rep = 0; rep * len < 101.0; ++rep)
        for (const auto& s : one.samples()) samples.push_back({s.t + rep * len, s.x, s.phi});
    SpscRing<drivers::TickRecord> ring(1024);
    Scene scene = load_shipped_scene("block.json");
    drivers::sim::SimCldDevice dev({}, drivers::HandPath(std::move(samples)));
    ServoTick servo(drivers::servo_config_for(dev, 1000.0), ServoParams{});
    servo.scenes().publish(std::make_unique<ServoScene>(scene));
    drivers::ServoLoop loop(dev, servo, 1e-3, &ring);
    REQUIRE(loop.start());
    drivers::TickRecord r;
    // Warm-up tick takes the scene (allocated off-thread above); the proxy's scratch is reserved.
    loop.step(1e-3, false);
    while (ring.try_pop(r)) {}

    g_allocs = g_frees = g_locks = g_io = 0;
    long contact = 0;
    g_counting = true;
    for (int k = 0; k < 100000; ++k) {
        loop.step(1e-3, false);
        while (ring.try_pop(r)) contact += r.contact ? 1 : 0;
        // A parameter edit every second, as the UI would publish it (publishing is also
        // allocation-free; applying it is part of the tick).
        if (k % 1000 == 0) {
            ServoParams p;
            p.stiffness = 800.0 + (k / 1000 % 5) * 100.0;
            servo.publish_params(p);
        }
    }
    g_counting = false;
    CHECK(g_allocs.load() == 0);
    CHECK(g_frees.load() == 0);
    CHECK(g_locks.load() == 0);
    CHECK(g_io.load() == 0);
    CHECK(contact > 50000);  // the ticks measured were mostly in contact
    CHECK(servo.snapshot().fault_count == 0);
}
