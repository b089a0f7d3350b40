// test_bench_goals.cpp — the bench's verdicts on its goals (engine/bench/goals.hpp), from made-up
// results placed on each side of every goal's boundary: met at the figure itself, missed just
// past it, and `machine` only where the same run's measure of the code alone (each tick's least
// over the passes; the bare loop's late periods) meets the goal.
#include "engine/bench/goals.hpp"

#include <doctest/doctest.h>

#include <stdexcept>
#include <string>
#include <vector>

using namespace contactlab;
using namespace contactlab::bench;

namespace {

constexpr int kLargest = 100000;

TickStats ticks(double median_ns, double p999_ns, double max_ns) {
    TickStats t;
    t.median_ns = median_ns, t.p99_ns = 0.5 * (median_ns + p999_ns), t.p999_ns = p999_ns, t.max_ns = max_ns;
    t.ticks = 12000;
    return t;
}

// A full run's shape: every kind at 10 and at the largest size, three passes (least figures at half
// the all-ticks ones), every figure well inside its goal; the servo and the study inside theirs.
BenchResults full_run_within_goals() {
    BenchResults r;
    for (const Growth g : {Growth::extent, Growth::dense})
        for (const SegmentKind k : {SegmentKind::lines, SegmentKind::arcs, SegmentKind::curves})
            for (const int n : {10, kLargest}) {
                CostRow row;
                row.scene = {k, g, n};
                row.key = case_key(k, g);
                const double median = n == 10 ? 300.0 : 2400.0;  // lines_dense: 8x
                row.proxy = ticks(median, 50e3, 300e3);
                row.hover = ticks(median, 60e3, 250e3);
                row.proxy_least = ticks(0.9 * median, 25e3, 150e3);
                row.hover_least = ticks(0.9 * median, 30e3, 120e3);
                r.cost.push_back(row);
            }
    ServoBesideRenderer& sb = r.servo_beside;
    sb.skipped.clear();
    sb.alone = {5000, 1, 0.0, 1.05e-3, 1.9e-3};
    sb.beside = {5000, 2, 0.0, 1.06e-3, 2.1e-3};
    sb.alone_10k = {50000, 20, 0.0, 110e-6, 1e-3};
    sb.beside_10k = {50000, 24, 0.0, 112e-6, 1e-3};
    sb.floor_10k = {50000, 30, 1e-8, 40e-6, 2e-3};
    r.study.skipped.clear();
    r.study.profile.wall = 2.0;           // s
    r.study.profile.virtual_s = 1200.0;   // s
    r.study.rows_time_s = 1100.0;         // s: 550x by the rows
    return r;
}

CostRow& row_of(BenchResults& r, const std::string& key, int n) {
    for (CostRow& row : r.cost)
        if (row.key == key && row.scene.segments == n) return row;
    throw std::logic_error("no row " + key);
}

// judge_goals' order.
enum : std::size_t { kP999, kMax, kRatio, kServo10k, kServo1k, kStudy, kGoals };

}  // namespace

TEST_CASE("bench goals: a run inside every goal meets all six, and says so in the page and the JSON") {
    const BenchResults r = full_run_within_goals();
    const std::vector<GoalRow> goals = judge_goals(r);
    REQUIRE(goals.size() == kGoals);
    for (const GoalRow& g : goals) CHECK_MESSAGE(g.verdict == GoalVerdict::met, g.goal, ": ", g.measured);
    CHECK(goals[kP999].measured.find("12 of 12 strokes within 100 us") != std::string::npos);
    CHECK(goals[kRatio].measured.find("8.00x") != std::string::npos);
    CHECK(goals[kStudy].measured.find("550x by the rows (600x by the whole virtual time)") != std::string::npos);
    const std::string md = goals_markdown(goals);
    CHECK(md.rfind("## Goals in this run\n\n6 of 6 measured goals met.", 0) == 0);
    const nlohmann::json j = goals_json(goals);
    REQUIRE(j.size() == kGoals);
    CHECK(j[kRatio]["verdict"] == "met");
}

