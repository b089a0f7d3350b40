// side_effects.cpp — the counting overrides behind side_effects.hpp. Calls from this executable
// (the servo path is linked in statically) land here first; they are counted while counting is on
// for the thread, then forwarded to libc.
#include "side_effects.hpp"

#include <atomic>
#include <cstdarg>
#include <cstdio>
#include <cstdlib>
#include <dlfcn.h>
#include <new>
#include <pthread.h>
#include <unistd.h>

namespace {
std::atomic<bool> g_all{false};
thread_local bool t_this = false;
std::atomic<long> g_allocs{0}, g_frees{0}, g_locks{0}, g_io{0};

bool counting() { return t_this || g_all.load(std::memory_order_relaxed); }
void bump(std::atomic<long>& c) {
    if (counting()) c.fetch_add(1, std::memory_order_relaxed);
}
template <class F>
F next_symbol(const char* name) { return reinterpret_cast<F>(dlsym(RTLD_NEXT, name)); }
}  // namespace

namespace contactlab::test {
void reset_side_effects() { g_allocs = g_frees = g_locks = g_io = 0; }
void count_all_threads(bool on) { g_all.store(on); }
void count_this_thread(bool on) { t_this = on; }
SideEffects side_effects() { return {g_allocs.load(), g_frees.load(), g_locks.load(), g_io.load()}; }
}  // namespace contactlab::test

extern "C" int pthread_mutex_lock(pthread_mutex_t* m) {
    bump(g_locks);
    static auto real = next_symbol<int (*)(pthread_mutex_t*)>("pthread_mutex_lock");
    return real(m);
}
extern "C" int pthread_mutex_trylock(pthread_mutex_t* m) {
    bump(g_locks);
    static auto real = next_symbol<int (*)(pthread_mutex_t*)>("pthread_mutex_trylock");
    return real(m);
}
extern "C" ssize_t write(int fd, const void* buf, size_t n) {
    bump(g_io);
    static auto real = next_symbol<ssize_t (*)(int, const void*, size_t)>("write");
    return real(fd, buf, n);
}
extern "C" size_t fwrite(const void* p, size_t size, size_t n, FILE* f) {
    bump(g_io);
    static auto real = next_symbol<size_t (*)(const void*, size_t, size_t, FILE*)>("fwrite");
    return real(p, size, n, f);
}
extern "C" int ioctl(int fd, unsigned long request, ...) {
    bump(g_io);
    va_list ap;
    va_start(ap, request);
    void* arg = va_arg(ap, void*);
    va_end(ap);
    static auto real = next_symbol<int (*)(int, unsigned long, void*)>("ioctl");
    return real(fd, request, arg);
}

void* operator new(std::size_t n) {
    bump(g_allocs);
    if (void* p = std::malloc(n ? n : 1)) return p;
    throw std::bad_alloc();
}
void* operator new[](std::size_t n) { return operator new(n); }
void* operator new(std::size_t n, const std::nothrow_t&) noexcept {
    bump(g_allocs);
    return std::malloc(n ? n : 1);
}
void* operator new[](std::size_t n, const std::nothrow_t& t) noexcept { return operator new(n, t); }
// GCC 12 sees free() inside operator delete and warns of a new/free mismatch; every operator new
// above allocates with malloc, so free is the matching release.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"
void operator delete(void* p) noexcept {
    if (p) bump(g_frees);
    std::free(p);
}
#pragma GCC diagnostic pop
void operator delete[](void* p) noexcept { operator delete(p); }
void operator delete(void* p, std::size_t) noexcept { operator delete(p); }
void operator delete[](void* p, std::size_t) noexcept { operator delete(p); }
