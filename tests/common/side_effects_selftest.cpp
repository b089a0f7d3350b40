// side_effects_selftest.cpp — compiled into every executable that uses side_effects.cpp: proves the
// overrides are in effect there (a link order or a libc that bypassed them would make every "no
// allocation" test pass vacuously).
#include "side_effects.hpp"

#include <doctest/doctest.h>

#include <pthread.h>
#include <unistd.h>

using namespace contactlab::test;

namespace {
// One allocation, one free, one mutex lock and one write(2), as the servo must never do.
void one_of_each() {
    pthread_mutex_t m = PTHREAD_MUTEX_INITIALIZER;
    int* volatile p = new int(3);  // volatile: the compiler may not elide the new/delete pair
    pthread_mutex_lock(&m);
    (void)!write(-1, "", 0);
    pthread_mutex_unlock(&m);
    delete p;
}
}  // namespace

TEST_CASE("the counters see an allocation, a free, a lock and a write (the overrides are in effect)") {
    // On this thread only: what it did. (A preloaded library's write(2), umockdev's in the USB
    // tests, may take a mutex of its own inside the call: locks are at least one.)
    reset_side_effects();
    count_this_thread(true);
    one_of_each();
    count_this_thread(false);
    SideEffects e = side_effects();
    CHECK(e.allocs == 1);
    CHECK(e.frees == 1);
    CHECK(e.locks >= 1);
    CHECK(e.io == 1);
    // On every thread: at least that (an emulator's or a library's own threads may add theirs).
    reset_side_effects();
    count_all_threads(true);
    one_of_each();
    count_all_threads(false);
    e = side_effects();
    CHECK(e.allocs >= 1);
    CHECK(e.frees >= 1);
    CHECK(e.locks >= 1);
    CHECK(e.io >= 1);
}