TEST_CASE("bench goals: p99.9 at 100 us is met, past it the code's own tail decides between machine and missed") {
    BenchResults r = full_run_within_goals();
    CostRow& curves = row_of(r, "curves_dense", kLargest);
    curves.hover.p999_ns = 100e3;  // at the goal
    CHECK(judge_goals(r)[kP999].verdict == GoalVerdict::met);
    curves.hover.p999_ns = 101e3;  // past it, the least of passes (30 us) within
    GoalRow g = judge_goals(r)[kP999];
    CHECK(g.verdict == GoalVerdict::machine);
    CHECK(g.measured.find("11 of 12") != std::string::npos);
    CHECK(g.floor.find("curves_dense hovering 101 us, least of passes 30 us") != std::string::npos);
    CHECK(goals_markdown(judge_goals(r)).find("5 of 6 measured goals met, 1 missed by what the machine did in this run") !=
          std::string::npos);
    curves.hover_least->p999_ns = 101e3;  // slow in every pass: the code's own
    CHECK(judge_goals(r)[kP999].verdict == GoalVerdict::missed);
    // Two strokes over: one slow in every pass (the code's own), one with no passes to split. The
    // code's own miss is what the row says.
    BenchResults both = r;
    row_of(both, "arcs_dense", kLargest).proxy.p999_ns = 120e3;
    row_of(both, "arcs_dense", kLargest).proxy_least.reset();
    g = judge_goals(both)[kP999];
    CHECK(g.verdict == GoalVerdict::missed);
    CHECK(g.floor.find("is the code's own") != std::string::npos);
    curves.hover_least.reset();  // one pass: nothing tells the machine's stalls apart
    g = judge_goals(r)[kP999];
    CHECK(g.verdict == GoalVerdict::missed);
    CHECK(g.floor.find("One pass: the code's own tail and the machine's stalls cannot be told apart") != std::string::npos);
    // The sizes below the largest are not the goal's: a slow tick at 10 segments changes nothing.
    BenchResults small = full_run_within_goals();
    row_of(small, "arcs", 10).proxy.p999_ns = 500e3;
    CHECK(judge_goals(small)[kP999].verdict == GoalVerdict::met);
}

TEST_CASE("bench goals: max at 1 ms is met, a longer tick is the machine's only when its least is within") {
    BenchResults r = full_run_within_goals();
    CostRow& arcs = row_of(r, "arcs_dense", kLargest);
    arcs.proxy.max_ns = 1e6;
    CHECK(judge_goals(r)[kMax].verdict == GoalVerdict::met);
    arcs.proxy.max_ns = 4.43e6;
    CHECK(judge_goals(r)[kMax].verdict == GoalVerdict::machine);
    arcs.proxy_least->max_ns = 1.01e6;
    CHECK(judge_goals(r)[kMax].verdict == GoalVerdict::missed);
}

TEST_CASE("bench goals: the dense ratio at 10x is met, past it the least-of-passes medians decide") {
    BenchResults r = full_run_within_goals();
    CostRow& big = row_of(r, "lines_dense", kLargest);
    big.proxy.median_ns = 3000.0;  // 3,000 / 300: exactly 10x
    CHECK(judge_goals(r)[kRatio].verdict == GoalVerdict::met);
    big.proxy.median_ns = 3003.0;  // 10.01x; least 2,160 / 270 = 8x
    const GoalRow g = judge_goals(r)[kRatio];
    CHECK(g.verdict == GoalVerdict::machine);
    CHECK(g.floor.find("8.00x") != std::string::npos);
    big.proxy_least->median_ns = 2703.0;  // 10.01x in the code's own ticks too
    CHECK(judge_goals(r)[kRatio].verdict == GoalVerdict::missed);
    // One pass (no least figures): missed, and the row says why it cannot tell.
    big.proxy_least.reset();
    const GoalRow one = judge_goals(r)[kRatio];
    CHECK(one.verdict == GoalVerdict::missed);
    CHECK(one.floor.rfind("One pass: the code's own tail and the machine's stalls cannot be told apart", 0) == 0);
    // A run without the 10-segment row cannot judge it.
    BenchResults no_small = full_run_within_goals();
    std::erase_if(no_small.cost, [](const CostRow& row) { return row.key == "lines_dense" && row.scene.segments == 10; });
    CHECK(judge_goals(no_small)[kRatio].verdict == GoalVerdict::not_measured);
}

