// suites.cpp — the measurements behind `contactlab bench` (suites.hpp).
//
// Index
//   measure            one benchmark: a proxy over a stroke, every tick timed
//   first contact      the first tick in contact after an approach, at the largest size
//   cost growth        extent and density, lines/arcs/curves, with the two baselines
//   feature costs      each force-law feature used, and all enabled but unused
//   Pareto             curve modes against exact mode on seed 002's bumps stimulus
//   time_trace         a user's scene and trace
#include "engine/bench/suites.hpp"

#include "engine/bench/gbench_run.hpp"
#include "haptics/environment.hpp"
#include "haptics/proxy.hpp"
#include "haptics/scene_io.hpp"
#include "haptics/stimuli.hpp"

#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace contactlab::bench {
namespace {

// Brute force builds pieces for every segment every tick: at 100,000 segments that is ~10 ms a
// tick and minutes a table, so it runs up to this size.
constexpr int kBruteForceMaxSegments = 10000;
constexpr int kBruteForceMaxSegmentsQuick = 1000;
constexpr double kStartAbove = 0.003;  // m: each pass starts this far above its first sample

// ---- measure ----------------------------------------------------------------------------------
struct Measured {
    TickStats stats;
    // Each tick of the stroke, its least time over the passes (least_over_passes; with one pass,
    // that pass's times), and with two passes or more their statistics: the code's own tail
    // without the machine's one-pass stalls.
    std::vector<double> least_ns;
    std::optional<TickStats> least;
    double contact_fraction = 0.0;
    ProxyStages stages;  // mean ns per tick in each stage (def.profile; zero otherwise)
    TailSplit tail;      // the slowest ticks and their stages (stages zero without def.profile)
    std::vector<TickRow> rows;  // every tick, in order (when asked)
};

// The slowest 0.1 % of the ticks (at least one): their mean time and mean stage split.
TailSplit tail_split(const std::vector<double>& ns, const std::vector<ProxyStages>& stages) {
    TailSplit t;
    if (ns.empty()) return t;
    std::vector<std::size_t> order(ns.size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
    t.ticks = std::max<std::size_t>(1, ns.size() / 1000);
    std::partial_sort(order.begin(), order.begin() + static_cast<std::ptrdiff_t>(t.ticks), order.end(),
                      [&](std::size_t a, std::size_t b) { return ns[a] > ns[b]; });
    for (std::size_t k = 0; k < t.ticks; ++k) {
        t.mean_ns += ns[order[k]];
        t.stages += stages[order[k]];
    }
    const double per = 1.0 / static_cast<double>(t.ticks);
    t.mean_ns *= per;
    t.stages = {t.stages.gather * per, t.stages.pieces * per, t.stages.walk * per, t.stages.contact * per,
                t.stages.anticipate * per};
    return t;
}

// One Google Benchmark run of `passes` x the stroke, one iteration per tick. Each pass starts
// with no history at the first sample raised by `start_above` (m). Each tick's stages and contact
// are kept beside its time (reserved up front: nothing allocates between the timed ticks).
Measured measure(const std::string& name, const Environment& env, const ProxyDef& def,
                 const std::vector<FingerSample>& path, int passes, double start_above = kStartAbove,
                 bool keep_rows = false) {
    Measured result;
    const auto iterations = static_cast<benchmark::IterationCount>(path.size() * static_cast<std::size_t>(passes));
    benchmark::RegisterBenchmark(name.c_str(), [&](benchmark::State& state) {
        Proxy proxy(env, def);
        TickTimer timer(static_cast<std::size_t>(iterations));
        std::vector<ProxyStages> tick_stages;
        std::vector<char> tick_contact;
        tick_stages.reserve(static_cast<std::size_t>(iterations));
        tick_contact.reserve(static_cast<std::size_t>(iterations));
        std::size_t k = 0, contacts = 0, ticks = 0;
        ProxyStages sum;
        proxy.reset(path[0].x + Vec2{0.0, start_above}, path[0].phi);
        for (auto _ : state) {
            const FingerSample& s = path[k];
            const ProxyOutput* o = nullptr;
            timer.time([&] { o = &proxy.update(s.x, s.phi); });
            benchmark::DoNotOptimize(o->force);
            contacts += o->contact ? 1 : 0;
            ++ticks;
            sum += o->stages;
            tick_stages.push_back(o->stages);
            tick_contact.push_back(o->contact ? 1 : 0);
            if (++k == path.size()) {  // lift the finger back to the start
                k = 0;
                proxy.reset(path[0].x + Vec2{0.0, start_above}, path[0].phi);
            }
        }
        result.stats = timer.stats();
        result.least_ns = least_over_passes(timer.samples(), path.size());
        if (passes > 1) result.least = tick_stats(result.least_ns);
        result.tail = tail_split(timer.samples(), tick_stages);
        if (keep_rows) {
            result.rows.resize(ticks);
            for (std::size_t i = 0; i < ticks; ++i)
                result.rows[i] = {static_cast<int>(i / path.size()), i % path.size(), timer.samples()[i], tick_contact[i] != 0,
                                  tick_stages[i]};
        }
        result.contact_fraction = ticks ? static_cast<double>(contacts) / static_cast<double>(ticks) : 0.0;
        const double per_tick = ticks ? 1.0 / static_cast<double>(ticks) : 0.0;
        result.stages = {sum.gather * per_tick, sum.pieces * per_tick, sum.walk * per_tick, sum.contact * per_tick,
                         sum.anticipate * per_tick};
        state.counters["median_ns"] = result.stats.median_ns;
        state.counters["p99_ns"] = result.stats.p99_ns;
        state.counters["p999_ns"] = result.stats.p999_ns;
        state.counters["max_ns"] = result.stats.max_ns;
        state.counters["contact"] = result.contact_fraction;
    })->Iterations(iterations)->Unit(benchmark::kNanosecond);
    run_registered();
    return result;
}

// The finger brought down onto `stroke`'s first sample at `speed` (m/s, a sample a 1 ms tick), then
// along the stroke; timed `passes` times (FirstContact).
FirstContact first_contact_after_approach(const std::string& name, const Environment& env, const ProxyDef& def,
                                          const std::vector<FingerSample>& stroke, double speed, int passes) {
    FirstContact fc;
    fc.speed = speed;
    const double step = speed * 1e-3;  // m a tick at 1 kHz
    std::vector<FingerSample> path;
    const auto above = static_cast<int>(std::ceil(kApproachFrom / step - 1e-9));
    for (int k = above; k >= 1; --k) {
        FingerSample s = stroke[0];
        s.x.y += k * step;
        path.push_back(s);
    }
    path.insert(path.end(), stroke.begin(), stroke.begin() + std::min<std::ptrdiff_t>(stroke.size(), kApproachStrokeTicks));
    char label[32];
    std::snprintf(label, sizeof label, "/approach_%gm_s", speed);
    const Measured m = measure(name + label, env, def, path, passes, 0.0, true);
    const std::vector<double>& least = m.least_ns;
    for (std::size_t i = 0; i < path.size(); ++i) {
        if (!m.rows[i].contact) continue;
        fc.found = true;
        fc.tick = i;
        fc.ns = least[i];
        fc.later = tick_stats(std::vector<double>(least.begin() + static_cast<std::ptrdiff_t>(i) + 1, least.end()));
        break;
    }
    return fc;
}

// ---- cost growth --------------------------------------------------------------------------------
void cost_growth(const BenchOptions& o, BenchResults& r) {
    const std::vector<int> sizes = o.quick ? std::vector<int>{10, 1000, 100000}
                                           : std::vector<int>{10, 100, 1000, 10000, 100000};
    const int ticks = o.quick ? 1000 : 4000;
    const int passes = o.quick ? 1 : 3;
    const int brute_max = o.quick ? kBruteForceMaxSegmentsQuick : kBruteForceMaxSegments;
    for (const Growth growth : {Growth::extent, Growth::dense}) {
        for (const SegmentKind kind : {SegmentKind::lines, SegmentKind::arcs, SegmentKind::curves}) {
            for (const int n : sizes) {
                CostRow row;
                row.scene = {kind, growth, n};
                row.key = case_key(kind, growth);
                const Scene scene = cost_scene(row.scene);
                validate_scene(scene);
                const Environment env = build_environment(scene);
                row.env_segments = static_cast<int>(env.segments.size());
                const auto path = cost_stroke(row.scene, ticks);
                const std::string name = row.key + "/" + std::to_string(n);
                ProxyDef def = proxy_def_of(scene);
                const Measured m = measure(name, env, def, path, passes);
                row.proxy = m.stats;
                row.proxy_least = m.least;
                row.contact_fraction = m.contact_fraction;
                if (n <= brute_max) {
                    ProxyDef brute = def;
                    brute.use_index = false;
                    row.brute_force = measure(name + "/brute_force", env, brute, path, 1).stats;
                }
                ProxyDef point = def;
                point.finger = FingerShape{FingerKind::point, 0.0, 0.0};
                // The point finger rides the contour itself: put it 1 mm deep under the same stroke.
                std::vector<FingerSample> point_path = path;
                for (FingerSample& s : point_path) s.x.y -= def.finger.radius;
                row.point_finger = measure(name + "/point_finger", env, point, point_path, passes).stats;
                std::vector<FingerSample> hover_path = path;
                for (FingerSample& s : hover_path) s.x.y += 0.011;  // m: 1 cm above the surface
                const Measured h = measure(name + "/hover", env, def, hover_path, passes);
                row.hover = h.stats;
                row.hover_least = h.least;
                if (n == sizes.back()) {
                    // Where the slowest ticks' time goes: the same strokes again with the stages
                    // timed (their clock reads cost a little, so the plain passes stay the figures).
                    ProxyDef profiled = def;
                    profiled.profile = true;
                    row.tail_contact = measure(name + "/profiled", env, profiled, path, passes).tail;
                    row.tail_hover = measure(name + "/hover/profiled", env, profiled, hover_path, passes).tail;
                    // Anticipation spread over ticks (an option, not the default): its times, and
                    // its l_d against the exact hover's on the same stroke.
                    ProxyDef spread = def;
                    spread.anticipation_budget = kBenchAnticipationBudget;
                    row.hover_spread = measure(name + "/hover/spread", env, spread, hover_path, passes).stats;
                    row.spread_error = anticipation_spread_error(env, def, hover_path, kBenchAnticipationBudget);
                    for (const double speed : kApproachSpeeds)
                        row.first_contact.push_back(first_contact_after_approach(name, env, def, path, speed, passes));
                }
                r.cost.push_back(row);
            }
        }
    }
}

// ---- feature costs ------------------------------------------------------------------------------
void feature_costs(const BenchOptions& o, BenchResults& r) {
    const CostCase c{SegmentKind::lines, Growth::extent, 1000};
    const Scene base = cost_scene(c);
    const Environment env = build_environment(base);
    const int ticks = o.quick ? 1000 : 4000;
    const int passes = o.quick ? 1 : 3;
    const std::vector<FingerSample> contact = cost_stroke(c, ticks);
    std::vector<FingerSample> free_space_path = contact;
    for (FingerSample& s : free_space_path) s.x.y += 0.006;  // 5 mm above the surface: anticipation only
    const std::vector<FingerSample>& free_space = free_space_path;

    struct Variant {
        const char* name;
        void (*apply)(ForceLaw&);
    };
    const Variant variants[] = {
        {"spring (baseline)", [](ForceLaw&) {}},
        {"ellipsoid field, e = 0.5", [](ForceLaw& l) { l.model = ForceModel::ellipsoid; l.k_tangential = 1000.0; l.k_normal = 500.0; }},
        {"friction cone, mu 0.5 / 0.4", [](ForceLaw& l) { l.mu_static = 0.5; l.mu_dynamic = 0.4; }},
        {"normal damping, B = 2 N s/m", [](ForceLaw& l) { l.damping = 2.0; }},
        {"contact sum (seed 002)", [](ForceLaw& l) { l.contacts = ContactForce::sum; }},
        {"all of the above", [](ForceLaw& l) {
             l.model = ForceModel::ellipsoid; l.k_tangential = 1000.0; l.k_normal = 500.0;
             l.mu_static = 0.5; l.mu_dynamic = 0.4; l.damping = 2.0; l.contacts = ContactForce::sum; }},
    };
    for (const auto& [stroke_name, stroke] : {std::pair{"contact", &contact}, std::pair{"free space", &free_space}}) {
        for (const Variant& v : variants) {
            if (std::string(stroke_name) == "free space" && std::string(v.name) != "spring (baseline)" &&
                std::string(v.name) != "all of the above")
                continue;  // in free space no force law runs: baseline against everything enabled
            ProxyDef def = proxy_def_of(base);
            v.apply(def.law);
            const Measured m = measure(std::string("feature/") + v.name + "/" + stroke_name, env, def, *stroke, passes);
            r.features.push_back(FeatureRow{v.name, stroke_name, m.stats});
        }
    }
}

// ---- Pareto -------------------------------------------------------------------------------------
// Seed 002's stimulus (generate bumps, seed 1) traced 1 mm deep along the normal of exact mode's
// own c-space boundary: a guide proxy 3 mm under the envelope gives the boundary and its normal.
std::vector<FingerSample> bumps_stroke(const GeneratedScene& g) {
    const Environment env = build_environment(g.scene);
    Proxy guide(env, proxy_def_of(g.scene));
    const auto& e = g.envelope;
    std::vector<FingerSample> path;
    std::size_t j = 0;
    guide.reset({0.005, 0.3}, 0.0);
    for (double x = 0.005; x <= 0.175; x += 3.5e-5) {
        while (j + 2 < e.size() && e[j + 1].x < x) ++j;
        const double t = (x - e[j].x) / (e[j + 1].x - e[j].x);
        const Vec2 f{x, e[j].y + t * (e[j + 1].y - e[j].y) + 0.026 - 0.003};
        const ProxyOutput& out = guide.update(f, 0.0);
        if (out.contact && out.depth > 0.0)
            path.push_back({1e-3 * static_cast<double>(path.size()), out.proxy - 0.001 * (out.proxy - f) / out.depth, 0.0});
    }
    return path;
}

void pareto(const BenchOptions& o, BenchResults& r) {
    const GeneratedScene g = generate_bumps(BumpsDef{});
    const auto path = bumps_stroke(g);
    const int passes = o.quick ? 1 : 3;
    // Exact mode's outputs are the reference (its own error against the true Bezier is ~1e-9 m,
    // tests/haptics/test_curves.cpp).
    std::vector<Vec2> ref_proxy;
    std::vector<double> ref_depth;
    {
        const Environment env = build_environment(g.scene);
        Proxy p(env, proxy_def_of(g.scene));
        p.reset(path[0].x + Vec2{0.0, kStartAbove}, 0.0);
        for (const FingerSample& s : path) {
            const ProxyOutput& out = p.update(s.x, s.phi);
            ref_proxy.push_back(out.proxy);
            ref_depth.push_back(out.depth);
        }
    }
    std::vector<std::pair<CurveMode, double>> modes = {{CurveMode::exact, 0.0}};
    for (const double tol : o.quick ? std::vector<double>{1e-4, 1e-5} : std::vector<double>{1e-3, 1e-4, 1e-5, 1e-6})
        modes.push_back({CurveMode::flatten, tol});
    for (const auto& [mode, tol] : modes) {
        Scene scene = g.scene;
        if (mode == CurveMode::flatten) scene.curves = {CurveMode::flatten, tol};
        const Environment env = build_environment(scene);
        ParetoRow row;
        row.mode = curve_mode_name(mode);
        row.tolerance = tol;
        row.env_segments = static_cast<int>(env.segments.size());
        Proxy p(env, proxy_def_of(scene));
        p.reset(path[0].x + Vec2{0.0, kStartAbove}, 0.0);
        std::vector<double> depth_err, proxy_err;
        for (std::size_t k = 0; k < path.size(); ++k) {
            const ProxyOutput& out = p.update(path[k].x, path[k].phi);
            depth_err.push_back(std::abs(out.depth - ref_depth[k]));
            proxy_err.push_back(glm::length(out.proxy - ref_proxy[k]));
        }
        std::sort(depth_err.begin(), depth_err.end());
        std::sort(proxy_err.begin(), proxy_err.end());
        row.depth_error_max = depth_err.back();
        row.depth_error_p99 = depth_err[depth_err.size() * 99 / 100];
        row.proxy_error_max = proxy_err.back();
        row.proxy_error_p99 = proxy_err[proxy_err.size() * 99 / 100];
        char name[64];
        std::snprintf(name, sizeof name, "pareto/%s/%g", row.mode.c_str(), tol);
        row.stats = measure(name, env, proxy_def_of(scene), path, passes).stats;
        r.pareto.push_back(row);
    }
}

}  // namespace

BenchResults run_suites(const BenchOptions& options) {
    BenchResults r;
    r.quick = options.quick;
    cost_growth(options, r);
    feature_costs(options, r);
    pareto(options, r);
    // Closed-loop simulation in virtual time (drivers/sim/bench_probes.hpp): no timing involved.
    r.stability = stability_table(options.quick);
    r.zwidth = zwidth_table(options.quick);
    r.energy = energy_table(options.quick);
    r.study = study_speed(options.study_protocol, options.quick);
    r.wearable_study = study_speed(options.wearable_study_protocol, options.quick);
    r.roller = roller_tracking_table(options.quick);
    r.roller_jump = roller_jump_table(options.quick);
    r.roller_bandwidth_hz = roller_bandwidth_hz(options.quick);
    r.render = render_frame_suite(options.quick);
    r.servo_beside = servo_beside_renderer(options.quick);
    return r;
}

TraceTiming time_trace(const Scene& scene, const std::vector<FingerSample>& samples, int passes, bool keep_rows) {
    TraceTiming t;
    t.samples = samples.size();
    t.passes = passes;
    if (samples.empty()) return t;
    const Environment env = build_environment(scene);
    // Starts from the first sample with no history, as `contactlab trace` does.
    const Measured m = measure("trace", env, proxy_def_of(scene), samples, passes, 0.0, keep_rows);
    t.stats = m.stats;
    t.least = m.least;
    t.contact_fraction = m.contact_fraction;
    // Where the time goes: the same again with the stages timed (their clock reads cost a little,
    // so the plain pass above stays the figure to budget with).
    ProxyDef profiled = proxy_def_of(scene);
    profiled.profile = true;
    const Measured p = measure("trace_profiled", env, profiled, samples, passes, 0.0, keep_rows);
    t.stages = p.stages;
    t.profiled = p.stats;
    t.tail = p.tail;
    // One row per tick: its time in the plain pass, its stages (and their sum) in the profiled one,
    // which replays the same samples in the same order.
    if (keep_rows) {
        t.rows = m.rows;
        for (std::size_t i = 0; i < t.rows.size() && i < p.rows.size(); ++i) {
            t.rows[i].stages = p.rows[i].stages;
            t.rows[i].profiled_ns = p.rows[i].ns;
        }
    }
    return t;
}

}  // namespace contactlab::bench
