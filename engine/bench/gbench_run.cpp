// gbench_run.cpp — one place that drives Google Benchmark for every suite (gbench_run.hpp).
#include "engine/bench/gbench_run.hpp"

#include <benchmark/benchmark.h>

namespace contactlab::bench {

void run_registered() {
    static bool initialised = false;
    if (!initialised) {
        // Static: the library keeps argv[0] and prints it as "Running ..." before every run.
        static char name[] = "contactlab-bench";
        static char* argv[] = {name, nullptr};
        int argc = 1;
        benchmark::Initialize(&argc, argv);
        initialised = true;
    }
    // A fresh reporter each run: the library's default one does not survive a second run.
    benchmark::ConsoleReporter reporter(benchmark::ConsoleReporter::OO_Tabular);
    benchmark::RunSpecifiedBenchmarks(&reporter);
    benchmark::ClearRegisteredBenchmarks();
}

}  // namespace contactlab::bench
