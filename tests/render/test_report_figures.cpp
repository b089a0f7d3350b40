// test_report_figures.cpp — the seeds' figures in `experiment analyze --report`
// (engine/reports/experiment_figures.hpp): small results tables with counts chosen by hand, the points
// and intervals each figure must show (Wilson bounds worked independently, to 1e-4), the rules
// (categorical axes, no lines, n on every point, proportions in [0, 1], distinct colours), and
// golden images of each chart drawn by lavapipe.
#include "render_fixture.hpp"
#include "snapshot.hpp"

#include "engine/reports/experiment_figures.hpp"
#include "engine/reports/threshold_figures.hpp"
#include "engine/render/chart_image.hpp"

#include <nlohmann/json.hpp>

#include <doctest/doctest.h>

#include <cmath>
#include <set>

using namespace render_test;
using contactlab::reports::ReportFigure;
using contactlab::reports::seed_figures;
using contactlab::reports::seed_of;
using contactlab::experiments::ResultsTable;

namespace {

const ReportFigure& figure(const std::vector<ReportFigure>& figures, const std::string& file) {
    for (const ReportFigure& f : figures)
        if (f.file == file) return f;
    FAIL("no figure " << file);
    return figures.front();
}

// Every figure: categorical x, markers only, one colour per series, n said (on the points or on
// the x axis), proportions and their bars inside [0, 1].
void check_rules(const ReportFigure& f, bool proportion) {
    CAPTURE(f.file);
    CHECK_FALSE(f.chart.x.categories.empty());
    CHECK_FALSE(f.caption.empty());
    std::set<std::tuple<int, int, int>> colours;
    for (const ChartSeries& s : f.chart.series) {
        CHECK_FALSE(s.connect);
        colours.insert({s.color.r, s.color.g, s.color.b});
        const bool n_on_points = !s.labels.empty();
        CHECK((n_on_points || f.chart.x.title.find("(n = ") != std::string::npos));
        for (std::size_t i = 0; i < s.y.size(); ++i) {
            if (n_on_points) CHECK(s.labels[i].rfind("n=", 0) == 0);
            if (!proportion) continue;
            CHECK(s.y[i] >= 0.0);
            CHECK(s.y[i] <= 1.0);
            if (i < s.y_low.size() && std::isfinite(s.y_low[i])) {
                CHECK(s.y_low[i] >= 0.0);
                CHECK(s.y_high[i] <= 1.0);
            }
        }
    }
    CHECK(colours.size() == f.chart.series.size());
}

void check_golden(const ReportFigure& f, const std::string& name) {
    const Image img = render_chart(lavapipe(), f.chart);
    const SnapshotResult r = check_snapshot(name, img);
    INFO(r.message);
    CHECK(r.ok);
    CHECK(lavapipe().validation_messages() == 0);
}

ResultsTable table(std::vector<std::string> columns) {
    ResultsTable t;
    t.origin = "test";
    t.columns = std::move(columns);
    return t;
}

// Seed 000: d = 4 cm, force: 3 of 4 failed (times of the one success: 3 s); force+cld: 0 of 4
// (2, 3, 4, 5 s). d = 6 cm: force+cld only, 1 of 2 failed.
ResultsTable seed000_table() {
    ResultsTable t = table({"participant", "condition", "trial", "stimulus", "response", "correct", "valid", "warmup",
                            "time_s", "failed"});
    auto row = [&](const char* c, const char* d, const char* time, int failed) {
        t.rows.push_back({"p1", c, "1", d, "", "", "1", "0", time, std::to_string(failed)});
    };
    row("force", "0.04", "9", 1);
    row("force", "0.04", "9", 1);
    row("force", "0.04", "9", 1);
    row("force", "0.04", "3", 0);
    row("force+cld", "0.04", "2", 0);
    row("force+cld", "0.04", "3", 0);
    row("force+cld", "0.04", "4", 0);
    row("force+cld", "0.04", "5", 0);
    row("force+cld", "0.06", "9", 1);
    row("force+cld", "0.06", "4", 0);
    t.rows.push_back({"p1", "force", "0", "0.04", "", "", "1", "1", "1", "1"});  // warm-up: left out
    t.rows.push_back({"p1", "force", "9", "0.04", "", "", "0", "0", "1", "0"});  // invalid: left out
    return t;
}

}  // namespace

