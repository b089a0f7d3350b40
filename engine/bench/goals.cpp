// goals.cpp — judging one bench run against the goals (goals.hpp).
//
// Index
//   helpers        per-10,000 rates, the largest size's rows (figures: tick_stats.hpp)
//   tick goals     p99.9 and max at the largest size, contact and hovering; the dense ratio
//   servo goals    10 kHz and 1 kHz beside the renderer against alone, the bare loop's floor
//   study goal     seed 002 at 500x real time by the rows
//   output         Markdown and JSON
#include "engine/bench/goals.hpp"

#include <algorithm>
#include <cstdio>
#include <optional>

namespace contactlab::bench {
namespace {

// ---------------------------------------------------------------------------------------------
// helpers

// Events per `per` ticks (0 with no ticks).
double rate_per(std::uint64_t events, std::uint64_t ticks, double per) {
    return ticks > 0 ? per * static_cast<double>(events) / static_cast<double>(ticks) : 0.0;
}

int largest_size(const BenchResults& r) {
    int n = 0;
    for (const CostRow& row : r.cost) n = std::max(n, row.scene.segments);
    return n;
}

const CostRow* find_row(const BenchResults& r, const std::string& key, int segments) {
    for (const CostRow& row : r.cost)
        if (row.key == key && row.scene.segments == segments) return &row;
    return nullptr;
}

// ---------------------------------------------------------------------------------------------
// tick goals

constexpr const char* kOnePass = ". One pass: the code's own tail and the machine's stalls cannot be told apart";

// One figure of one stroke (a kind's contact or hover stroke at the largest size): every tick's,
// and the code's own (each tick's least over the passes) when the run had passes.
struct TickFigure {
    std::string name;  // "curves_dense hovering"
    double all_ns = 0.0;
    std::optional<double> least_ns;
};

// A tick goal over every stroke at the largest size: met when every stroke's figure is within
// `limit_ns`; `machine` when each one that is not has its least-of-passes figure within it.
GoalRow judge_tick_figures(std::string goal, const std::vector<TickFigure>& figures, double limit_ns) {
    GoalRow g;
    g.goal = std::move(goal);
    if (figures.empty()) return g;  // not measured
    std::vector<const TickFigure*> over;
    const TickFigure* slowest = &figures.front();
    for (const TickFigure& f : figures) {
        if (f.all_ns > limit_ns) over.push_back(&f);
        if (f.all_ns > slowest->all_ns) slowest = &f;
    }
    g.measured = std::to_string(figures.size() - over.size()) + " of " + std::to_string(figures.size()) +
                 " strokes within " + duration(limit_ns) + "; slowest " + slowest->name + " " + duration(slowest->all_ns);
    if (over.empty()) {
        g.verdict = GoalVerdict::met;
        return g;
    }
    bool one_pass = false, code_misses = false;
    std::string least;
    for (const TickFigure* f : over) {
        least += (least.empty() ? "" : "; ") + f->name + " " + duration(f->all_ns) + ", least of passes " +
                 (f->least_ns ? duration(*f->least_ns) : std::string("not measured"));
        if (!f->least_ns) one_pass = true;
        else if (*f->least_ns > limit_ns) code_misses = true;
    }
    const bool code_meets = !one_pass && !code_misses;
    g.verdict = code_meets ? GoalVerdict::machine : GoalVerdict::missed;
    // A stroke slow in every pass is the code's own, whatever the others say; then a stroke with
    // one pass, which cannot be split.
    g.floor = least + (code_meets    ? ". Rule: every stroke that missed meets the goal by each tick's least time over "
                                       "the passes of the same stroke (the code's own tail); the rest is the machine's "
                                       "stalls in single passes"
                       : code_misses ? ". Rule: a stroke missed by its least time over the passes too is the code's own"
                                     : kOnePass);
    return g;
}

std::vector<GoalRow> tick_goals(const BenchResults& r) {
    const int n = largest_size(r);
    if (r.quick) {
        // A --quick run's stroke is 4x faster (20 cm/s) with one pass and fewer ticks: its tails
        // are not the goals' strokes, so it does not judge them.
        const std::string why = "not measured: a --quick run (one pass of a faster stroke); a full run judges it";
        return {{"every bench kind at the largest size, in contact and hovering: p99.9 at most " + duration(kGoalTickP999Ns),
                 "", GoalVerdict::not_measured, why},
                {"the same: max at most " + duration(kGoalTickMaxNs), "", GoalVerdict::not_measured, why},
                {"dense against sparse: lines_dense median at the largest size over 10 segments, at most " +
                     printf_text("%.0fx", kGoalDenseRatio),
                 "", GoalVerdict::not_measured, why}};
    }
    // A least-of-passes figure, when the run had passes.
    auto opt = [](const std::optional<TickStats>& s, double TickStats::*field) -> std::optional<double> {
        if (!s) return std::nullopt;
        return (*s).*field;
    };
    std::vector<TickFigure> p999, max;
    for (const CostRow& row : r.cost) {
        if (row.scene.segments != n) continue;
        p999.push_back({row.key + " in contact", row.proxy.p999_ns, opt(row.proxy_least, &TickStats::p999_ns)});
        p999.push_back({row.key + " hovering", row.hover.p999_ns, opt(row.hover_least, &TickStats::p999_ns)});
        max.push_back({row.key + " in contact", row.proxy.max_ns, opt(row.proxy_least, &TickStats::max_ns)});
        max.push_back({row.key + " hovering", row.hover.max_ns, opt(row.hover_least, &TickStats::max_ns)});
    }
    const std::string at = " at " + std::to_string(n) + " segments, in contact and hovering";
    std::vector<GoalRow> goals;
    goals.push_back(judge_tick_figures("every bench kind" + at + ": p99.9 at most " + duration(kGoalTickP999Ns), p999,
                                       kGoalTickP999Ns));
    goals.push_back(judge_tick_figures("the same: max at most " + duration(kGoalTickMaxNs), max, kGoalTickMaxNs));

    // The dense ratio: lines_dense's median at the largest size over its median at 10 segments.
    GoalRow ratio;
    ratio.goal = "dense against sparse: lines_dense median at " + std::to_string(n) + " over 10 segments, at most " +
                 printf_text("%.0fx", kGoalDenseRatio);
    const CostRow* big = find_row(r, "lines_dense", n);
    const CostRow* small = find_row(r, "lines_dense", 10);
    if (big && small && small->proxy.median_ns > 0.0 && n > 10) {
        const double x = big->proxy.median_ns / small->proxy.median_ns;
        ratio.measured = duration(big->proxy.median_ns) + " against " + duration(small->proxy.median_ns) + printf_text(", %.2fx", x);
        if (x <= kGoalDenseRatio) {
            ratio.verdict = GoalVerdict::met;
        } else if (big->proxy_least && small->proxy_least && small->proxy_least->median_ns > 0.0) {
            const double xl = big->proxy_least->median_ns / small->proxy_least->median_ns;
            ratio.verdict = xl <= kGoalDenseRatio ? GoalVerdict::machine : GoalVerdict::missed;
            ratio.floor = "medians of each tick's least over the passes: " + duration(big->proxy_least->median_ns) +
                          " against " + duration(small->proxy_least->median_ns) + printf_text(", %.2fx. Rule: ", xl) +
                          (xl <= kGoalDenseRatio ? "the code's own ticks meet the ratio" : "the code's own ticks miss it too");
        } else {
            ratio.verdict = GoalVerdict::missed;
            ratio.floor = std::string(kOnePass + 2);  // without the leading ". "
        }
    }
    goals.push_back(ratio);
    return goals;
}

// ---------------------------------------------------------------------------------------------
// servo goals

// The phases (alone, beside, the bare loop) run one after another, so a noisy spell in one of them
// moves the comparison: an alone phase that overran often makes "no more than alone" easy, a bare
// loop that stalled often excuses the servo beside the renderer. A met or machine verdict says so
// when its references overran more than kNoisyReference per 10,000 ticks (ten times the 10 kHz
// goal's allowance); empty otherwise.
constexpr double kNoisyReference = 10.0;  // overruns per 10,000 ticks

std::string noisy_reference(const ServoBesideRenderer& sb, const ServoPeriodFigures& alone, bool ten_khz) {
    const double alone_rate = rate_per(alone.overruns, alone.ticks, 10000.0);
    const double floor_rate = rate_per(sb.floor_10k.missed, sb.floor_10k.ticks, 10000.0);
    const std::string tail =
        printf_text("%.0f; the phases run one after another, so a quieter run is the firmer verdict", kNoisyReference);
    if (!ten_khz)  // the bare loop runs at 10 kHz, in a phase of its own: 1 kHz's reference is its alone phase
        return alone_rate <= kNoisyReference
                   ? ""
                   : printf_text("Noisy reference: alone %.1f overruns per 10,000 ticks, over ", alone_rate) + tail;
    if (alone_rate <= kNoisyReference && floor_rate <= kNoisyReference) return "";
    return printf_text("Noisy references: alone %.1f and the bare loop %.1f overruns per 10,000 ticks, over ", alone_rate,
                floor_rate) +
           tail;
}

GoalRow servo_goal(const ServoBesideRenderer& sb, bool ten_khz) {
    GoalRow g;
    const double per = ten_khz ? 10000.0 : 5000.0;
    const double allowed = ten_khz ? kGoalExtraOverruns10k : kGoalExtraOverruns1k;
    g.goal = std::string("servo at ") + (ten_khz ? "10 kHz" : "1 kHz") + " beside the renderer: at most " +
             printf_text("%.0f overrun(s) per %.0f ticks more than alone, p99 within ", allowed, per) +
             printf_text("%.1fx of alone", kGoalP99Ratio);
    if (!sb.skipped.empty()) {
        g.floor = "not measured: " + sb.skipped;
        return g;
    }
    const ServoPeriodFigures& alone = ten_khz ? sb.alone_10k : sb.alone;
    const ServoPeriodFigures& beside = ten_khz ? sb.beside_10k : sb.beside;
    if (alone.ticks == 0 || beside.ticks == 0 || !(alone.p99 > 0.0)) return g;
    const double beside_rate = rate_per(beside.overruns, beside.ticks, per);
    const double extra = beside_rate - rate_per(alone.overruns, alone.ticks, per);
    const double p99_ratio = beside.p99 / alone.p99;
    g.measured = std::to_string(beside.overruns) + " overruns in " + std::to_string(beside.ticks) + " beside, " +
                 std::to_string(alone.overruns) + " in " + std::to_string(alone.ticks) + " alone" +
                 printf_text(" (%+.1f per %.0f); ", extra, per) + printf_text("p99 %.3fx", p99_ratio);
    const double floor_rate = rate_per(sb.floor_10k.missed, sb.floor_10k.ticks, 10000.0);
    const std::string bare = "the bare loop at 10 kHz with no work on the servo's CPU: " +
                             std::to_string(sb.floor_10k.missed) + " of " + std::to_string(sb.floor_10k.ticks) +
                             " periods a whole period late";
    if (extra <= allowed && p99_ratio <= kGoalP99Ratio) {
        g.verdict = GoalVerdict::met;
        g.floor = noisy_reference(sb, alone, ten_khz);
    } else if (ten_khz && p99_ratio <= kGoalP99Ratio && sb.floor_10k.ticks > 0 && beside_rate <= floor_rate) {
        // (at 10 kHz `per` is 10,000, so beside_rate and floor_rate are in the same unit)
        g.verdict = GoalVerdict::machine;
        g.floor = bare + printf_text(" (%.1f per 10,000). Rule: beside the renderer the servo overran no more often (%.1f per "
                              "10,000) than a loop doing nothing on the same CPU in the same run",
                              floor_rate, beside_rate);
        const std::string noisy = noisy_reference(sb, alone, ten_khz);
        if (!noisy.empty()) g.floor += ". " + noisy;
    } else {
        g.verdict = GoalVerdict::missed;
        if (sb.floor_10k.ticks > 0)
            g.floor = bare + printf_text(" (%.1f per 10,000)", floor_rate) +
                      (ten_khz ? printf_text("; the servo beside the renderer overran %.1f per 10,000", beside_rate)
                               : std::string("; no bare loop at 1 kHz in this run (tools/servo-beside-editor's rounds "
                                             "give the hypervisor's steal time on the servo's CPU)"));
    }
    return g;
}

// ---------------------------------------------------------------------------------------------
// study goal

GoalRow study_goal(const StudySpeed& st) {
    GoalRow g;
    g.goal = "one simulated participant of seed 002 on one core: at least " + printf_text("%.0fx", kStudySpeedGoal) +
             " real time by the rows' time_s";
    if (!st.skipped.empty()) {
        g.floor = "not measured: " + st.skipped;
        return g;
    }
    const double x = st.x_real_time_by_rows();
    g.measured = printf_text("%.0fx by the rows (%.0fx by the whole virtual time)", x, st.x_real_time());
    g.verdict = x >= kStudySpeedGoal ? GoalVerdict::met : GoalVerdict::missed;
    return g;
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// output

std::vector<GoalRow> judge_goals(const BenchResults& r) {
    std::vector<GoalRow> goals = tick_goals(r);
    goals.push_back(servo_goal(r.servo_beside, true));
    goals.push_back(servo_goal(r.servo_beside, false));
    goals.push_back(study_goal(r.study));
    return goals;
}

const char* verdict_name(GoalVerdict v) {
    switch (v) {
        case GoalVerdict::met: return "met";
        case GoalVerdict::machine: return "machine";
        case GoalVerdict::missed: return "missed";
        case GoalVerdict::not_measured: break;
    }
    return "not measured";
}

std::string goals_markdown(const std::vector<GoalRow>& goals) {
    int met = 0, machine = 0, measured = 0;
    for (const GoalRow& g : goals) {
        met += g.verdict == GoalVerdict::met;
        machine += g.verdict == GoalVerdict::machine;
        measured += g.verdict != GoalVerdict::not_measured;
    }
    std::string md = "## Goals in this run\n\n" + std::to_string(met) + " of " + std::to_string(measured) +
                     " measured goals met";
    if (machine > 0) md += ", " + std::to_string(machine) + " missed by what the machine did in this run (`machine`)";
    md += ". `machine`: missed by the figure a user meets, while the same run shows the miss is the machine's (the "
          "code's own tail, each tick's least over the passes, meets the goal; or the servo overran no more often than "
          "a bare loop doing nothing on its CPU); the row gives the figure and the rule. The CHAI3D side by side is "
          "`tools/peer-chai3d`, not this run.\n\n"
          "| goal | measured | verdict | the machine's floor in this run, and the rule |\n| --- | --- | --- | --- |\n";
    for (const GoalRow& g : goals)
        md += "| " + g.goal + " | " + (g.measured.empty() ? "-" : g.measured) + " | " + verdict_name(g.verdict) + " | " +
              g.floor + " |\n";
    return md + "\n";
}

nlohmann::json goals_json(const std::vector<GoalRow>& goals) {
    nlohmann::json j = nlohmann::json::array();
    for (const GoalRow& g : goals)
        j.push_back({{"goal", g.goal}, {"measured", g.measured}, {"verdict", verdict_name(g.verdict)}, {"floor", g.floor}});
    return j;
}

}  // namespace contactlab::bench
