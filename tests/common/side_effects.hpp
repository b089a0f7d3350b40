// side_effects.hpp — counts what the servo path must never do: heap allocations and frees,
// mutex locks, and I/O (write, fwrite, ioctl). side_effects.cpp replaces the global operator
// new/delete and interposes those libc calls for the whole executable it is compiled into, so it
// goes only into the dedicated "no allocation" test executables (never under ASan, which owns
// operator new itself).
//
// Counting is off until asked for, either on every thread (a servo thread running while the test
// thread sleeps) or on the calling thread only (a servo thread beside threads that legitimately
// allocate and do I/O, such as libusb's event thread).
#pragma once

namespace contactlab::test {

struct SideEffects {
    long allocs = 0;  // operator new (all forms)
    long frees = 0;   // operator delete of a non-null pointer
    long locks = 0;   // pthread_mutex_lock / trylock (std::mutex goes through these)
    long io = 0;      // write(2), fwrite(3), ioctl(2)
};

void reset_side_effects();
void count_all_threads(bool on);
void count_this_thread(bool on);
SideEffects side_effects();

}  // namespace contactlab::test