TEST_CASE("report figures: seed 000 failures per d with 99 % Wilson intervals, times of successes with t intervals") {
    const ResultsTable t = seed000_table();
    CHECK(seed_of(t) == "000");
    const auto figures = seed_figures(t);
    const ReportFigure& f = figure(figures, "seed000_failures.png");
    check_rules(f, true);
    CHECK(f.chart.x.categories == std::vector<std::string>{"4", "6"});  // cm
    REQUIRE(f.chart.series.size() == 2);
    const ChartSeries& force = f.chart.series[0];
    CHECK(force.name == "force");
    REQUIRE(force.y.size() == 1);  // no point at d = 6 cm, where force has no trial
    CHECK(force.y[0] == doctest::Approx(0.75));
    CHECK(std::abs(force.y_low[0] - 0.218126) < 1e-4);
    CHECK(std::abs(force.y_high[0] - 0.969934) < 1e-4);
    CHECK(force.labels[0] == "n=4");
    const ChartSeries& cld = f.chart.series[1];
    REQUIRE(cld.y.size() == 2);
    CHECK(cld.y[0] == 0.0);
    CHECK(cld.y_low[0] == 0.0);
    CHECK(std::abs(cld.y_high[0] - 0.623880) < 1e-4);
    CHECK(cld.y[1] == doctest::Approx(0.5));
    // Side by side at d = 4 cm, each within its category's slot.
    CHECK(force.x[0] < cld.x[0]);
    CHECK(std::abs(force.x[0]) < 0.5);
    CHECK(std::abs(cld.x[1] - 1.0) < 0.5);

    const ReportFigure& times = figure(figures, "seed000_time.png");
    check_rules(times, false);
    REQUIRE(times.chart.series.size() == 2);
    CHECK(times.chart.series[0].y[0] == doctest::Approx(3.0));
    CHECK(std::isnan(times.chart.series[0].y_low[0]));  // one success: no interval
    // force+cld at 4 cm: 2..5 s, mean 3.5, sd sqrt(5/3), t_{0.995, 3} = 5.8409093.
    const double half = 5.8409093 * std::sqrt(5.0 / 3.0) / 2.0;
    CHECK(times.chart.series[1].y[0] == doctest::Approx(3.5));
    CHECK(times.chart.series[1].y_low[0] == doctest::Approx(3.5 - half).epsilon(1e-6));
    CHECK(times.chart.series[1].y_high[0] == doctest::Approx(3.5 + half).epsilon(1e-6));
    check_golden(f, "report_seed000_failures");
}

