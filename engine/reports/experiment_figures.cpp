// experiment_figures.cpp — the seeds' figures from a results table (experiment_figures.hpp).
//
// Index: rows and groups | chart helpers | seed 000 | seed 002 | seed 003 | seed 004 | entry points
#include "engine/reports/experiment_figures.hpp"

#include "engine/experiments/analysis/intervals.hpp"
#include "engine/experiments/analysis/statistics.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <optional>
#include <set>

namespace contactlab::reports {
namespace {

using experiments::ResultsTable;
using render::Chart;
using render::ChartSeries;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// ---- rows and groups ---------------------------------------------------------------------------

// The rows the analysis uses: not warm-up, valid.
std::vector<std::size_t> used_rows(const ResultsTable& t) {
    const auto valid = t.column("valid"), warm = t.column("warmup");
    std::vector<std::size_t> rows;
    for (std::size_t i = 0; i < t.rows.size(); ++i) {
        if (valid && t.number(i, *valid) == 0.0) continue;
        if (warm && t.number(i, *warm) != 0.0) continue;
        rows.push_back(i);
    }
    return rows;
}

// Distinct values of a column in order of first appearance (conditions as the protocol ran them).
std::vector<std::string> in_order(const ResultsTable& t, const std::vector<std::size_t>& rows, std::size_t col) {
    std::vector<std::string> out;
    for (std::size_t i : rows)
        if (std::find(out.begin(), out.end(), t.rows[i][col]) == out.end()) out.push_back(t.rows[i][col]);
    return out;
}

// Distinct numeric values of a column, ascending.
std::vector<double> levels(const ResultsTable& t, const std::vector<std::size_t>& rows, std::size_t col) {
    std::set<double> s;
    for (std::size_t i : rows) s.insert(t.number(i, col));
    return {s.begin(), s.end()};
}

std::string number_text(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%g", v);
    return buf;
}

std::string n_label(long n) { return "n=" + std::to_string(n); }

// Whether a row's answer was right: the `correct` column, else response == stimulus (the
// columns looked up once per table, not once per row).
struct Grader {
    const ResultsTable& t;
    std::optional<std::size_t> correct_col = t.column("correct"), response = t.column("response"),
                               stimulus = t.column("stimulus");
    bool operator()(std::size_t row) const {
        if (correct_col) return t.number(row, *correct_col) != 0.0;
        return response && stimulus && t.rows[row][*response] == t.rows[row][*stimulus];
    }
};

// ---- chart helpers -----------------------------------------------------------------------------

Chart proportion_chart(std::string title, std::string x) {
    Chart c = report_chart(std::move(title), std::move(x), "proportion correct");
    c.y.min = 0.0;
    c.y.max = 1.0;
    return c;
}

void add_point(ChartSeries& s, double x, double y, double low, double high, const std::string& label) {
    s.x.push_back(x);
    s.y.push_back(y);
    s.y_low.push_back(low);
    s.y_high.push_back(high);
    s.labels.push_back(label);
}

// When every point of a chart has the same n, one note on the x axis says so instead of a label
// at each point (labels of nearby points would overlap); `what` names the unit ("trials").
void one_n_note(Chart& c, const std::string& what) {
    std::string n;
    for (const ChartSeries& s : c.series)
        for (const std::string& l : s.labels) {
            if (n.empty()) n = l;
            if (l != n) return;
        }
    if (n.empty()) return;
    for (ChartSeries& s : c.series) s.labels.clear();
    c.x.title += "   (n = " + n.substr(2) + " " + what + " per point)";
}

// Each participant's mean of `value` over the rows that pass `keep`, for one condition.
template <class Value, class Keep>
std::vector<double> participant_means(const ResultsTable& t, const std::vector<std::size_t>& rows,
                                      const std::string& condition, Value value, Keep keep) {
    const auto pc = t.column("participant"), cc = t.column("condition");
    std::map<std::string, std::pair<double, long>> by;
    for (std::size_t i : rows) {
        if (t.rows[i][*cc] != condition || !keep(i)) continue;
        auto& [sum, n] = by[pc ? t.rows[i][*pc] : std::string()];
        sum += value(i);
        ++n;
    }
    std::vector<double> means;
    for (const auto& [p, sn] : by) means.push_back(sn.first / static_cast<double>(sn.second));
    return means;
}

double mean(const std::vector<double>& v) { return experiments::summarize(v).mean; }  // NaN when empty

// ---- seed 000: failures and completion time per d (Fig. 10) ------------------------------------

std::vector<ReportFigure> seed000(const ResultsTable& t) {
    const auto rows = used_rows(t);
    const auto cc = t.column("condition"), sc = t.column("stimulus"), fc = t.column("failed"), tc = t.column("time_s");
    if (!cc || !sc || !fc || !tc) return {};
    const auto conditions = in_order(t, rows, *cc);
    const auto ds = levels(t, rows, *sc);
    std::vector<std::string> d_labels;
    for (double d : ds) d_labels.push_back(number_text(d * 100.0));  // m -> cm

    Chart failures = proportion_chart("Failures per block length (seed 000, Fig. 10)", "block length d (cm)");
    failures.y.title = "proportion of trials failed";
    failures.x.categories = d_labels;
    Chart times = report_chart("Completion time of successful trials (seed 000, Fig. 10)", "block length d (cm)", "time (s)");
    times.x.categories = d_labels;
    times.y.include_zero = true;
    const int nc = static_cast<int>(conditions.size());
    for (int ci = 0; ci < nc; ++ci) {
        ChartSeries f = marker_series(conditions[ci], ci), s = marker_series(conditions[ci], ci);
        for (std::size_t di = 0; di < ds.size(); ++di) {
            long n = 0, failed = 0;
            std::vector<double> ok_times;
            for (std::size_t i : rows) {
                if (t.rows[i][*cc] != conditions[ci] || t.number(i, *sc) != ds[di]) continue;
                ++n;
                if (t.number(i, *fc) != 0.0) ++failed;
                else ok_times.push_back(t.number(i, *tc));
            }
            if (n == 0) continue;  // no point where there is no data
            const double x = static_cast<double>(di) + dodge(ci, nc);
            const auto w = experiments::wilson_interval(failed, n, 0.99);
            add_point(f, x, static_cast<double>(failed) / static_cast<double>(n), w.low, w.high, n_label(n));
            if (!ok_times.empty()) {
                const auto m = experiments::mean_interval(ok_times, 0.99);
                add_point(s, x, mean(ok_times), m.low, m.high, n_label(static_cast<long>(ok_times.size())));
            }
        }
        if (!f.x.empty()) failures.series.push_back(std::move(f));
        if (!s.x.empty()) times.series.push_back(std::move(s));
    }
    one_n_note(failures, "trials");
    one_n_note(times, "successful trials");
    std::vector<ReportFigure> out;
    out.push_back({"seed000_failures.png", failures,
                   "Each point: the share of valid trials at that d and condition in which the finger slipped off "
                   "the block (n trials), with its 99 % Wilson interval."});
    if (!times.series.empty())
        out.push_back({"seed000_time.png", times,
                       "Each point: the mean completion time of the successful trials (n) at that d and condition, "
                       "with its 99 % t interval (none for a single trial)."});
    return out;
}

// ---- seed 002: identification, small vs large bumps, error by small bumps ----------------------

std::vector<ReportFigure> seed002(const ResultsTable& t) {
    const auto rows = used_rows(t);
    const auto cc = t.column("condition"), sc = t.column("stimulus"), rc = t.column("response"),
               pc = t.column("participant");
    if (!cc || !sc || !rc) return {};
    const auto conditions = in_order(t, rows, *cc);
    const int nc = static_cast<int>(conditions.size());
    const long participants = pc ? static_cast<long>(in_order(t, rows, *pc).size()) : 1;
    std::vector<ReportFigure> out;
    const auto all = [](std::size_t) { return true; };
    const Grader correct{t};
    const auto right = [&](std::size_t i) { return correct(i) ? 1.0 : 0.0; };

    // Fig. 5a: proportion correct and IT_est per condition, the participants' mean +- SE.
    Chart pc_chart = proportion_chart("Bump counting: proportion correct (seed 002, Fig. 5a)", "condition");
    Chart it_chart = report_chart("Bump counting: information transfer (seed 002, Fig. 5a)", "condition", "IT_est (bits)");
    pc_chart.x.categories = conditions;
    it_chart.x.categories = conditions;
    it_chart.y.include_zero = true;
    for (int ci = 0; ci < nc; ++ci) {
        ChartSeries p = marker_series(conditions[ci], ci), it = marker_series(conditions[ci], ci);
        const auto means = participant_means(t, rows, conditions[ci], right, all);
        const double se = experiments::standard_error(means), m = mean(means);
        // Mean +- SE of proportions, cut at 0 and 1 (a proportion's bar never leaves [0, 1]).
        add_point(p, ci, m, std::max(0.0, m - se), std::min(1.0, m + se), n_label(static_cast<long>(means.size())));
        // IT_est per participant (eq. 6 is biased upward for small n: the seed averages them).
        std::map<std::string, std::pair<std::vector<std::string>, std::vector<std::string>>> per;
        for (std::size_t i : rows)
            if (t.rows[i][*cc] == conditions[ci]) {
                auto& sr = per[pc ? t.rows[i][*pc] : std::string()];
                sr.first.push_back(t.rows[i][*sc]);
                sr.second.push_back(t.rows[i][*rc]);
            }
        std::vector<double> its;
        for (const auto& [who, sr] : per) its.push_back(experiments::it_est_bits(experiments::make_confusion(sr.first, sr.second)));
        const double ise = experiments::standard_error(its), im = mean(its);
        add_point(it, ci, im, im - ise, im + ise, n_label(static_cast<long>(its.size())));
        pc_chart.series.push_back(std::move(p));
        it_chart.series.push_back(std::move(it));
    }
    one_n_note(pc_chart, "participants");
    one_n_note(it_chart, "participants");
    const std::string per_participant = "Each point: the mean of the " + std::to_string(participants) +
                                        " participants' values (n participants) with its standard error.";
    out.push_back({"seed002_proportion_correct.png", pc_chart, per_participant});
    out.push_back({"seed002_it_est.png", it_chart, per_participant + " IT_est is seed 002's eq. 6, per participant."});

    // Fig. 6 and Fig. 8 need to know which bumps were small and which large.
    const auto small = t.column("small_bumps"), large = t.column("large_bumps");
    if (!small || !large) return out;
    Chart sl = proportion_chart("Small bumps only against large bumps only (seed 002, Fig. 6)", "stimuli");
    sl.x.categories = {"small bumps only", "large bumps only"};
    Chart err = report_chart("Error by number of small bumps (seed 002, eq. 7, Fig. 8)", "small bumps in the stimulus",
                      "mean |answer - bumps| (bumps)");
    err.y.include_zero = true;
    const auto ks = levels(t, rows, *small);
    for (double k : ks) err.x.categories.push_back(number_text(k));
    for (int ci = 0; ci < nc; ++ci) {
        ChartSeries s = marker_series(conditions[ci], ci), e = marker_series(conditions[ci], ci);
        for (int kind = 0; kind < 2; ++kind) {
            const auto keep = [&](std::size_t i) {
                const double ns = t.number(i, *small), nl = t.number(i, *large);
                return kind == 0 ? (ns > 0 && nl == 0) : (nl > 0 && ns == 0);
            };
            const auto means = participant_means(t, rows, conditions[ci], right, keep);
            if (means.empty()) continue;
            const double se = experiments::standard_error(means), m = mean(means);
            add_point(s, kind + dodge(ci, nc), m, std::max(0.0, m - se), std::min(1.0, m + se),
                      n_label(static_cast<long>(means.size())));
        }
        for (std::size_t ki = 0; ki < ks.size(); ++ki) {
            std::vector<double> errors;
            for (std::size_t i : rows)
                if (t.rows[i][*cc] == conditions[ci] && t.number(i, *small) == ks[ki])
                    errors.push_back(std::abs(t.number(i, *rc) - t.number(i, *sc)));
            if (errors.empty()) continue;
            const double se = experiments::standard_error(errors), m = mean(errors);
            add_point(e, ki + dodge(ci, nc), m, m - se, m + se, n_label(static_cast<long>(errors.size())));
        }
        if (!s.x.empty()) sl.series.push_back(std::move(s));
        if (!e.x.empty()) err.series.push_back(std::move(e));
    }
    one_n_note(sl, "participants");
    one_n_note(err, "trials");
    if (!sl.series.empty())
        out.push_back({"seed002_small_large.png", sl,
                       per_participant + " Stimuli with small bumps only, or large bumps only (none: 0 bumps)."});
    if (!err.series.empty())
        out.push_back({"seed002_error_by_small_bumps.png", err,
                       "Each point: the mean absolute counting error of the n trials whose stimulus had that many "
                       "small bumps (seed 002 eq. 7, read as a mean), with its standard error."});
    return out;
}

// ---- seed 003: proportion correct per height, per task (Fig. 10) --------------------------------

std::vector<ReportFigure> seed003(const ResultsTable& t) {
    const auto rows = used_rows(t);
    const auto cc = t.column("condition"), sc = t.column("stimulus");
    if (!cc || !sc) return {};
    const auto tasks = in_order(t, rows, *cc);
    const Grader correct{t};
    const auto heights = levels(t, rows, *sc);
    Chart c = proportion_chart("Curvature: proportion correct per arc height (seed 003, Fig. 10)", "arc height (mm)");
    for (double h : heights) c.x.categories.push_back(number_text(h));
    const int nt = static_cast<int>(tasks.size());
    for (int ti = 0; ti < nt; ++ti) {
        ChartSeries s = marker_series("task " + tasks[ti], ti);
        for (std::size_t hi = 0; hi < heights.size(); ++hi) {
            long n = 0, ok = 0;
            for (std::size_t i : rows)
                if (t.rows[i][*cc] == tasks[ti] && t.number(i, *sc) == heights[hi]) {
                    ++n;
                    ok += correct(i) ? 1 : 0;
                }
            if (n == 0) continue;
            const auto w = experiments::wilson_interval(ok, n, 0.95);
            add_point(s, hi + dodge(ti, nt), static_cast<double>(ok) / static_cast<double>(n), w.low, w.high, n_label(n));
        }
        if (!s.x.empty()) c.series.push_back(std::move(s));
    }
    one_n_note(c, "trials");
    return {{"seed003_proportion_correct.png", c,
             "Each point: the share of the n valid trials at that height and task answered correctly, with its 95 % "
             "Wilson interval."}};
}

// ---- seed 004: phi against e, per k -------------------------------------------------------------

std::vector<ReportFigure> seed004(const ResultsTable& t) {
    const auto rows = used_rows(t);
    const auto e = t.column("e"), k = t.column("k"), st = t.column("stimulus"), rs = t.column("response");
    if (!e || !k || !st || !rs) return {};
    const auto es = levels(t, rows, *e), ks = levels(t, rows, *k);
    Chart c = report_chart("Orientation matched to the field: Cramer's phi (seed 004)", "eccentricity e = k2 / k1",
                    "Cramer's phi (0: none, 1: complete)");
    c.y.min = 0.0;
    c.y.max = 1.0;
    for (double v : es) c.x.categories.push_back(number_text(v));
    const int nk = static_cast<int>(ks.size());
    for (int ki = 0; ki < nk; ++ki) {
        ChartSeries s = marker_series("k = " + number_text(ks[ki]) + " N/mm", ki);
        for (std::size_t ei = 0; ei < es.size(); ++ei) {
            std::vector<std::string> stimuli, responses;
            for (std::size_t i : rows)
                if (t.number(i, *e) == es[ei] && t.number(i, *k) == ks[ki]) {
                    stimuli.push_back(t.rows[i][*st]);
                    responses.push_back(t.rows[i][*rs]);
                }
            if (stimuli.empty()) continue;
            const double phi = experiments::cramers_phi(experiments::make_confusion(stimuli, responses));
            add_point(s, ei + dodge(ki, nk), phi, kNaN, kNaN, n_label(static_cast<long>(stimuli.size())));
        }
        if (!s.x.empty()) c.series.push_back(std::move(s));
    }
    one_n_note(c, "trials");
    return {{"seed004_phi.png", c,
             "Each point: Cramer's phi of the 2 x 2 table of field orientation (45 / 135 deg) against the template "
             "chosen, over the n valid trials at that e and k (seed 004 pools all participants' repetitions)."}};
}

}  // namespace

// ---- shared with experiment_report.cpp -----------------------------------------------------------

std::string report_number(const nlohmann::json& v, const char* format) {
    if (!v.is_number()) return "-";
    char buf[64];
    std::snprintf(buf, sizeof buf, format, v.get<double>());
    return buf;
}

Chart report_chart(std::string title, std::string x, std::string y) {
    Chart c;
    c.title = std::move(title);
    c.x.title = std::move(x);
    c.y.title = std::move(y);
    c.width = 900;
    c.height = 540;
    return c;
}

// A series of markers (no line) in palette colour `index` with its own marker shape; its points
// are shifted sideways within their category by dodge(), so series stand side by side.
ChartSeries marker_series(const std::string& name, int index) {
    ChartSeries s;
    s.name = name;
    s.color = render::chart_color(index);
    const render::Marker markers[] = {render::Marker::disc, render::Marker::square, render::Marker::triangle,
                                      render::Marker::diamond};
    s.marker = markers[index % 4];
    s.connect = false;
    s.line_width = 2.f;
    return s;
}

// Offset of series `index` of `count` within a category slot (width 1): they share half of it.
double dodge(int index, int count) { return count <= 1 ? 0.0 : (index - (count - 1) / 2.0) * (0.5 / count); }

// ---- entry points -------------------------------------------------------------------------------

std::string seed_of(const ResultsTable& t) {
    // The edge-sharpness task shares seed 000's condition names; its own columns tell it apart.
    if (t.column("reference_mm")) return "";
    if (t.column("e") && t.column("k")) return "004";
    if (t.column("motion")) return "003";
    const auto cc = t.column("condition");
    if (!cc) return "";
    std::set<std::string> conditions;
    for (const auto& r : t.rows) conditions.insert(r[*cc]);
    if (conditions.count("F") || conditions.count("F+CLD")) return "002";
    if (conditions.count("force") || conditions.count("force+cld")) return "000";
    return "";
}

std::vector<ReportFigure> seed_figures(const ResultsTable& t) {
    const std::string seed = seed_of(t);
    if (seed == "000") return seed000(t);
    if (seed == "002") return seed002(t);
    if (seed == "003") return seed003(t);
    if (seed == "004") return seed004(t);
    return {};
}

}  // namespace contactlab::reports
