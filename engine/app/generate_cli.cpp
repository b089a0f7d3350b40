// generate_cli.cpp — `contactlab generate bumps|block|arc ... --output SCENE.json`: the seeds'
// stimuli as scene files (haptics/stimuli.hpp); `generate peer-workload`: the bench's dense
// sinusoid and its 1 mm deep stroke as files, the workload to time another haptics library on.
#include "engine/app/number_options.hpp"
#include "engine/app/subcommands.hpp"
#include "engine/bench/cost_scenes.hpp"
#include "haptics/atomic_file.hpp"
#include "haptics/scene_io.hpp"
#include "haptics/stimuli.hpp"

#include <cstdio>
#include <sstream>
#include <stdexcept>
#include <string>

namespace contactlab::app {
namespace {

struct GenerateArgs {
    std::string output;
    BumpsDef bumps;
    double d = 0.06;        // m, block top length before the edge
    double chord = 0.30;    // m, arc stimulus chord
    double height = 0.02;   // m, arc stimulus height
    int segments = 1000;    // peer workload: line segments on the 0.4 m sinusoid
    std::string trace;      // peer workload: the finger samples CSV to write
};

// The finger samples as `contactlab trace` / `bench --input` read them (t,x,y,phi; s, m, m, rad),
// every value exact to the last bit.
void save_trace(const std::vector<FingerSample>& samples, const std::string& path) {
    std::ostringstream csv;
    csv << kFingerSamplesHeader << "\n";
    for (const FingerSample& s : samples)
        csv << exact(s.t) << "," << exact(s.x.x) << "," << exact(s.x.y) << "," << exact(s.phi) << "\n";
    write_file_atomically(path, csv.str());
    std::fprintf(stderr, "generate: %zu finger samples written to %s\n", samples.size(), path.c_str());
}

void save(const Scene& scene, const std::string& path, const std::string& what) {
    save_scene_file(scene, path);
    std::fprintf(stderr, "generate: %s written to %s\n", what.c_str(), path.c_str());
}

// Generators report bad parameters as std::invalid_argument naming the option: exit 2.
template <class F>
void run(F f) {
    try {
        f();
    } catch (const std::invalid_argument& e) {
        throw BadInput(std::string("generate: ") + e.what());
    }
}

}  // namespace

void register_generate_command(CLI::App& app, int& rc) {
    static GenerateArgs a;
    CLI::App* gen = app.add_subcommand("generate", "Write one of the seeds' stimuli as a scene file");
    gen->require_subcommand(1);

    CLI::App* bumps = gen->add_subcommand("bumps", "Seed 002: base shape + small/large bumps as G1 quadratic Beziers");
    bumps->add_option("--output,-o", a.output, "Scene file to write")->required();
    add_whole_option(bumps, "--seed", a.bumps.seed, 0, kMaxSeed, "Random seed (same seed, same file)");
    bumps->add_option("--small", a.bumps.small_bumps, "Number of small (3 mm) bumps")->default_val(2);
    bumps->add_option("--large", a.bumps.large_bumps, "Number of large (18 mm) bumps")->default_val(1);
    bumps->add_option("--length", a.bumps.length, "Traced length (m)")->default_val(0.184);
    bumps->add_option("--base-span", a.bumps.base_span, "Vertical span of the base shape (m)")->default_val(0.20);
    bumps->callback([&rc] {
        run([] {
            const GeneratedScene g = generate_bumps(a.bumps);
            for (const BumpPlacement& b : g.bumps)
                std::fprintf(stderr, "  %s bump at x = %.1f mm, width %.1f mm, height %.0f mm\n",
                             b.large ? "large" : "small", b.start * 1e3, b.width * 1e3, b.height * 1e3);
            save(g.scene, a.output, std::to_string(g.bumps.size()) + " bumps, " +
                                        std::to_string(g.scene.contours[0].segments.size()) + " segments");
        });
        rc = 0;
    });

    CLI::App* block = gen->add_subcommand("block", "Seed 000: the contour-following block");
    block->add_option("--output,-o", a.output, "Scene file to write")->required();
    block->add_option("--d", a.d, "Top length before the edge (m), 0.04-0.10 in the seed")->default_val(0.06);
    block->callback([&rc] {
        run([] { save(generate_block(a.d), a.output, "block, d = " + std::to_string(a.d) + " m"); });
        rc = 0;
    });

    CLI::App* arc = gen->add_subcommand("arc", "Seed 003: a circular bump of given chord and height");
    arc->add_option("--output,-o", a.output, "Scene file to write")->required();
    arc->add_option("--chord", a.chord, "Chord (m)")->default_val(0.30);
    arc->add_option("--height", a.height, "Height (m): 0.01, 0.02 or 0.03 in the seed")->default_val(0.02);
    // The peer workload (issue 18): what the bench's "dense" lines case times, as files.
    CLI::App* peer = gen->add_subcommand(
        "peer-workload", "The bench's dense case as files: a 0.4 m sinusoid (1 cm amplitude, 10 cm wavelength) of "
                         "N line segments, and a 4000-tick stroke 1 mm deep along it (R = 2.6 cm pad facing down) after one "
                         "sample 5 cm above its start");
    peer->add_option("--output,-o", a.output, "Scene file to write")->required();
    peer->add_option("--trace", a.trace, "Finger samples CSV to write (t,x,y,phi), for bench --input or a peer")
        ->required();
    peer->add_option("--segments", a.segments, "Line segments on the 0.4 m contour")
        ->default_val(1000)
        ->check(CLI::Range(1, 10000000));
    peer->callback([&rc] {
        const bench::CostCase c{bench::SegmentKind::lines, bench::Growth::dense, a.segments};
        save(bench::cost_scene(c), a.output, "peer workload (" + std::to_string(a.segments) + " segments)");
        // One sample 5 cm above the stroke's start first, as the bench's suites start: a trace
        // begins with no history, and a first sample already 1 mm deep would put the proxy inside
        // the solid, where it follows the finger freely (timing anticipation, not contact).
        std::vector<FingerSample> samples = bench::cost_stroke(c);
        FingerSample lead = samples.front();
        lead.x.y += 0.05;
        for (FingerSample& s : samples) s.t += 1e-3;
        samples.insert(samples.begin(), lead);
        save_trace(samples, a.trace);
        rc = 0;
    });
    arc->callback([&rc] {
        run([] { save(generate_arc(a.chord, a.height), a.output, "arc stimulus"); });
        rc = 0;
    });
}

}  // namespace contactlab::app