TEST_CASE("report figures: seed 002 per-condition means with standard errors, small against large, error by small bumps") {
    ResultsTable t = table({"participant", "condition", "trial", "stimulus", "response", "correct", "valid", "warmup",
                            "small_bumps", "large_bumps"});
    // Two participants. p1 F: small-only 2 bumps answered 1 (wrong), large-only 1 answered 1 (right);
    // p2 F: both right. F+CLD: all four right. Stimuli: (small, large) = (2, 0) and (0, 1).
    auto row = [&](const char* p, const char* c, const char* stim, const char* resp, const char* small, const char* large) {
        t.rows.push_back({p, c, "1", stim, resp, std::string(stim) == resp ? "1" : "0", "1", "0", small, large});
    };
    row("p1", "F", "2", "1", "2", "0");
    row("p1", "F", "1", "1", "0", "1");
    row("p2", "F", "2", "2", "2", "0");
    row("p2", "F", "1", "1", "0", "1");
    for (const char* p : {"p1", "p2"}) {
        row(p, "F+CLD", "2", "2", "2", "0");
        row(p, "F+CLD", "1", "1", "0", "1");
    }
    CHECK(seed_of(t) == "002");
    const auto figures = seed_figures(t);
    const ReportFigure& pc = figure(figures, "seed002_proportion_correct.png");
    check_rules(pc, true);
    REQUIRE(pc.chart.series.size() == 2);
    // F: p1 0.5, p2 1.0 -> mean 0.75, SE = sd / sqrt(2) = 0.25.
    CHECK(pc.chart.series[0].y[0] == doctest::Approx(0.75));
    CHECK(pc.chart.series[0].y_low[0] == doctest::Approx(0.5));
    CHECK(pc.chart.series[0].y_high[0] == doctest::Approx(1.0));
    CHECK(pc.chart.series[1].y[0] == doctest::Approx(1.0));
    CHECK(pc.chart.x.title.find("(n = 2 participants per point)") != std::string::npos);

    const ReportFigure& sl = figure(figures, "seed002_small_large.png");
    check_rules(sl, true);
    CHECK(sl.chart.x.categories == std::vector<std::string>{"small bumps only", "large bumps only"});
    // F, small only: p1 0, p2 1 -> 0.5 +- 0.5; large only: both right -> 1 (SE 0).
    CHECK(sl.chart.series[0].y[0] == doctest::Approx(0.5));
    CHECK(sl.chart.series[0].y_high[0] == doctest::Approx(1.0));
    CHECK(sl.chart.series[0].y[1] == doctest::Approx(1.0));

    const ReportFigure& err = figure(figures, "seed002_error_by_small_bumps.png");
    check_rules(err, false);
    CHECK(err.chart.x.categories == std::vector<std::string>{"0", "2"});
    // F, 2 small bumps: |1 - 2| and |2 - 2| -> mean 0.5 over n = 2 trials.
    CHECK(err.chart.series[0].y[1] == doctest::Approx(0.5));
    CHECK(err.chart.series[0].y[0] == doctest::Approx(0.0));
    check_golden(sl, "report_seed002_small_large");
}

TEST_CASE("report figures: seed 003 per height and task, seed 004 phi per e and k (Table I gives 0.766)") {
    ResultsTable t3 = table({"participant", "condition", "trial", "stimulus", "response", "correct", "valid", "warmup",
                             "motion"});
    for (int i = 0; i < 10; ++i) t3.rows.push_back({"p1", "A", "1", "10", "10", i < 8 ? "1" : "0", "1", "0", "A"});
    for (int i = 0; i < 10; ++i) t3.rows.push_back({"p1", "B", "1", "20", "20", i < 5 ? "1" : "0", "1", "0", "B"});
    CHECK(seed_of(t3) == "003");
    const auto figures3 = seed_figures(t3);
    const ReportFigure& f3 = figure(figures3, "seed003_proportion_correct.png");
    check_rules(f3, true);
    CHECK(f3.chart.x.categories == std::vector<std::string>{"10", "20"});
    CHECK(f3.chart.series[0].y[0] == doctest::Approx(0.8));
    CHECK(f3.chart.series[1].x[0] > 0.5);  // task B's only point sits in the 20 mm slot

    ResultsTable t4 = table({"participant", "condition", "trial", "stimulus", "response", "correct", "valid", "warmup",
                             "e", "k"});
    auto add = [&](const char* e, const char* k, const char* stim, const char* resp, int count) {
        for (int i = 0; i < count; ++i) t4.rows.push_back({"p1", "c", "1", stim, resp, "0", "1", "0", e, k});
    };
    add("0.4", "0.75", "45", "A", 41);  // seed 004 Table I
    add("0.4", "0.75", "45", "B", 9);
    add("0.4", "0.75", "135", "A", 3);
    add("0.4", "0.75", "135", "B", 47);
    add("1", "0.75", "45", "A", 25);  // no association at all
    add("1", "0.75", "45", "B", 25);
    add("1", "0.75", "135", "A", 25);
    add("1", "0.75", "135", "B", 25);
    CHECK(seed_of(t4) == "004");
    const auto figures4 = seed_figures(t4);
    const ReportFigure& f4 = figure(figures4, "seed004_phi.png");
    check_rules(f4, true);
    CHECK(f4.chart.x.categories == std::vector<std::string>{"0.4", "1"});
    REQUIRE(f4.chart.series.size() == 1);
    CHECK(f4.chart.series[0].name == "k = 0.75 N/mm");
    // (41 47 - 9 3) / sqrt(50 50 44 56) = 0.76554.
    CHECK(f4.chart.series[0].y[0] == doctest::Approx(0.76554).epsilon(1e-4));
    CHECK(f4.chart.series[0].y[1] == doctest::Approx(0.0).scale(1.0));
    CHECK(f4.chart.x.title.find("(n = 100 trials per point)") != std::string::npos);
    check_golden(f3, "report_seed003");
    check_golden(f4, "report_seed004");
}

