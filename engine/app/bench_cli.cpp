// bench_cli.cpp — `contactlab bench`: the proxy's cost, its growth with the scene, what each
// feature adds and the speed/accuracy trade, the renderer's frame time, measured here and now
// (engine/bench/suites.hpp); --report adds PNG plots drawn by ContactLab (engine/bench/plots.hpp).
// Without a Vulkan device the tables are still written and the page says why the plots are not.
//
//   contactlab bench [--quick] [--json OUT.json] [--report DIR]
//   contactlab bench --scene SCENE.json --input IN.csv [--passes N] [--json OUT.json] [--ticks OUT.csv]
#include "engine/app/data_path.hpp"
#include "engine/app/subcommands.hpp"
#include "engine/bench/report.hpp"
#include "engine/bench/suites.hpp"
#include "haptics/atomic_file.hpp"
#include "haptics/scene_io.hpp"

#include <cstdio>
#include <filesystem>

namespace contactlab::app {
namespace {

struct BenchArgs {
    bool quick = false;
    std::string json;
    std::string report;
    std::string scene;
    std::string input;
    std::string ticks;  // --ticks: one CSV row per tick
    int passes = 20;
};

void write(const std::string& path, const std::string& text, const char* what) {
    try {
        write_file_atomically(path, text);
    } catch (const FileWriteError& e) {
        throw BadInput(std::string("bench: ") + e.what());
    }
    std::fprintf(stderr, "bench: %s written to %s\n", what, path.c_str());
}

int run_trace_timing(const BenchArgs& a) {
    if (a.input.empty()) throw BadInput("bench: --scene needs --input IN.csv (header t,x,y,phi)");
    if (a.passes < 1 || a.passes > 100000) throw BadInput("bench: --passes must lie in [1, 100000]");
    const Scene scene = load_scene_file(a.scene);
    const auto samples = read_finger_samples_file(a.input);
    if (samples.empty()) throw BadInput("bench: " + a.input + ": no samples");
    const bench::TraceTiming t = bench::time_trace(scene, samples, a.passes, !a.ticks.empty());
    std::printf("%s over %s: %zu samples x %d passes, %.0f %% in contact\n", a.scene.c_str(), a.input.c_str(),
                t.samples, t.passes, 100.0 * t.contact_fraction);
    std::printf("ns per tick: median %.0f, p99 %.0f, p99.9 %.0f, max %.0f  (a 1 kHz servo has 1,000,000; 10 kHz 100,000)\n",
                t.stats.median_ns, t.stats.p99_ns, t.stats.p999_ns, t.stats.max_ns);
    std::printf("ticks over 100 us: %zu, over 1 ms: %zu, of %zu\n", t.stats.over_100us, t.stats.over_1ms, t.stats.ticks);
    if (t.least)
        std::printf("each tick's least over the %d passes (the code's own tail; the rest of the above is the machine's): "
                    "median %.0f, p99 %.0f, p99.9 %.0f, max %.0f\n",
                    t.passes, t.least->median_ns, t.least->p99_ns, t.least->p999_ns, t.least->max_ns);
    const ProxyStages& s = t.stages;
    std::printf("stages, mean ns per tick (a second pass, timed by stage; its median %.0f ns): gather %.0f, "
                "pieces %.0f, walk %.0f, contact %.0f, anticipate %.0f\n",
                t.profiled.median_ns, s.gather, s.pieces, s.walk, s.contact, s.anticipate);
    const ProxyStages& w = t.tail.stages;
    std::printf("the slowest %zu tick(s) of that pass, mean %.0f ns: gather %.0f, pieces %.0f, walk %.0f, contact %.0f, "
                "anticipate %.0f\n",
                t.tail.ticks, t.tail.mean_ns, w.gather, w.pieces, w.walk, w.contact, w.anticipate);
    if (!a.json.empty()) write(a.json, bench::trace_json(t).dump(2) + "\n", "JSON");
    if (!a.ticks.empty()) write(a.ticks, bench::ticks_csv(t), "ticks CSV");
    return 0;
}

int run_suites(const BenchArgs& a) {
    bench::BenchOptions options;
    options.quick = a.quick;
    options.study_protocol = installed_data_path("scenes/experiments/002-bump-counting.json");
    options.wearable_study_protocol = installed_data_path("scenes/experiments/003-curvature.json");
    const bench::BenchResults r = bench::run_suites(options);
    const std::string md = bench::results_markdown(r);
    std::printf("\n%s", md.c_str());
    if (!a.json.empty()) write(a.json, bench::results_json(r).dump(2) + "\n", "JSON");
    if (!a.report.empty()) {
        std::error_code ec;
        std::filesystem::create_directories(a.report, ec);
        if (ec) throw BadInput("bench: --report " + a.report + ": " + ec.message());
        // Plots first, so the page links exactly the figures that were written (or says why not).
        const bench::ReportPlots plots = bench::write_report_plots(r, a.report);
        if (!plots.skipped.empty()) std::fprintf(stderr, "bench: plots skipped: %s\n", plots.skipped.c_str());
        for (const bench::PlotFile& f : plots.files) {
            if (f.error.empty()) std::fprintf(stderr, "bench: plot written to %s/%s\n", a.report.c_str(), f.file.c_str());
            else std::fprintf(stderr, "bench: plot %s not drawn: %s\n", f.file.c_str(), f.error.c_str());
        }
        write(a.report + "/README.md", bench::results_markdown(r, &plots), "report");
        write(a.report + "/bench.json", bench::results_json(r).dump(2) + "\n", "JSON");
    }
    return 0;
}

}  // namespace

void register_bench_command(CLI::App& app, int& rc) {
    static BenchArgs a;
    CLI::App* cmd = app.add_subcommand("bench", "Measure the proxy's cost per tick: growth, features, accuracy trade");
    cmd->add_flag("--quick", a.quick, "Fewer sizes and ticks: finishes within a minute (CI smoke run)");
    cmd->add_option("--json", a.json, "Write the results as JSON (keys tick_ns.<kind>.<N>)");
    cmd->add_option("--report", a.report, "Write a Markdown report with PNG plots (and the JSON) into this folder");
    cmd->add_option("--scene", a.scene, "Time your own scene over --input instead of the suites");
    cmd->add_option("--input", a.input, "Finger samples for --scene (the trace input: t,x,y,phi)");
    cmd->add_option("--passes", a.passes, "With --scene: how many times to replay the input")->default_val(20);
    cmd->add_option("--ticks", a.ticks,
                    "With --scene: write one CSV row per tick (pass,sample,ns,contact and each stage's ns)");
    cmd->callback([&rc] {
        if (!a.ticks.empty() && a.scene.empty()) throw BadInput("bench: --ticks needs --scene SCENE --input IN.csv");
        rc = a.scene.empty() ? run_suites(a) : run_trace_timing(a);
    });
}

}  // namespace contactlab::app