TEST_CASE("bench goals: 10 kHz beside the renderer, overruns against alone and the bare loop's floor, p99 ratio") {
    BenchResults r = full_run_within_goals();
    ServoBesideRenderer& sb = r.servo_beside;
    sb.beside_10k.overruns = 25;  // 25 - 20 in 50,000: exactly 1 per 10,000 more
    CHECK(judge_goals(r)[kServo10k].verdict == GoalVerdict::met);
    sb.beside_10k.overruns = 26;  // 1.2 per 10,000 more; 5.2 per 10,000 against the bare loop's 6
    CHECK(judge_goals(r)[kServo10k].verdict == GoalVerdict::machine);
    sb.beside_10k.overruns = 30;  // as often as the bare loop (30 in 50,000): still no more often
    CHECK(judge_goals(r)[kServo10k].verdict == GoalVerdict::machine);
    CHECK(judge_goals(r)[kServo10k].floor.find("Noisy references") == std::string::npos);
    sb.beside_10k.overruns = 31;  // more often than the bare loop (30)
    CHECK(judge_goals(r)[kServo10k].verdict == GoalVerdict::missed);
    sb.beside_10k.overruns = 24;
    sb.beside_10k.p99 = 1.11 * sb.alone_10k.p99;  // overruns fine, p99 past 1.1x: the floor does not excuse it
    CHECK(judge_goals(r)[kServo10k].verdict == GoalVerdict::missed);
    // Met against an alone phase that overran 11 per 10,000 (the phases run one after another):
    // the verdict stands by the goal's definition and says its reference was noisy.
    sb.beside_10k.p99 = sb.alone_10k.p99;
    sb.alone_10k.overruns = 55, sb.beside_10k.overruns = 50;
    GoalRow noisy = judge_goals(r)[kServo10k];
    CHECK(noisy.verdict == GoalVerdict::met);
    CHECK(noisy.floor.find("Noisy references: alone 11.0 and the bare loop 6.0 overruns per 10,000 ticks") == 0);
    sb.skipped = "one CPU";
    const GoalRow g = judge_goals(r)[kServo10k];
    CHECK(g.verdict == GoalVerdict::not_measured);
    CHECK(g.floor == "not measured: one CPU");
}

TEST_CASE("bench goals: 1 kHz beside the renderer, 2 per 5,000 more is met, more is missed (no 1 kHz floor)") {
    BenchResults r = full_run_within_goals();
    ServoBesideRenderer& sb = r.servo_beside;
    sb.beside.overruns = 3;  // 3 - 1 in 5,000
    CHECK(judge_goals(r)[kServo1k].verdict == GoalVerdict::met);
    sb.beside.overruns = 4;
    GoalRow g = judge_goals(r)[kServo1k];
    CHECK(g.verdict == GoalVerdict::missed);
    CHECK(g.floor.find("no bare loop at 1 kHz") != std::string::npos);
    // The 10 kHz bare loop is no floor for 1 kHz: however often it stalled, the miss stands.
    sb.floor_10k.missed = 5000;
    g = judge_goals(r)[kServo1k];
    CHECK(g.verdict == GoalVerdict::missed);
    // Nor is it 1 kHz's reference: a met verdict is called noisy by its alone phase only.
    sb.beside.overruns = 1;
    CHECK(judge_goals(r)[kServo1k].verdict == GoalVerdict::met);
    CHECK(judge_goals(r)[kServo1k].floor.empty());
    sb.alone.overruns = 6, sb.beside.overruns = 6;  // 12 per 10,000 alone
    g = judge_goals(r)[kServo1k];
    CHECK(g.verdict == GoalVerdict::met);
    CHECK(g.floor.rfind("Noisy reference: alone 12.0 overruns per 10,000 ticks", 0) == 0);
}

TEST_CASE("bench goals: seed 002 at 500x by the rows is met, below is missed, not run is not measured") {
    BenchResults r = full_run_within_goals();
    r.study.rows_time_s = 1000.0;  // 500x
    CHECK(judge_goals(r)[kStudy].verdict == GoalVerdict::met);
    r.study.rows_time_s = 999.0;
    CHECK(judge_goals(r)[kStudy].verdict == GoalVerdict::missed);
    r.study.skipped = "no protocol file";
    CHECK(judge_goals(r)[kStudy].verdict == GoalVerdict::not_measured);
    const std::string md = goals_markdown(judge_goals(r));
    CHECK(md.find("5 of 5 measured goals met.") != std::string::npos);
    CHECK(md.find("| not measured | not measured: no protocol file |") != std::string::npos);
}

TEST_CASE("bench goals: a --quick run does not judge the tick goals (a faster stroke, one pass), the rest it does") {
    BenchResults r = full_run_within_goals();
    r.quick = true;
    const std::vector<GoalRow> goals = judge_goals(r);
    REQUIRE(goals.size() == kGoals);
    for (const std::size_t i : {kP999, kMax, kRatio}) {
        CHECK(goals[i].verdict == GoalVerdict::not_measured);
        CHECK(goals[i].floor.find("a --quick run") != std::string::npos);
    }
    for (const std::size_t i : {kServo10k, kServo1k, kStudy}) CHECK(goals[i].verdict == GoalVerdict::met);
    CHECK(goals_markdown(goals).find("3 of 3 measured goals met.") != std::string::npos);
}
