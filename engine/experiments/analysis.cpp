// analysis.cpp — results table -> the seeds' figures (analysis.hpp).
#include "engine/experiments/analysis.hpp"

#include "engine/experiments/statistics.hpp"

#include <nlohmann/json.hpp>

#include <cmath>
#include <map>
#include <set>

namespace contactlab::experiments {
namespace {

using nlohmann::json;

// NaN is not JSON: it goes out as null.
json num(double v) { return std::isfinite(v) ? json(v) : json(nullptr); }

// The rows one group of figures is computed from.
struct Rows {
    std::vector<std::size_t> index;
};

struct Columns {
    std::optional<std::size_t> condition, participant, stimulus, response, correct, valid, warmup, time, failed;
};

bool truthy(const ResultsTable& t, std::size_t row, std::size_t col) { return t.number(row, col) != 0.0; }

json confusion_json(const Confusion& c) {
    json m = json::array();
    for (const auto& row : c.counts) m.push_back(row);
    return m;
}

// The figures for one set of rows (a condition, a participant within it, a stimulus).
json figures(const ResultsTable& t, const Columns& col, const std::vector<std::size_t>& rows, bool with_confusion) {
    json out;
    out["n"] = rows.size();
    if (col.stimulus && col.response) {
        std::vector<std::string> s, r;
        for (std::size_t i : rows) {
            if (t.rows[i][*col.response].empty()) continue;  // a timed task has no answer
            s.push_back(t.rows[i][*col.stimulus]);
            r.push_back(t.rows[i][*col.response]);
        }
        if (!s.empty()) {
            const Confusion c = make_confusion(s, r);
            if (col.correct) {
                double right = 0.0;
                for (std::size_t i : rows)
                    if (!t.rows[i][*col.response].empty()) right += truthy(t, i, *col.correct) ? 1.0 : 0.0;
                out["proportion_correct"] = num(right / static_cast<double>(s.size()));
            } else {
                out["proportion_correct"] = num(proportion_correct(c));
            }
            out["it_est_bits"] = num(it_est_bits(c));
            out["cramers_phi"] = num(cramers_phi(c));
            if (with_confusion) {
                out["labels"] = {{"stimuli", c.stimuli}, {"responses", c.responses}};
                out["confusion"] = confusion_json(c);
            }
        }
    }
    if (col.time) {
        std::vector<double> times;
        long failures = 0;
        for (std::size_t i : rows) {
            const bool failed = col.failed && truthy(t, i, *col.failed);
            failures += failed;
            if (!failed) times.push_back(t.number(i, *col.time));
        }
        const Summary s = summarize(times);
        out["time_s"] = {{"n", s.n}, {"mean", num(s.mean)}, {"sd", num(s.sd)}};
        if (col.failed) out["failure_proportion"] = num(rows.empty() ? NAN : static_cast<double>(failures) / rows.size());
    }
    return out;
}

// Values of `column` grouped by `key` column (insertion order of first appearance kept sorted).
std::map<std::string, std::vector<std::size_t>> group(const ResultsTable& t, std::optional<std::size_t> key,
                                                      const std::vector<std::size_t>& rows, const char* fallback) {
    std::map<std::string, std::vector<std::size_t>> g;
    for (std::size_t i : rows) g[key ? t.rows[i][*key] : std::string(fallback)].push_back(i);
    return g;
}

json test_json(const TTest& r, const std::string& measure) {
    return {{"measure", measure},       {"paired", r.paired},   {"n_a", r.n_a},
            {"n_b", r.n_b},             {"mean_difference", num(r.mean_difference)},
            {"t", num(r.t)},            {"df", num(r.df)},       {"p", num(r.p)},
            {"confidence", r.confidence}, {"ci_low", num(r.ci_low)}, {"ci_high", num(r.ci_high)},
            {"valid", r.valid}};
}

// A number from a figures object, NaN when absent or null.
double get(const json& j, const char* a, const char* b = nullptr) {
    const json* p = &j;
    if (!p->contains(a)) return NAN;
    p = &(*p)[a];
    if (b) {
        if (!p->contains(b)) return NAN;
        p = &(*p)[b];
    }
    return p->is_number() ? p->get<double>() : NAN;
}

}  // namespace

json analyze_results(const ResultsTable& t, const AnalyzeOptions& o) {
    Columns col;
    col.condition = t.column("condition");
    col.participant = t.column("participant");
    col.stimulus = t.column("stimulus");
    col.response = t.column("response");
    col.correct = t.column("correct");
    col.valid = t.column("valid");
    col.warmup = t.column("warmup");
    col.time = t.column("time_s");
    col.failed = t.column("failed");

    std::vector<std::size_t> kept;
    std::size_t excluded = 0;
    for (std::size_t i = 0; i < t.rows.size(); ++i) {
        const bool out = (col.valid && !truthy(t, i, *col.valid)) || (col.warmup && truthy(t, i, *col.warmup));
        if (out) ++excluded;
        else kept.push_back(i);
    }

    json result;
    result["source"] = t.origin;
    result["rows"] = t.rows.size();
    result["excluded"] = excluded;
    json conditions = json::object();
    const auto by_condition = group(t, col.condition, kept, "all");
    // Per participant, per condition: the figures the paired tests use.
    std::map<std::string, std::map<std::string, json>> per_participant;
    for (const auto& [name, rows] : by_condition) {
        json c = figures(t, col, rows, true);
        if (col.stimulus) {
            json per = json::object();
            for (const auto& [s, srows] : group(t, col.stimulus, rows, "")) per[s] = figures(t, col, srows, false);
            c["per_stimulus"] = per;
        }
        if (col.participant) {
            json parts = json::object();
            std::vector<double> pc, it, tm;
            for (const auto& [p, prows] : group(t, col.participant, rows, "")) {
                json f = figures(t, col, prows, true);
                per_participant[name][p] = f;
                pc.push_back(get(f, "proportion_correct"));
                it.push_back(get(f, "it_est_bits"));
                tm.push_back(get(f, "time_s", "mean"));
                parts[p] = std::move(f);
            }
            c["participants"] = parts;
            json means = json::object();
            for (const auto& [key, v] : {std::pair{"proportion_correct", pc}, std::pair{"it_est_bits", it}, std::pair{"time_s", tm}}) {
                std::vector<double> finite;
                for (double x : v)
                    if (std::isfinite(x)) finite.push_back(x);
                if (!finite.empty()) means[key] = num(summarize(finite).mean);
            }
            c["participant_means"] = means;
        }
        conditions[name] = std::move(c);
    }
    result["conditions"] = conditions;

    // Two conditions: t tests on what the seeds compare.
    json comparisons = json::array();
    if (by_condition.size() == 2) {
        const std::string a = by_condition.begin()->first, b = std::next(by_condition.begin())->first;
        const auto& ra = by_condition.begin()->second;
        const auto& rb = std::next(by_condition.begin())->second;
        // Paired across participants when both conditions have the same participants (2 or more).
        std::set<std::string> pa, pb;
        for (const auto& [p, f] : per_participant[a]) pa.insert(p);
        for (const auto& [p, f] : per_participant[b]) pb.insert(p);
        const bool paired = col.participant && pa == pb && pa.size() >= 2;
        auto compare = [&](const std::string& measure, auto per_participant_value, auto per_trial_value) {
            std::vector<double> va, vb;
            if (paired) {
                for (const std::string& p : pa) {
                    const double x = per_participant_value(per_participant[a][p]), y = per_participant_value(per_participant[b][p]);
                    if (std::isfinite(x) && std::isfinite(y)) {
                        va.push_back(x);
                        vb.push_back(y);
                    }
                }
                comparisons.push_back(test_json(paired_t_test(va, vb, o.confidence), measure));
            } else {
                for (std::size_t i : ra)
                    if (const double x = per_trial_value(i); std::isfinite(x)) va.push_back(x);
                for (std::size_t i : rb)
                    if (const double x = per_trial_value(i); std::isfinite(x)) vb.push_back(x);
                comparisons.push_back(test_json(welch_t_test(va, vb, o.confidence), measure));
            }
            comparisons.back()["a"] = a;
            comparisons.back()["b"] = b;
        };
        const bool answers = col.stimulus && col.response && conditions[a].contains("proportion_correct");
        if (answers) {
            // Per trial: 1 for a right answer, 0 for a wrong one.
            auto right = [&](std::size_t i) {
                if (t.rows[i][*col.response].empty()) return static_cast<double>(NAN);
                if (col.correct) return truthy(t, i, *col.correct) ? 1.0 : 0.0;
                return t.rows[i][*col.response] == t.rows[i][*col.stimulus] ? 1.0 : 0.0;
            };
            compare("proportion_correct", [](const json& f) { return get(f, "proportion_correct"); }, right);
            if (paired) compare("it_est_bits", [](const json& f) { return get(f, "it_est_bits"); }, right);
        }
        if (col.time) {
            auto time = [&](std::size_t i) {
                if (col.failed && truthy(t, i, *col.failed)) return static_cast<double>(NAN);
                return t.number(i, *col.time);
            };
            compare("time_s", [](const json& f) { return get(f, "time_s", "mean"); }, time);
        }
        if (col.failed) {
            auto failed = [&](std::size_t i) { return truthy(t, i, *col.failed) ? 1.0 : 0.0; };
            compare("failure_proportion", [](const json& f) { return get(f, "failure_proportion"); }, failed);
        }
    }
    result["comparisons"] = comparisons;
    return result;
}

}  // namespace contactlab::experiments
