// gbench_run.hpp — run what is registered with Google Benchmark, then clear it: each suite
// registers its measurements, runs them, and reads its own per-tick timings back.
#pragma once

namespace contactlab::bench {

// Initialises the library on first use (no command line of its own: `contactlab bench` owns it),
// runs every registered benchmark with a fresh console reporter, and clears the registrations.
void run_registered();

}  // namespace contactlab::bench
