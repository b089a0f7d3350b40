// fuzz_contact_cli.cpp — `contactlab fuzz-contact [--rows N] [--seed S] [--jobs J] [--dump DIR]`:
// the long soak of the proxy against the brute-force reference (haptics/verify/contact_fuzz.hpp).
// Prints the counts; exit 1 when any row violated a property. --dump writes the first failure's
// scene and hand path so `contactlab trace DIR/scene.json --input DIR/hand.csv` replays it.
#include "engine/app/number_options.hpp"
#include "engine/app/progress_bar.hpp"
#include "engine/app/subcommands.hpp"
#include "haptics/atomic_file.hpp"
#include "haptics/scene_io.hpp"
#include "haptics/bezier.hpp"
#include "haptics/verify/contact_fuzz.hpp"

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <string>
#include <thread>


namespace contactlab::app {
namespace {

struct FuzzArgs {
    long long rows = 1000000;
    unsigned long long seed = 1;
    int jobs = 0;  // 0: every core
    std::string dump;
};

void print_progress(std::int64_t done, std::int64_t total) { show_progress("fuzz-contact", done, total, "rows"); }

void dump_failure(const verify::FuzzFailure& f, const std::string& dir) {
    namespace fs = std::filesystem;
    fs::create_directories(dir);
    const verify::ContactCase c = verify::make_contact_case(f.case_seed);
    save_scene_file(c.scene, (fs::path(dir) / "scene.json").string());
    std::string csv = "t,x,y,phi\n";
    char line[160];
    for (int row = 0; row <= f.row; ++row) {
        const verify::HandSample& h = c.path[static_cast<std::size_t>(row)];
        std::snprintf(line, sizeof line, "%.17g,%.17g,%.17g,%.17g\n", row * 1e-3, h.finger.x, h.finger.y, h.phi);
        csv += line;
    }
    write_file_atomically((fs::path(dir) / "hand.csv").string(), csv);
}

int run(const FuzzArgs& a) {
    if (a.rows <= 0) throw BadInput("fuzz-contact: --rows must be positive");
    verify::FuzzOptions opt;
    opt.rows = a.rows;
    opt.seed = a.seed;
    opt.jobs = a.jobs > 0 ? a.jobs : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
    opt.progress = print_progress;
    const auto t0 = std::chrono::steady_clock::now();
    const verify::FuzzReport r = verify::run_contact_fuzz(opt);
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    std::printf("fuzz-contact: seed %llu, %lld rows in %lld random scenes (%d jobs, %.1f s)\n", a.seed,
                static_cast<long long>(r.rows), static_cast<long long>(r.cases), opt.jobs, s);
    std::printf("  rows in contact %lld, rows with the hand's pad > %.0f um inside a solid %lld, deepest hand %.1f mm\n",
                static_cast<long long>(r.contact_rows), verify::kHandInside * 1e6, static_cast<long long>(r.inside_rows),
                r.max_hand_depth * 1e3);
    std::printf("  deepest proxy pad %.3g m (allowed %.0e m)\n", r.max_proxy_penetration, verify::kMaxProxyPenetration);
    std::printf("  stored energy: the walk moved the proxy at most %.3g m further from the finger (allowed %.0e m, "
                "%.1e m on exact curves; %lld rows at an unchanged finger angle)\n",
                r.max_walk_distance_gain, verify::kEnergyDistanceSlack,
                verify::kEnergyDistanceSlack + 2.0 * kExactCurveTolerance, static_cast<long long>(r.same_angle_rows));
    for (int k = 0; k < verify::kViolationKinds; ++k)
        std::printf("  %-15s %lld\n", verify::to_string(static_cast<verify::Violation>(k)),
                    static_cast<long long>(r.violations[static_cast<std::size_t>(k)]));
    std::printf("  violations      %lld (in %lld of the %lld scenes; the first of each below)\n",
                static_cast<long long>(r.total_violations()), static_cast<long long>(r.failing_cases),
                static_cast<long long>(r.cases));
    for (const verify::FuzzFailure& f : r.failures) {
        std::printf("  FAIL %s: case seed %llu row %d: hand (%.9g, %.9g) phi %.9g, hand pad %.3g m deep, proxy pad %.3g m, "
                    "output depth %.3g m, contact %d [%s]\n",
                    verify::to_string(f.kind), static_cast<unsigned long long>(f.case_seed), f.row, f.hand.finger.x,
                    f.hand.finger.y, f.hand.phi, f.hand_depth, f.proxy_depth, f.output_depth, f.contact ? 1 : 0,
                    f.summary.c_str());
    }
    if (!a.dump.empty() && !r.failures.empty()) {
        dump_failure(r.failures.front(), a.dump);
        std::printf("  first failure written to %s/scene.json and %s/hand.csv (contactlab trace replays it)\n", a.dump.c_str(),
                    a.dump.c_str());
    }
    return r.total_violations() == 0 ? 0 : 1;
}

}  // namespace

void register_fuzz_contact_command(CLI::App& app, int& rc) {
    static FuzzArgs a;
    CLI::App* cmd = app.add_subcommand("fuzz-contact",
                                       "Soak the proxy against a brute-force reference on seeded random scenes");
    add_whole_option(cmd, "--rows", a.rows, 1, std::numeric_limits<long long>::max(), "hand samples (servo ticks) in all");
    add_whole_option(cmd, "--seed", a.seed, 0, kMaxSeed, "seed of the random scenes and hand paths");
    add_whole_option(cmd, "--jobs", a.jobs, 0, kMaxJobs, "threads (0: one per core; the counts do not depend on it)");
    cmd->add_option("--dump", a.dump, "folder for the first failure's scene.json and hand.csv");
    cmd->callback([&rc] { rc = run(a); });
}

}  // namespace contactlab::app
