// suites.hpp — what `contactlab bench` measures (issue 8), as data: the cost-growth suite with
// its baselines, the feature-cost table, the speed/accuracy Pareto table, the renderer's frame
// time (render_frames.hpp), and timing one user-supplied trace. Google Benchmark runs every
// measurement (benchmark::RegisterBenchmark with a fixed iteration count, one iteration per proxy
// tick); each tick is also timed on its own so the medians and 99th percentiles are per tick, not
// per batch.
#pragma once

#include "engine/bench/anticipation_spread.hpp"
#include "engine/bench/cost_scenes.hpp"
#include "engine/bench/energy_table.hpp"
#include "engine/bench/render_frames.hpp"
#include "engine/bench/servo_beside_renderer.hpp"
#include "engine/bench/study_speed.hpp"
#include "engine/bench/tick_stats.hpp"
#include "drivers/sim/bench_probes.hpp"
#include "haptics/proxy.hpp"
#include "haptics/scene.hpp"

#include <optional>
#include <string>
#include <vector>

namespace contactlab::bench {

struct BenchOptions {
    bool quick = false;  // CI smoke run: fewer sizes and ticks, within a minute
    // Seed 002's protocol file, for the simulated study's speed (study_speed.hpp); empty skips it.
    std::string study_protocol;
    // Seed 003's on the wearable platform, the same way; empty skips it.
    std::string wearable_study_protocol;
};

// The slowest ticks of a profiled run (ProxyDef::profile): the slowest 0.1 % (at least one), their
// mean time and mean time in each of the proxy's stages: which stage made the slow ones slow.
struct TailSplit {
    std::size_t ticks = 0;
    double mean_ns = 0.0;
    ProxyStages stages;  // mean ns per slow tick in each stage
};

// One tick of `bench --scene --ticks`: which pass and sample, its time, whether it ended in
// contact, and (from the profiled replay of the same sample) each stage's time.
struct TickRow {
    int pass = 0;
    std::size_t sample = 0;
    double ns = 0.0;           // the plain pass's time of this tick
    bool contact = false;
    ProxyStages stages;        // ns in each stage, profiled pass
    double profiled_ns = 0.0;  // the profiled pass's time of this tick (stages plus their clock reads)
};

// The first tick in contact after a hand's approach: the finger comes straight down from
// kApproachFrom above the stroke's first sample at `speed` (a sample a 1 ms tick), then slides the
// stroke's first kApproachStrokeTicks ticks. A hand reaches a surface over many ticks, its gathers
// made by the hover's anticipation on the way, so the first contact tick should cost what later
// ones cost (the strokes above start 3 mm above the profile and press 1 mm in within one tick).
inline constexpr double kApproachFrom = 0.01;     // m
inline constexpr int kApproachStrokeTicks = 500;  // ticks of the stroke after the approach
inline constexpr double kApproachSpeeds[] = {0.1, 0.5};  // m/s: a slow reach and a quick tap
struct FirstContact {
    double speed = 0.0;        // m/s
    bool found = false;        // the approach reached contact
    std::size_t tick = 0;      // the first tick in contact, counted from the approach's first
    double ns = 0.0;           // its time: least over the passes (one with --quick)
    TickStats later;           // the ticks after it, each its least over the passes
};

// One scene size: ContactLab's proxy, and in the same process the baselines: brute force (every
// segment every tick, no index; run up to `kBruteForceMaxSegments`) and a point-finger
// god-object on the same contour.
struct CostRow {
    CostCase scene;
    std::string key;            // tick_ns.<key>.<segments>
    TickStats proxy;
    std::optional<TickStats> brute_force;
    TickStats point_finger;
    // The same stroke 1 cm above the surface: free space, where the tick's cost is the
    // anticipation of the nearest contact (hover_ns.<key>.<segments>).
    TickStats hover;
    // With more than one pass (the full suite runs 3): each tick's least time over the passes, in
    // contact and hovering (least_over_passes): the code's own tail, the machine's stalls that hit
    // one pass only taken out. The figures above stay every tick's, as a user meets them.
    std::optional<TickStats> proxy_least, hover_least;
    // At the suite's largest size: the slowest ticks' stage split, in contact and hovering.
    TailSplit tail_contact, tail_hover;
    // At the largest size: hovering with anticipation spread over ticks (kBenchAnticipationBudget
    // segments a tick), its times and its l_d error against the exact hover.
    std::optional<TickStats> hover_spread;
    // At the largest size: the first tick in contact after an approach, one per kApproachSpeeds.
    std::vector<FirstContact> first_contact;
    SpreadError spread_error;
    double contact_fraction = 0.0;  // ticks in contact / ticks
    int env_segments = 0;           // after compiling curves to arcs
};

struct FeatureRow {
    std::string feature;
    std::string stroke;  // "contact" (1 mm deep) or "free space" (5 mm above)
    TickStats stats;
};

struct ParetoRow {
    std::string mode;             // "exact" or "flatten"
    double tolerance = 0.0;       // m, flatten chord tolerance
    int env_segments = 0;
    double depth_error_max = 0.0;  // m, against exact mode
    double depth_error_p99 = 0.0;  // m
    double proxy_error_max = 0.0;  // m
    double proxy_error_p99 = 0.0;  // m
    TickStats stats;
};

struct BenchResults {
    bool quick = false;
    std::vector<StabilityRow> stability;          // rate vs stiffness, closed loop (drivers)
    std::vector<ZWidthRow> zwidth;                // largest stable K vs virtual damping B, press and slide
    std::vector<EnergyRow> energy;                // the energy balance's terms on the seeds' trials
    std::vector<RollerTrackingRow> roller;        // roller error vs gains and finger speed: tracking and jumps
    std::vector<RollerJumpRow> roller_jump;       // roller alone: settling after a jump of l_d
    double roller_bandwidth_hz = 0.0;             // 1 cm sine, -3 dB, 1 kHz
    std::vector<CostRow> cost;
    std::vector<FeatureRow> features;
    std::vector<ParetoRow> pareto;
    RenderFrameResults render;                    // offscreen frame time (engine/render)
    ServoBesideRenderer servo_beside;             // the real-time servo's period, alone and drawing
    StudySpeed study;                             // a simulated participant of seed 002, by stage
    StudySpeed wearable_study;                    // ... and of seed 003 on the wearable platform
};

BenchResults run_suites(const BenchOptions& options);

// `contactlab bench --scene --input`: the proxy over the trace's samples, `passes` times, each
// tick timed (I/O and set-up excluded).
struct TraceTiming {
    TickStats stats;
    std::optional<TickStats> least;  // with --passes 2 or more: each tick's least over the passes
    // A second pass with ProxyDef::profile: mean ns per tick in each named stage, and that pass's
    // own tick statistics (the stages' clock reads included).
    ProxyStages stages;
    TickStats profiled;
    TailSplit tail;              // the profiled pass's slowest ticks, by stage
    std::vector<TickRow> rows;   // every tick, when asked (--ticks)
    std::size_t samples = 0;
    int passes = 0;
    double contact_fraction = 0.0;
};
TraceTiming time_trace(const Scene& scene, const std::vector<FingerSample>& samples, int passes, bool keep_rows = false);

}  // namespace contactlab::bench
