// gbench_run.cpp — one place that drives Google Benchmark for every suite (gbench_run.hpp).
#include "engine/bench/gbench_run.hpp"

#include <benchmark/benchmark.h>

#include <cstdio>
#include <string>
#include <unistd.h>

namespace contactlab::bench {
namespace {

// The library's console reporter prints its context (CPU, caches, a "built as DEBUG" warning
// about Debian's packaged library) and a table before every one of the ~80 runs: 800 lines in
// which a user could not find the figures (issue 19). The suites read their own per-tick timings
// back and print one summary at the end, so this reporter prints one header for the whole
// `contactlab bench` and, on a terminal, a progress line on stderr.
class QuietReporter : public benchmark::BenchmarkReporter {
public:
    bool ReportContext(const Context& context) override {
        static bool printed = false;
        if (!printed) {
            const benchmark::CPUInfo& cpu = context.cpu_info;
            std::printf("contactlab bench: Google Benchmark on %d CPUs at %.0f MHz", cpu.num_cpus,
                        cpu.cycles_per_second / 1e6);
            if (cpu.load_avg.size() >= 3)
                std::printf(", load average %.2f %.2f %.2f", cpu.load_avg[0], cpu.load_avg[1], cpu.load_avg[2]);
            std::printf("; every tick or frame is also timed on its own (figures below)\n");
            std::fflush(stdout);
            printed = true;
        }
        return true;
    }
    void ReportRuns(const std::vector<Run>& runs) override {
        static int done = 0;
        done += static_cast<int>(runs.size());
        if (!isatty(fileno(stderr)) || runs.empty()) return;
        const std::string name = runs.back().benchmark_name();
        std::fprintf(stderr, "\r\033[Kbench: %d measured, last %s", done, name.c_str());
    }
    void Finalize() override {
        if (isatty(fileno(stderr))) std::fputs("\r\033[K", stderr);
    }
};

}  // namespace

void run_registered() {
    static bool initialised = false;
    if (!initialised) {
        // Static: the library keeps argv[0].
        static char name[] = "contactlab-bench";
        static char* argv[] = {name, nullptr};
        int argc = 1;
        benchmark::Initialize(&argc, argv);
        initialised = true;
    }
    QuietReporter reporter;
    benchmark::RunSpecifiedBenchmarks(&reporter);
    benchmark::ClearRegisteredBenchmarks();
}

}  // namespace contactlab::bench
