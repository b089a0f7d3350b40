// test_bench_report.cpp — `contactlab bench --report`: the plots drawn from the results, the
// Markdown linking them (or saying why they are missing), and the output of the quick run.
//
// Three groups, run as separate ctests (tests/bench/CMakeLists.txt):
//   report       charts and Markdown from made-up results, PNGs rendered on lavapipe
//   no_vulkan    the same with no Vulkan driver to be found: plots and frame times skipped, said why
//   quick_output what `contactlab bench --quick --report DIR` left in DIR (runs after that test)
#include "engine/bench/plots.hpp"
#include "engine/bench/render_frames.hpp"
#include "engine/bench/report.hpp"
#include "engine/render/image.hpp"

#include <algorithm>
#include <doctest/doctest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>
#include <tuple>
#include <fstream>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace fs = std::filesystem;
using namespace contactlab;
using namespace contactlab::bench;

namespace {

const std::vector<std::string> kPlotFiles = {"cost_extent.png", "cost_dense.png",      "tail_dense.png",
                                             "pareto.png",      "stability.png",       "zwidth.png",
                                             "roller_tracking.png", "render_frame.png"};

TickStats stats(double median_ns) {
    TickStats t;
    t.median_ns = median_ns, t.p99_ns = 2.0 * median_ns, t.p999_ns = 2.5 * median_ns, t.max_ns = 3.0 * median_ns;
    t.ticks = 100;
    return t;
}

// Results shaped like a quick run's, with plausible figures.
BenchResults made_up_results() {
    BenchResults r;
    r.quick = true;
    for (const Growth g : {Growth::extent, Growth::dense})
        for (const SegmentKind k : {SegmentKind::lines, SegmentKind::arcs, SegmentKind::curves})
            for (const int n : {10, 1000, 100000}) {
                CostRow row;
                row.scene = {k, g, n};
                row.key = case_key(k, g);
                row.proxy = stats(1000.0 + n * 0.01);
                row.point_finger = stats(300.0);
                row.hover = stats(800.0 + n * 0.02);
                if (n <= 1000) row.brute_force = stats(50.0 * n);
                row.contact_fraction = 1.0;
                r.cost.push_back(row);
            }
    ParetoRow exact;
    exact.mode = "exact";
    exact.stats = stats(9500.0);
    r.pareto.push_back(exact);
    for (const double tol : {1e-4, 1e-5}) {
        ParetoRow p;
        p.mode = "flatten";
        p.tolerance = tol;
        p.depth_error_p99 = tol * 0.8;
        p.depth_error_max = 2e-4;
        p.proxy_error_p99 = tol * 5.0;
        p.proxy_error_max = 3.7e-3;
        p.stats = stats(tol > 5e-5 ? 980.0 : 1780.0);
        r.pareto.push_back(p);
    }
    for (const double rate : {250.0, 1000.0}) {
        StabilityRow s;
        s.rate_hz = rate;
        s.passivity_bound = 2.0 * 5.0 * rate;
        s.k_no_fault = 1.5 * s.passivity_bound;
        s.k_settles = 1.2 * s.passivity_bound;
        s.k_ideal_settles = 1.1 * s.passivity_bound;
        r.stability.push_back(s);
    }
    // Z-width rows shaped like the quick table's (b_normal 1.7, b_declared 1.15 N s/m; the 10 kHz
    // damper applying B / 10; one K that not even the bracket's low end held).
    for (const double rate : {1000.0, 10000.0})
        for (const double b : {0.0, 1.0, 2.0}) {
            ZWidthRow z;
            z.rate_hz = rate;
            z.damping = b;
            z.damping_applied = rate > 5000.0 ? 0.1 * b : b;
            z.b_normal = 1.7;
            z.b_declared = 1.15;
            z.bound_normal = 2.0 * (z.b_normal - z.damping_applied) * rate;
            z.bound_declared = 2.0 * (z.b_declared - z.damping_applied) * rate;
            z.search_lo = 0.05 * 2.0 * z.b_normal * rate;
            z.search_hi = 4.0 * 2.0 * z.b_normal * rate;
            z.resolution = 1.02;
            z.k_press = rate > 5000.0 && b == 2.0 ? 0.0 : 4400.0 - 1500.0 * b;
            z.k_slide = 2600.0 - 500.0 * b;
            z.k_press_no_fault = 2.0 * (z.b_normal + z.damping_applied) * rate * 1.1;
            z.k_slide_no_fault = z.k_press_no_fault;
            r.zwidth.push_back(z);
        }
    for (const double g : {1.0, 2.0})
        for (const double v : {0.02, 0.05}) {
            RollerTrackingRow t;
            t.gain_scale = g;
            t.finger_speed = v;
            t.max_error = v * 1e-3 / g;
            t.rms_error = v * 0.3e-3 / g;
            t.max_tracking_error = v * 0.4e-3 / g;
            t.rms_tracking_error = v * 0.1e-3 / g;
            t.max_jump_error = t.max_error;
            t.jumps = 2;
            t.max_true_tracking_error = v * 0.6e-3 / g;
            t.rms_true_tracking_error = v * 0.2e-3 / g;
            t.max_true_encoder_error = v * 0.5e-3 / g;
            t.max_target_staircase = 0.04e-3;
            r.roller.push_back(t);
        }
    r.render.device = "made-up device";
    for (const int n : {10, 1000, 100000}) r.render.rows.push_back({n, stats(2e6 + 100.0 * n), 1000});
    return r;
}

fs::path fresh_dir(const std::string& name) {
    const fs::path d = fs::temp_directory_path() / name;
    fs::remove_all(d);
    fs::create_directories(d);
    return d;
}

std::string read_text(const fs::path& p) {
    std::ifstream in(p);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

}  // namespace

TEST_SUITE("report") {
TEST_CASE("tick_stats: nearest-rank percentiles, and the ticks that miss a 10 kHz or 1 kHz period") {
    // 2,000 ticks of 1..2,000 us, shuffled: rank k of the sorted list is (k + 1) us.
    std::vector<double> ns;
    for (int i = 2000; i >= 1; --i) ns.push_back(i * 1000.0);
    std::swap(ns[3], ns[1500]);
    const TickStats s = tick_stats(ns);
    CHECK(s.ticks == 2000);
    CHECK(s.median_ns == 1001e3);  // rank 1,000
    CHECK(s.p99_ns == 1981e3);     // rank 1,980
    CHECK(s.p999_ns == 1999e3);    // rank 1,998
    CHECK(s.max_ns == 2000e3);
    CHECK(s.over_100us == 1900);   // 101..2,000 us: exactly 100 us is not over
    CHECK(s.over_1ms == 1000);     // 1,001..2,000 us
    // Fewer than 1,000 ticks: p99.9 is the slowest one.
    const TickStats few = tick_stats({5.0, 1.0, 3.0});
    CHECK(few.p999_ns == 5.0);
    CHECK(few.over_100us == 0);
    CHECK(tick_stats({}).ticks == 0);
}

TEST_CASE("least_over_passes: each tick's least time across whole passes, a part pass refused") {
    // Three passes of four ticks; the machine stalls a different tick in each pass.
    const std::vector<double> ns = {10, 20, 900, 40,   //
                                    11, 700, 30, 41,   //
                                    800, 19, 31, 39};
    const std::vector<double> least = least_over_passes(ns, 4);
    REQUIRE(least.size() == 4);
    CHECK(least == std::vector<double>{10, 19, 30, 39});
    // One pass: its own times.
    CHECK(least_over_passes({5, 6, 7}, 3) == std::vector<double>{5, 6, 7});
    CHECK(least_over_passes({}, 4).empty());
    CHECK_THROWS_AS(least_over_passes(ns, 5), std::invalid_argument);  // 12 ticks are not whole passes of 5
    CHECK_THROWS_AS(least_over_passes(ns, 0), std::invalid_argument);
    // A tick slow in every pass stays slow: the code's own tail survives the least.
    const std::vector<double> slow_everywhere = {1, 500, 1, 501, 1, 502};
    CHECK(tick_stats(least_over_passes(slow_everywhere, 2)).max_ns == 500.0);
}

TEST_CASE("bench report: with passes, the code's tail (least of passes) beside every tick's, in the page and the JSON") {
    BenchResults r = made_up_results();
    // A quick run has one pass: no such table.
    CHECK(results_markdown(r).find("### The code's tail and the machine's") == std::string::npos);
    CHECK_FALSE(results_json(r).contains("tick_ns_least_of_passes"));
    for (CostRow& row : r.cost) {
        TickStats c = stats(row.proxy.median_ns), h = stats(row.hover.median_ns);
        c.ticks = h.ticks = 50;  // the rows' 100 ticks were two passes of 50
        c.p999_ns = 0.5 * row.proxy.p999_ns, c.max_ns = 0.25 * row.proxy.max_ns;
        h.p999_ns = 0.5 * row.hover.p999_ns, h.max_ns = 0.25 * row.hover.max_ns;
        row.proxy_least = c, row.hover_least = h;
    }
    const std::string md = results_markdown(r);
    const std::size_t at = md.find("### The code's tail and the machine's");
    REQUIRE(at != std::string::npos);
    // lines_dense at 100,000: contact p99.9 2.5 x 2,000 ns = 5 us all ticks, 2.5 us least; max
    // 6 us / 1.5 us; hover p99.9 2.5 x 2,800 = 7 us / 3.5 us, max 8.4 us / 2.1 us. Two passes.
    CHECK(md.find("| lines_dense | 100000 | 2 | 5 us / 2.5 us | 6 us / 1.5 us | 7 us / 3.5 us | 8.4 us / 2.1 us |",
                  at) != std::string::npos);
    const nlohmann::json j = results_json(r);
    CHECK(j["tick_ns_least_of_passes"]["lines_dense"]["100000"]["p999"].get<double>() == doctest::Approx(2500.0));
    CHECK_FALSE(j.contains("first_contact"));  // none measured in these rows
    CHECK(j["hover_ns_least_of_passes"]["curves"]["10"]["max"].get<double>() ==
          doctest::Approx(0.25 * 3.0 * (800.0 + 10 * 0.02)));
}

TEST_CASE("bench report: the first tick in contact after an approach, a row per speed, or says none was reached") {
    BenchResults r = made_up_results();
    CHECK(results_markdown(r).find("### The first tick in contact") == std::string::npos);
    CostRow& row = r.cost.back();  // curves_dense at 100,000
    REQUIRE(row.key == "curves_dense");
    FirstContact slow{0.1, true, 91, 12e3, stats(4e3)};
    FirstContact none{0.5, false, 0, 0.0, {}};
    row.first_contact = {slow, none};
    const std::string md = results_markdown(r);
    const std::size_t at = md.find("### The first tick in contact, after an approach");
    REQUIRE(at != std::string::npos);
    CHECK(md.find("descends from 10 mm above", at) != std::string::npos);
    CHECK(md.find("| curves_dense | 100000 | 0.1 m/s | 91 | 12 us | 4 us / 10 us / 12 us |", at) != std::string::npos);
    CHECK(md.find("| curves_dense | 100000 | 0.5 m/s | no contact | | |", at) != std::string::npos);
    const nlohmann::json j = results_json(r);
    const nlohmann::json& fc = j["first_contact"]["curves_dense"]["100000"];
    REQUIRE(fc.size() == 2);
    CHECK(fc[0]["tick"].get<int>() == 91);
    CHECK(fc[0]["ns"].get<double>() == 12e3);
    CHECK(fc[0]["later_ns"]["p999"].get<double>() == 10e3);
    CHECK_FALSE(fc[1]["found"].get<bool>());
    CHECK_FALSE(fc[1].contains("tick"));
}

TEST_CASE("bench report: one chart per figure, cost charts with ContactLab and both baselines per kind") {
    const auto charts = report_charts(made_up_results());
    REQUIRE(charts.size() == kPlotFiles.size());
    for (std::size_t i = 0; i < charts.size(); ++i) {
        CHECK(charts[i].file == kPlotFiles[i]);
        CHECK(charts[i].chart.width == kPlotWidth);
        CHECK(charts[i].chart.height == kPlotHeight);
        CHECK_NOTHROW(render::layout_chart(charts[i].chart));
    }
    // 3 kinds x (ContactLab, brute force, point finger), on log-log axes.
    const render::Chart& extent = charts[0].chart;
    CHECK(extent.series.size() == 9);
    CHECK(extent.x.scale == render::AxisScale::log10);
    CHECK(extent.y.scale == render::AxisScale::log10);
    // Brute force ran up to 1000 segments here: two points.
    CHECK(extent.series[1].name == "lines, brute force");
    CHECK(extent.series[1].x.size() == 2);
    // The tail on the dense contours: per kind p99.9, in contact and hovering (2 series x 3 kinds,
    // 3 sizes each), against the 10 kHz and 1 kHz periods.
    const render::Chart& tail = charts[2].chart;
    REQUIRE(tail.series.size() == 6);
    CHECK(tail.series[0].name == "lines, in contact");
    CHECK(tail.series[0].y[2] == doctest::Approx(2.5 * (1000.0 + 100000 * 0.01)));
    CHECK(tail.series[1].name == "lines, hovering");
    CHECK(tail.series[1].y[0] == doctest::Approx(2.5 * (800.0 + 10 * 0.02)));
    CHECK(tail.series[5].name == "curves, hovering");
    REQUIRE(tail.references.size() == 2);
    CHECK(tail.references[0].value == doctest::Approx(100e3));
    CHECK(tail.references[1].value == doctest::Approx(1e6));
    // Pareto: exact mode is a vertical reference at its cost; flatten rows are points.
    const render::Chart& pareto = charts[3].chart;
    REQUIRE(pareto.references.size() == 1);
    CHECK(pareto.references[0].vertical);
    CHECK(pareto.references[0].value == doctest::Approx(9500.0));
    CHECK(pareto.series[0].x.size() == 2);
    // Stability: the 2b/T bound beside the measured stiffnesses.
    CHECK(charts[4].chart.series[0].name == "2b/T, b along the normal");
    CHECK(charts[4].chart.series[0].y[1] == doctest::Approx(10000.0));
    CHECK(charts[4].chart.series[1].name == "2b/T, b declared (servo's)");
    // Z-width: per rate (one colour each) the stable press and slide, the unreported press, and
    // the three theory lines; K on a log axis against B.
    const render::Chart& zw = charts[5].chart;
    CHECK(zw.x.scale == render::AxisScale::linear);
    CHECK(zw.y.scale == render::AxisScale::log10);
    CHECK(zw.x.title.find("(N s/m)") != std::string::npos);
    CHECK(zw.y.title.find("(N/m)") != std::string::npos);
    REQUIRE(zw.series.size() == 12);
    CHECK(zw.series[0].name == "1 kHz press: stable");
    CHECK(zw.series[6].name == "10 kHz press: stable");
    CHECK(zw.series[0].color.r != zw.series[6].color.r);  // distinct colours per rate
    CHECK(zw.series[0].x.size() == 3);
    CHECK(zw.series[6].x.size() == 2);  // the K that was not found is left out, not drawn at 0
    // Colgate's bound 2 (b_n - B_a) / T: 3400 N/m at B = 0, 1 kHz, and down to the floor where
    // it dives to 0 at B_a = b_n; at 10 kHz it falls with B / 10.
    const render::ChartSeries& passive = zw.series[3];
    CHECK(passive.name == "1 kHz passive: 2(b_n - B_a)/T");
    CHECK(passive.dashed);
    CHECK(passive.y.front() == doctest::Approx(3400.0));
    CHECK(passive.x.back() < 1.7);
    CHECK(passive.y.back() >= 100.0);
    CHECK(zw.series[9].y.back() == doctest::Approx(2.0 * (1.7 - 0.2) * 10000.0));
    const render::ChartLayout zl = render::layout_chart(zw);
    CHECK(zl.skipped_points == 0);
}

TEST_CASE("bench report: PNGs written at the plot size and linked from the Markdown") {
    const BenchResults r = made_up_results();
    const fs::path dir = fresh_dir("contactlab_test_bench_report");
    const ReportPlots plots = write_report_plots(r, dir.string());
    CHECK(plots.skipped.empty());
    REQUIRE(plots.files.size() == kPlotFiles.size());
    for (const PlotFile& f : plots.files) {
        CHECK_MESSAGE(f.error.empty(), f.file, ": ", f.error);
        const render::Image img = render::read_png((dir / f.file).string());
        CHECK(img.width == kPlotWidth);
        CHECK(img.height == kPlotHeight);
    }
    const std::string md = results_markdown(r, &plots);
    for (const std::string& f : kPlotFiles) CHECK_MESSAGE(md.find("](" + f + ")") != std::string::npos, f);
    CHECK(md.find("| 100000 | 1000 | 12 ms |") != std::string::npos);  // the frame-time table
    fs::remove_all(dir);
}

TEST_CASE("bench report: a figure with no drawable data is not drawn and the page says why") {
    BenchResults r = made_up_results();
    for (RollerTrackingRow& t : r.roller)
        t.max_error = t.rms_error = t.max_tracking_error = t.rms_tracking_error = std::numeric_limits<double>::quiet_NaN();
    const fs::path dir = fresh_dir("contactlab_test_bench_report_nan");
    const ReportPlots plots = write_report_plots(r, dir.string());
    const PlotFile* roller = plots.find("roller_tracking.png");
    REQUIRE(roller != nullptr);
    CHECK(roller->error.find("no drawable point") != std::string::npos);
    CHECK_FALSE(fs::exists(dir / "roller_tracking.png"));
    CHECK(fs::exists(dir / "pareto.png"));
    const std::string md = results_markdown(r, &plots);
    CHECK(md.find("_Plot `roller_tracking.png` not drawn: ") != std::string::npos);
    fs::remove_all(dir);
}

TEST_CASE("bench report: the JSON splits the roller's tracking from its jumps, old keys kept") {
    BenchResults r = made_up_results();
    RollerJumpRow jump;
    jump.jump = 0.01;
    jump.jump_settle_s = 0.081;
    jump.force_limited_s = 0.059;
    r.roller_jump.push_back(jump);
    const nlohmann::json j = results_json(r);
    REQUIRE(j["roller_tracking"].size() == r.roller.size());
    const nlohmann::json& t = j["roller_tracking"][0];
    for (const char* key : {"max_error", "rms_error", "max_tracking_error", "rms_tracking_error", "max_jump_error",
                            "jumps", "jump_window_s", "feed_forward", "max_true_tracking_error",
                            "rms_true_tracking_error", "max_true_encoder_error", "max_target_staircase"})
        CHECK_MESSAGE(t.contains(key), key);
    CHECK(t["max_tracking_error"].get<double>() == doctest::Approx(r.roller[0].max_tracking_error));
    CHECK(t["max_true_tracking_error"].get<double>() == doctest::Approx(r.roller[0].max_true_tracking_error));
    CHECK(t["max_target_staircase"].get<double>() == doctest::Approx(0.04e-3));
    REQUIRE(j["roller_jump"].size() == 1);
    CHECK(j["roller_jump"][0]["jump_settle_s"].get<double>() == doctest::Approx(0.081));
    CHECK(j["roller_jump"][0]["force_limited_s"].get<double>() == doctest::Approx(0.059));
    const std::string md = results_markdown(r);
    CHECK(md.find("tracking max") != std::string::npos);
    CHECK(md.find("staircase max") != std::string::npos);
    CHECK(md.find("force-limited") != std::string::npos);
}

TEST_CASE("bench report: a paragraph longer than 255 characters comes whole, and the table after it on its own line") {
    // Regression: the report's printf helper wrote into 256 bytes, so the roller tracking's
    // paragraph (over 400 characters) was cut mid-sentence and its table's header joined that line.
    const std::string long_text = printf_text("%s|%.0f", std::string(300, 'x').c_str(), 42.0);
    CHECK(long_text.size() == 303);
    CHECK(long_text.substr(300) == "|42");
    const std::string md = results_markdown(made_up_results());
    CHECK(md.find("staircase: |l_d from the encoders - true l_d| there.\n\n| pole scale |") != std::string::npos);
}

TEST_CASE("bench report: the Z-width rows in the JSON and the Markdown") {
    const BenchResults r = made_up_results();
    const nlohmann::json j = results_json(r);
    REQUIRE(j["zwidth"].size() == r.zwidth.size());
    const nlohmann::json& z = j["zwidth"][4];  // 10 kHz, B = 1
    for (const char* key : {"rate_hz", "damping", "damping_applied", "k_press", "k_slide", "k_press_no_fault",
                            "k_slide_no_fault", "b_normal", "b_declared", "passivity_bound",
                            "passivity_bound_declared", "search_lo", "search_hi", "resolution"})
        CHECK_MESSAGE(z.contains(key), key);
    CHECK(z["rate_hz"].get<double>() == 10000.0);
    CHECK(z["damping_applied"].get<double>() == doctest::Approx(0.1));
    CHECK(z["passivity_bound"].get<double>() == doctest::Approx(2.0 * (1.7 - 0.1) * 10000.0));
    const std::string md = results_markdown(r);
    CHECK(md.find("## Z-width") != std::string::npos);
    CHECK(md.find("| 1000 Hz | 0.00 | 0.000 | 4400 | 2600 |") != std::string::npos);
    CHECK(md.find("| 1000 Hz | 2.00 | 2.000 | 1400 | 1600 | 8140 | 8140 | none | none | 7400 |") != std::string::npos);
    CHECK(md.find("| 10000 Hz | 2.00 | 0.200 | < 1700 |") != std::string::npos);
    // The damping applied, said from the rows: here 10 kHz applies B / 10 (a 1 ms divisor).
    CHECK(md.find("B_a = B except 0.1 B at 10000 Hz (the damper divides the depth's one-tick step by 1 ms, not by T)") !=
          std::string::npos);
}

TEST_CASE("bench report: the JSON holds render_ms.<N> in ms") {
    const nlohmann::json j = results_json(made_up_results());
    CHECK(j["render_ms"]["100000"]["median"].get<double>() == doctest::Approx(12.0));
    CHECK(j["render_ms"]["10"]["p99"].get<double>() == doctest::Approx(2.0 * (2e6 + 1000.0) / 1e6));
    CHECK(j["render_device"] == "made-up device");
}
}

TEST_SUITE("no_vulkan") {
TEST_CASE("bench report: with no Vulkan driver the plots and frame times are skipped, and the page says why") {
    // ctest points VK_DRIVER_FILES at a manifest that does not exist for this group.
    const RenderFrameResults frames = render_frame_suite(true);
    CHECK(frames.rows.empty());
    CHECK_FALSE(frames.skipped.empty());

    BenchResults r = made_up_results();
    r.render = frames;
    const fs::path dir = fresh_dir("contactlab_test_bench_report_novk");
    const ReportPlots plots = write_report_plots(r, dir.string());
    CHECK_FALSE(plots.skipped.empty());
    CHECK(plots.files.empty());
    CHECK(fs::is_empty(dir));
    const std::string md = results_markdown(r, &plots);
    CHECK(md.find("**Plots skipped**, Vulkan could not render them: " + plots.skipped) != std::string::npos);
    CHECK(md.find("![") == std::string::npos);
    CHECK(md.find("## Render frame time") != std::string::npos);
    CHECK(md.find("Skipped: " + frames.skipped) != std::string::npos);
    CHECK(results_json(r)["render_skipped"] == frames.skipped);
    fs::remove_all(dir);
}
}

TEST_SUITE("quick_output") {
TEST_CASE("bench --quick --report: every PNG decodes at the plot size, render_ms finite and positive") {
    const fs::path dir = CONTACTLAB_BENCH_QUICK_DIR;
    const std::string md = read_text(dir / "README.md");
    for (const std::string& f : kPlotFiles) {
        CAPTURE(f);
        REQUIRE(fs::exists(dir / f));
        const render::Image img = render::read_png((dir / f).string());
        CHECK(img.width == kPlotWidth);
        CHECK(img.height == kPlotHeight);
        CHECK(md.find("](" + f + ")") != std::string::npos);
    }
    const nlohmann::json j = nlohmann::json::parse(read_text(dir / "bench.json"));
    for (const char* n : {"10", "1000", "100000"}) {
        CAPTURE(n);
        REQUIRE(j["render_ms"].contains(n));
        for (const char* k : {"median", "p99", "max"}) {
            const double v = j["render_ms"][n][k].get<double>();
            CHECK(std::isfinite(v));
            CHECK(v > 0.0);
        }
        CHECK(j["render_ms"][n]["frames"].get<int>() >= 1);
    }
    CHECK_FALSE(j["render_device"].get<std::string>().empty());
    // The Z-width: 1 kHz at B = 0, 0.5, 1, 2, 5 N s/m and 10 kHz at 0, 1, 2, each K a bisection
    // result (in its bracket, or 0 where not even the low end held).
    REQUIRE(j["zwidth"].size() == 8);
    for (const nlohmann::json& z : j["zwidth"]) {
        CAPTURE(z.dump());
        for (const char* k : {"k_press", "k_slide", "k_press_no_fault", "k_slide_no_fault"}) {
            const double v = z[k].get<double>();
            CHECK((v == 0.0 || (v >= z["search_lo"].get<double>() && v <= z["search_hi"].get<double>())));
        }
        CHECK(z["k_press_no_fault"].get<double>() > 0.0);
    }
    CHECK(md.find("## Z-width") != std::string::npos);
    CHECK(md.find("## The tail: the slowest ticks") != std::string::npos);
    // At the largest size, the slowest ticks' stages: a share of the time, for contact and hover.
    for (const char* key : {"lines_dense", "arcs_dense", "curves_dense"}) {
        CAPTURE(key);
        const nlohmann::json& slow = j["slowest_ticks"][key]["100000"];
        for (const char* stroke : {"contact", "hover"}) {
            CHECK(slow[stroke]["ticks"].get<int>() >= 1);
            double staged = 0.0;
            for (const auto& [stage, ns] : slow[stroke]["stages_ns"].items()) staged += ns.get<double>();
            CHECK(staged > 0.0);
            CHECK(staged <= slow[stroke]["mean_ns"].get<double>());
        }
    }
    // Anticipation spread over ticks at the largest size: no tick asked more than the budget
    // plus a leaf's last items (ProxyDef::anticipation_budget), the l_d error is a length on the
    // pad (at most its whole span, 2 x 1 cm here), and the answers it showed came from at most
    // as many ticks back as the stroke had.
    CHECK(md.find("## Anticipation spread over ticks (an option)") != std::string::npos);
    for (const char* key : {"lines", "arcs", "curves", "lines_dense", "arcs_dense", "curves_dense"}) {
        CAPTURE(key);
        const nlohmann::json& spread = j["hover_spread_ns"][key]["100000"];
        CHECK(spread["segments_per_tick"].get<int>() == 256);
        CHECK(spread["segments_asked_max"].get<int>() <= 256 + 3);
        const double p99 = spread["l_d_error_p99_m"].get<double>(), max = spread["l_d_error_max_m"].get<double>();
        CHECK(p99 >= 0.0);
        CHECK(p99 <= max);
        CHECK(max <= 0.02 + 1e-12);
        CHECK(spread["ticks_behind_max"].get<int>() >= 0);
        CHECK(spread["ticks_behind_max"].get<int>() < spread["ticks"].get<int>());
    }
    // The first tick in contact after an approach from 1 cm above at 0.1 and 0.5 m/s (a sample a
    // 1 ms tick: 100 and 20 ticks down to the stroke's first sample, which is 1 mm deep): the
    // finger starts in free space and is in contact by that sample; every tick after it is timed.
    CHECK(md.find("### The first tick in contact, after an approach") != std::string::npos);
    for (const char* key : {"lines", "arcs", "curves", "lines_dense", "arcs_dense", "curves_dense"}) {
        CAPTURE(key);
        const nlohmann::json& fc = j["first_contact"][key]["100000"];
        REQUIRE(fc.size() == 2);
        for (const auto& [speed, approach_ticks] : {std::pair{0.1, 100}, std::pair{0.5, 20}}) {
            const nlohmann::json& f = fc[speed == 0.1 ? 0 : 1];
            CAPTURE(f.dump());
            CHECK(f["speed_m_s"].get<double>() == speed);
            REQUIRE(f["found"].get<bool>());
            CHECK(f["tick"].get<int>() >= 1);
            CHECK(f["tick"].get<int>() <= approach_ticks);
            CHECK(f["ns"].get<double>() > 0.0);
            CHECK(f["later_ns"]["ticks"].get<int>() == approach_ticks + 500 - f["tick"].get<int>() - 1);
            CHECK(f["later_ns"]["median"].get<double>() > 0.0);
        }
    }
    // The energy terms on the seeds' trials (energy_table.hpp): seed 002 at 5 and 10 cm/s, seed
    // 000's block. None faulted; the observer's sum stayed under its threshold (K T / 2 = 0.65 N s/m
    // < b: the loop dissipates), and counted, the hand's turn of the finger would have passed it
    // in a seed 002 trial at each speed (what faulted users' studies). Sliding, the hold and the
    // walk cancel but for the loop's net dissipation: what it generated is negative.
    REQUIRE(j["energy_terms"].size() == 3);
    for (const nlohmann::json& e : j["energy_terms"]) {
        CAPTURE(e.dump());
        CHECK(e["faulted"].get<int>() == 0);
        CHECK(e["peak_observer"].get<double>() < e["threshold"].get<double>());
        CHECK(e["generated"].get<double>() < 0.0);
        CHECK(e["proxy"].get<double>() <= 0.0);
        CHECK(e["hold"].get<double>() > 0.0);
        CHECK(std::abs(e["hold"].get<double>() + e["proxy"].get<double>()) < 0.05 * e["hold"].get<double>());
        if (e["task"].get<std::string>() == "seed 002 bumps") {
            CHECK(e["turn"].get<double>() > 0.0);
            CHECK(e["would_fault"].get<int>() >= 1);
            CHECK(e["peak_with_turn"].get<double>() > e["threshold"].get<double>());
        }
    }
    CHECK(md.find("## Where the energy comes from") != std::string::npos);
    // The simulated study (study_speed.hpp): seed 002's shipped protocol, found from the
    // checkout's root, 10 trials per condition, its hand moving by feel. Each trial is the reach
    // for the surface and 0.3 s of settling, then the 16.4 cm slide at the person's free speed
    // (80 mm/s at the median pace: 2.05 s), slower over the bumps' tops: 4.9 s a trial over 10
    // participants (docs/experiments.md). A trial of less than 3 s would have skipped the slide,
    // one of more than 8 s stalled in it. The stages are parts of the wall time the speed is
    // taken from.
    const nlohmann::json& st = j["simulated_study"];
    CAPTURE(st.dump());
    REQUIRE_FALSE(st.contains("skipped"));
    CHECK(st["trials"].get<int>() == 20);
    CHECK(st["virtual_s"].get<double>() > 20 * 3.0);
    CHECK(st["virtual_s"].get<double>() < 20 * 8.0);
    CHECK(st["x_real_time"].get<double>() == doctest::Approx(st["virtual_s"].get<double>() / st["wall_s"].get<double>()));
    CHECK(st["goal_x_real_time"].get<double>() == 500.0);
    // The goal's figure: the rows' time_s, each trial's slide from its start to its end (2.05 s at
    // the median pace, faster people 1.6 s), so at most the trial's virtual time less the reach
    // and the 0.3 s of settling before the slide.
    CHECK(st["rows_time_s"].get<double>() > 20 * 1.6);
    CHECK(st["rows_time_s"].get<double>() <= st["virtual_s"].get<double>() - 20 * 0.3);
    CHECK(st["x_real_time_by_rows"].get<double>() == doctest::Approx(st["rows_time_s"].get<double>() / st["wall_s"].get<double>()));
    double staged = 0.0;
    for (const char* k : {"servo_tick", "simulated_rig", "tick_records", "servo_scene", "stimulus", "wearable_platform", "perception", "files"}) {
        CAPTURE(k);
        CHECK(st["ms_per_virtual_s"][k].get<double>() >= 0.0);
        staged += st["ms_per_virtual_s"][k].get<double>();
    }
    CHECK(st["ms_per_virtual_s"]["servo_tick"].get<double>() > 0.0);
    CHECK(st["ms_per_virtual_s"]["wearable_platform"].get<double>() == 0.0);  // seed 002 runs on the CLD rig
    CHECK(staged <= st["ms_per_virtual_s"]["all"].get<double>() * (1.0 + 1e-9));
    CHECK(md.find("## Simulated study speed") != std::string::npos);
    // Seed 003 on the wearable platform, each of its 3 stimuli once per task (A and B): 6 trials
    // of 3.41 s each (the arc's sweep; test_trial_profile.cpp), all of it the platform's time.
    const nlohmann::json& sw = j["simulated_study_wearable"];
    CAPTURE(sw.dump());
    REQUIRE_FALSE(sw.contains("skipped"));
    CHECK(sw["trials"].get<int>() == 6);
    CHECK(sw["virtual_s"].get<double>() == doctest::Approx(6 * 3.41).epsilon(0.01));
    CHECK(sw["x_real_time"].get<double>() == doctest::Approx(sw["virtual_s"].get<double>() / sw["wall_s"].get<double>()));
    CHECK_FALSE(sw.contains("goal_x_real_time"));
    CHECK(sw["rows_time_s"].get<double>() > 0.0);
    CHECK(sw["rows_time_s"].get<double>() <= sw["virtual_s"].get<double>() * (1.0 + 1e-9));
    CHECK(sw["ms_per_virtual_s"]["wearable_platform"].get<double>() > 0.0);
    CHECK(sw["ms_per_virtual_s"]["servo_tick"].get<double>() == 0.0);  // no CLD servo: the platform's own loop
    CHECK(sw["ms_per_virtual_s"]["wearable_platform"].get<double>() <= sw["ms_per_virtual_s"]["all"].get<double>() * (1.0 + 1e-9));
    CHECK(md.find("## Simulated study speed on the wearable platform") != std::string::npos);
    // What the user reads: one header, none of the library's per-run context or warnings, the
    // summary tables (issue 19: it was ~800 lines with 80 "built as DEBUG" warnings).
    const std::string out = read_text(CONTACTLAB_BENCH_QUICK_STDOUT);
    auto count = [&](const std::string& what) {
        std::size_t n = 0;
        for (std::size_t at = out.find(what); at != std::string::npos; at = out.find(what, at + 1)) ++n;
        return n;
    };
    CHECK(count("contactlab bench: Google Benchmark on ") == 1);
    CHECK(count("WARNING") == 0);
    CHECK(count("Running contactlab-bench") == 0);
    CHECK(count("## Render frame time") == 1);
    CHECK(count("## Servo beside renderer") == 1);
    CHECK(std::count(out.begin(), out.end(), '\n') < 250);
    // The servo beside the renderer: 2 s a phase at 1 kHz and at 10 kHz, or the reason it could not run.
    const nlohmann::json& sb = j["servo_beside_renderer"];
    if (sb.contains("skipped")) {
        CHECK_FALSE(sb["skipped"].get<std::string>().empty());
        CHECK(md.find("## Servo beside renderer") != std::string::npos);
    } else {
        for (const auto& [rate, figures, ticks] : {std::tuple{"1 kHz", &sb, 2000}, std::tuple{"10 kHz", &sb["rate_10k"], 20000}}) {
            for (const char* phase : {"alone", "beside"}) {
                CAPTURE(rate);
                CAPTURE(phase);
                const nlohmann::json& f = (*figures)[phase];
                CHECK(f["ticks"].get<int>() == ticks);
                const double p50 = f["p50_us"].get<double>(), p99 = f["p99_us"].get<double>();
                CHECK(p50 > 0.0);
                CHECK(p99 >= p50);
                CHECK(f["max_us"].get<double>() >= p99);
                CHECK(f["overruns"].get<int>() <= ticks);
            }
        }
        CHECK(sb["fps"].get<double>() > 0.0);
        CHECK(md.find("| 1 kHz, beside the renderer | ") != std::string::npos);
        CHECK(md.find("| 10 kHz, beside the renderer | ") != std::string::npos);
        CHECK(sb["scheduling"].get<std::string>().find("of each wait polled") != std::string::npos);
        // The bare loop's floor: as many periods as the servo's 10 kHz phases, lateness ordered.
        const nlohmann::json& fl = sb["rate_10k"]["timer_floor"];
        CHECK(fl["ticks"].get<int>() == 20000);
        CHECK(fl["late_p50_us"].get<double>() >= 0.0);
        CHECK(fl["late_p99_us"].get<double>() >= fl["late_p50_us"].get<double>());
        CHECK(fl["late_max_us"].get<double>() >= fl["late_p99_us"].get<double>());
        CHECK(fl["missed"].get<int>() <= 20000);
        CHECK(md.find("The machine's own floor at 10 kHz") != std::string::npos);
    }
    // Every cost-growth case has its contact and free-space (hover) tick times.
    for (const char* key : {"lines", "arcs", "curves", "lines_dense", "arcs_dense", "curves_dense"}) {
        for (const char* n : {"10", "1000", "100000"}) {
            CAPTURE(key);
            CAPTURE(n);
            for (const char* table : {"tick_ns", "hover_ns"}) {
                CAPTURE(table);
                REQUIRE(j[table][key].contains(n));
                const nlohmann::json& st = j[table][key][n];
                const double median = st["median"].get<double>();
                CHECK(std::isfinite(median));
                CHECK(median > 0.0);
                // The tail, in order, and the period misses counted among the ticks.
                CHECK(st["p99"].get<double>() >= median);
                CHECK(st["p999"].get<double>() >= st["p99"].get<double>());
                CHECK(st["max"].get<double>() >= st["p999"].get<double>());
                CHECK(st["over_100us"].get<std::size_t>() <= st["ticks"].get<std::size_t>());
                CHECK(st["over_1ms"].get<std::size_t>() <= st["over_100us"].get<std::size_t>());
            }
        }
    }
}
}