TEST_CASE("report figures: another protocol's results get no seed figure") {
    ResultsTable t = table({"participant", "condition", "trial", "stimulus", "response"});
    t.rows.push_back({"p1", "left", "1", "a", "a"});
    CHECK(seed_of(t).empty());
    CHECK(seed_figures(t).empty());
}

TEST_CASE("report figures: a staircase's fit with an unbounded interval fits its data, with no text on text or data") {
    // The edge-sharpness force condition as a new user met it: nine levels, most trials at two
    // of them, a threshold of 1.03 mm whose interval the data do not bound, three tracks.
    nlohmann::json a = nlohmann::json::parse(R"({
      "stimulus_unit": "mm",
      "conditions": {"force": {
        "psychometric": {"function": "logistic", "guess": 0.5, "lapse": 0.06, "lapse_at_bound": true,
          "threshold": 1.03, "scale": null, "scale_undefined": "not bounded by these data: flat",
          "threshold_ci": null, "threshold_ci_undefined": "not bounded by these data: its lower end (-7194): far below",
          "ml": {"threshold": 1.03, "scale": 2.9, "lapse": 0.06},
          "bins": [{"x": 0.25, "n": 3, "k": 2}, {"x": 0.5, "n": 5, "k": 3}, {"x": 1, "n": 9, "k": 6}, {"x": 1.5, "n": 12, "k": 8},
                   {"x": 2, "n": 20, "k": 14}, {"x": 2.25, "n": 31, "k": 23}, {"x": 2.5, "n": 40, "k": 30}, {"x": 2.75, "n": 28, "k": 22},
                   {"x": 3, "n": 25, "k": 21}, {"x": 4, "n": 6, "k": 5}, {"x": 6, "n": 6, "k": 6}]},
        "adaptive": {"estimate": 3.23, "judged": 3, "converged": 0},
        "participants": {}}}})");
    for (int p = 1; p <= 3; ++p) {
        nlohmann::json track = nlohmann::json::array();
        for (int i = 0; i < 60; ++i) track.push_back({6.0 - 0.05 * i * p / 2.0, 1, i % 7 == 3 ? 1 : 0});
        a["conditions"]["force"]["participants"]["sim" + std::to_string(p)]["adaptive"] = {{"track", track}};
    }
    const auto figures = contactlab::reports::threshold_figures(a);
    REQUIRE(figures.size() == 2);
    for (const ReportFigure& f : figures) {
        CAPTURE(f.file);
        contactlab::render::DrawList out(f.chart.width, f.chart.height);
        const auto l = contactlab::render::draw_chart(f.chart, out);
        for (std::size_t i = 0; i < l.text_boxes.size(); ++i) {
            for (std::size_t j = i + 1; j < l.text_boxes.size(); ++j) CHECK_FALSE(l.text_boxes[i].intersects(l.text_boxes[j]));
            for (const auto& m : l.mark_boxes) CHECK_FALSE(l.text_boxes[i].intersects(m));
        }
    }
    const ReportFigure& fit = figure(figures, "psychometric_force.png");
    // No line for the interval the data do not bound, and an x axis from the data: the bins
    // span most of it, not one pixel column.
    for (const auto& r : fit.chart.references) CHECK(r.label.find("interval") == std::string::npos);
    contactlab::render::DrawList out(fit.chart.width, fit.chart.height);
    const auto l = contactlab::render::draw_chart(fit.chart, out);
    CHECK((6.0 - 0.25) / (l.x.hi - l.x.lo) > 0.8);
    CHECK(fit.caption.find("not bounded by these data (") != std::string::npos);
    CHECK(fit.caption.find("6: 6/6") != std::string::npos);  // the counts, for labels with no room
}
