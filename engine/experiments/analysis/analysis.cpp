// analysis.cpp — results table -> the seeds' figures (analysis.hpp).
#include "engine/experiments/analysis/analysis.hpp"

#include "engine/experiments/analysis/binary_tests.hpp"
#include "engine/experiments/analysis/intervals.hpp"
#include "engine/experiments/analysis/statistics.hpp"

#include <nlohmann/json.hpp>

#include <cmath>
#include <map>
#include <set>
#include <tuple>

namespace contactlab::experiments {
namespace {

using nlohmann::json;
using RowSet = std::vector<std::size_t>;

// NaN is not JSON: it goes out as null.
json num(double v) { return std::isfinite(v) ? json(v) : json(nullptr); }

struct Columns {
    std::optional<std::size_t> condition, participant, stimulus, response, correct, valid, warmup, time, failed, small, large;
    std::optional<std::size_t> breaks, fraction;  // contact_breaks, contact_fraction (the movement's measures)
};

bool truthy(const ResultsTable& t, std::size_t row, std::size_t col) { return t.number(row, col) != 0.0; }

// Bounds on the label sets: a confusion matrix is stimuli x responses per condition and per
// participant, so a column of measurements mistaken for labels (thousands of distinct values)
// would make millions of cells. Far above any seed's design (5 stimuli, 9 conditions, 10
// participants), far below what runs out of memory.
constexpr std::size_t kMaxConditions = 100, kMaxParticipants = 10000, kMaxStimuli = 200, kMaxResponses = 200;

void check_labels(const ResultsTable& t, const Columns& col) {
    auto bound = [&](std::optional<std::size_t> c, std::size_t most, const char* what) {
        if (!c) return;
        std::set<std::string> seen;
        for (std::size_t i = 0; i < t.rows.size(); ++i)
            if (seen.insert(t.rows[i][*c]).second && seen.size() > most)
                throw ExperimentError(t.where(i) + ", column " + t.columns[*c] + ": more than " + std::to_string(most) +
                                      " distinct " + what + " (the analysis counts each label's trials: a column of "
                                      "measurements is not a set of labels)");
    };
    bound(col.condition, kMaxConditions, "conditions");
    bound(col.participant, kMaxParticipants, "participants");
    bound(col.stimulus, kMaxStimuli, "stimulus labels");
    bound(col.response, kMaxResponses, "response labels");
    // A label that reads as a number must be one: "1e999" would sort, plot and subtract as
    // infinity.
    for (std::optional<std::size_t> c : {col.stimulus, col.response})
        if (c)
            for (std::size_t i = 0; i < t.rows.size(); ++i) {
                double v = 0.0;
                if (parse_number(t.rows[i][*c], v) == NumberParse::out_of_range) t.number(i, *c);  // throws, naming the line
            }
}

// 1 for a right answer, 0 for a wrong one, NaN for no answer (the timed task).
double right(const ResultsTable& t, const Columns& col, std::size_t i) {
    if (!col.stimulus || !col.response || t.rows[i][*col.response].empty()) return NAN;
    if (col.correct) return truthy(t, i, *col.correct) ? 1.0 : 0.0;
    return t.rows[i][*col.response] == t.rows[i][*col.stimulus] ? 1.0 : 0.0;
}

// Mean of f over the rows where it is finite; NaN when none.
template <class F>
double mean_of(const RowSet& rows, F f) {
    double sum = 0.0;
    std::size_t n = 0;
    for (std::size_t i : rows)
        if (const double v = f(i); std::isfinite(v)) sum += v, ++n;
    return n ? sum / static_cast<double>(n) : NAN;
}

json confusion_json(const Confusion& c) {
    json m = json::array();
    for (const auto& row : c.counts) m.push_back(row);
    return m;
}

// n, mean, sd and the mean's t interval over `x` (trials taken as independent: the interval
// says how well these trials bound the mean, not how a new participant would do); null bounds
// for fewer than two values.
json mean_json(const std::vector<double>& x, double confidence) {
    const Summary s = summarize(x);
    const Interval ci = mean_interval(x, confidence);
    return {{"n", s.n}, {"mean", num(s.n ? s.mean : NAN)}, {"sd", num(s.sd)}, {"ci_low", num(ci.low)}, {"ci_high", num(ci.high)}};
}

// The non-empty cells of column `c` over `rows`, as numbers.
std::vector<double> cells(const ResultsTable& t, std::size_t c, const RowSet& rows) {
    std::vector<double> out;
    for (std::size_t i : rows)
        if (!t.rows[i][c].empty()) out.push_back(t.number(i, c));
    return out;
}

// The figures for one set of rows (a condition, a participant within it, a stimulus).
json figures(const ResultsTable& t, const Columns& col, const RowSet& rows, bool with_confusion, double confidence) {
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
            out["proportion_correct"] = num(mean_of(rows, [&](std::size_t i) { return right(t, col, i); }));
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
            if (!failed && !t.rows[i][*col.time].empty()) times.push_back(t.number(i, *col.time));
        }
        // No time at all (a model observer records none): no figure, rather than "- +- 0".
        if (!times.empty()) out["time_s"] = mean_json(times, confidence);
        if (col.failed) out["failure_proportion"] = num(rows.empty() ? NAN : static_cast<double>(failures) / rows.size());
    }
    // How the finger moved, over every kept trial (failed ones too: a broken contact is part of
    // how people move), each with the mean's interval.
    // (Not for rows that record neither: a model observer's.)
    if (col.fraction)
        if (const auto v = cells(t, *col.fraction, rows); !v.empty()) out["contact_fraction"] = mean_json(v, confidence);
    if (col.breaks)
        if (const auto v = cells(t, *col.breaks, rows); !v.empty()) out["contact_breaks"] = mean_json(v, confidence);
    return out;
}

std::map<std::string, RowSet> group(const ResultsTable& t, std::optional<std::size_t> key, const RowSet& rows, const char* fallback) {
    std::map<std::string, RowSet> g;
    for (std::size_t i : rows) g[key ? t.rows[i][*key] : std::string(fallback)].push_back(i);
    return g;
}

// Seed 002's bump analyses need the bump counts and numeric answers.
struct Bumps {
    const ResultsTable& t;
    const Columns& col;
    int small(std::size_t i) const { return static_cast<int>(t.number(i, *col.small)); }
    int large(std::size_t i) const { return static_cast<int>(t.number(i, *col.large)); }
    // Seed 002 eq. 7's term: |number of bumps - the participant's answer|; NaN with no answer.
    double error(std::size_t i) const {
        if (t.rows[i][*col.response].empty()) return NAN;
        return std::abs(t.number(i, *col.stimulus) - t.number(i, *col.response));
    }
    RowSet where(const RowSet& rows, bool (*keep)(int, int)) const {
        RowSet out;
        for (std::size_t i : rows)
            if (keep(small(i), large(i))) out.push_back(i);
        return out;
    }
};

bool small_only(int s, int l) { return s > 0 && l == 0; }
bool large_only(int s, int l) { return l > 0 && s == 0; }

// Per count k of small bumps: n, proportion correct and seed 002 eq. 7's average error, pooled
// over the condition's trials and as the mean of the participants' values.
json by_small_bumps(const Bumps& b, const RowSet& rows, const std::map<std::string, RowSet>& by_participant) {
    std::map<int, RowSet> by_k;
    for (std::size_t i : rows) by_k[b.small(i)].push_back(i);
    json out = json::object();
    for (const auto& [k, krows] : by_k) {
        json f;
        f["n"] = krows.size();
        f["proportion_correct"] = num(mean_of(krows, [&](std::size_t i) { return right(b.t, b.col, i); }));
        f["average_error"] = num(mean_of(krows, [&](std::size_t i) { return b.error(i); }));
        std::vector<double> pc, err;
        for (const auto& [p, prows] : by_participant) {
            RowSet mine;
            for (std::size_t i : prows)
                if (b.small(i) == k) mine.push_back(i);
            if (mine.empty()) continue;
            pc.push_back(mean_of(mine, [&](std::size_t i) { return right(b.t, b.col, i); }));
            err.push_back(mean_of(mine, [&](std::size_t i) { return b.error(i); }));
        }
        if (!pc.empty()) f["participant_means"] = {{"participants", pc.size()}, {"proportion_correct", num(summarize(pc).mean)},
                                                   {"average_error", num(summarize(err).mean)}};
        out[std::to_string(k)] = f;
    }
    return out;
}

json test_json(const TTest& r, const std::string& measure) {
    return {{"measure", measure},         {"paired", r.paired},      {"n_a", r.n_a},
            {"n_b", r.n_b},               {"mean_difference", num(r.mean_difference)},
            {"t", num(r.t)},              {"df", num(r.df)},         {"p", num(r.p)},
            {"confidence", r.confidence}, {"ci_low", num(r.ci_low)}, {"ci_high", num(r.ci_high)},
            {"valid", r.valid},           {"undefined", r.valid ? json(nullptr) : json(r.undefined)}};
}

json binary_json(const BinaryComparison& r) {
    json j = {{"rule", kBinaryRule}, {"participants", r.participants}};
    if (!r.undefined.empty()) {
        j["undefined"] = r.undefined;
        return j;
    }
    j["mean_difference"] = r.mean_difference;
    j["permutation"] = {{"p", r.p}, {"exact", r.exact}, {"assignments", r.assignments}, {"smallest_possible_p", r.min_p}};
    j["confidence"] = r.confidence;
    if (r.ci_undefined.empty()) j["interval"] = {r.ci_low, r.ci_high};
    else j["interval"] = nullptr, j["interval_undefined"] = r.ci_undefined;
    return j;
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

const char* const kPairingRule =
    "paired t test across participants: a participant with kept rows in both conditions is one pair (their per-participant "
    "values); participants in only one condition, or without a value for the measure, are left out and named; with fewer "
    "than 2 pairs, or no participant column, Welch's t test over trials taken as independent";

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
    col.small = t.column("small_bumps");
    col.large = t.column("large_bumps");
    col.breaks = t.column("contact_breaks");
    col.fraction = t.column("contact_fraction");
    check_labels(t, col);

    RowSet kept;
    std::size_t excluded = 0;
    for (std::size_t i = 0; i < t.rows.size(); ++i) {
        const bool out = (col.valid && !truthy(t, i, *col.valid)) || (col.warmup && truthy(t, i, *col.warmup));
        if (out) ++excluded;
        else kept.push_back(i);
    }

    json result;
    result["source"] = t.origin;
    result["sources"] = t.files.empty() ? json::array({t.origin}) : json(t.files);
    result["rows"] = t.rows.size();
    result["excluded"] = excluded;
    json warnings = json::array();
    json conditions = json::object();
    const auto by_condition = group(t, col.condition, kept, "all");
    const bool bumps = col.small && col.large && col.stimulus && col.response;
    const Bumps b{t, col};
    // Per condition, per participant: rows and figures, for the paired tests.
    std::map<std::string, std::map<std::string, RowSet>> rows_of;
    std::map<std::string, std::map<std::string, json>> per_participant;
    for (const auto& [name, rows] : by_condition) {
        json c = figures(t, col, rows, true, o.confidence);
        if (col.stimulus) {
            json per = json::object();
            for (const auto& [s, srows] : group(t, col.stimulus, rows, "")) per[s] = figures(t, col, srows, false, o.confidence);
            c["per_stimulus"] = per;
        }
        if (col.participant) {
            json parts = json::object();
            std::vector<double> pc, it, tm, cf, cb;
            for (const auto& [p, prows] : group(t, col.participant, rows, "")) {
                json f = figures(t, col, prows, true, o.confidence);
                rows_of[name][p] = prows;
                per_participant[name][p] = f;
                pc.push_back(get(f, "proportion_correct"));
                it.push_back(get(f, "it_est_bits"));
                tm.push_back(get(f, "time_s", "mean"));
                cf.push_back(get(f, "contact_fraction", "mean"));
                cb.push_back(get(f, "contact_breaks", "mean"));
                parts[p] = std::move(f);
            }
            c["participants"] = parts;
            json means = json::object();
            for (const auto& [key, v] : {std::pair{"proportion_correct", pc}, std::pair{"it_est_bits", it}, std::pair{"time_s", tm},
                                         std::pair{"contact_fraction", cf}, std::pair{"contact_breaks", cb}}) {
                std::vector<double> finite;
                for (double x : v)
                    if (std::isfinite(x)) finite.push_back(x);
                if (!finite.empty()) means[key] = num(summarize(finite).mean);
            }
            c["participant_means"] = means;
        }
        if (bumps) {
            c["by_small_bumps"] = by_small_bumps(b, rows, rows_of[name]);
            for (const auto& [key, keep] : {std::pair{"small_only", &small_only}, std::pair{"large_only", &large_only}}) {
                const RowSet only = b.where(rows, keep);
                json f = {{"n", only.size()}, {"proportion_correct", num(mean_of(only, [&](std::size_t i) { return right(t, col, i); }))}};
                std::vector<double> pm;
                for (const auto& [p, prows] : rows_of[name])
                    if (const double v = mean_of(b.where(prows, keep), [&](std::size_t i) { return right(t, col, i); }); std::isfinite(v))
                        pm.push_back(v);
                if (!pm.empty()) f["participant_mean"] = num(summarize(pm).mean);
                c[key] = f;
            }
        }
        conditions[name] = std::move(c);
    }
    result["conditions"] = conditions;

    // Two conditions: t tests on what the seeds compare, paired or not by kPairingRule.
    json comparisons = json::array();
    json not_compared = json::array();  // measures with no values to compare, and why
    if (by_condition.size() == 2) {
        const std::string a = by_condition.begin()->first, bname = std::next(by_condition.begin())->first;
        const RowSet& ra = by_condition.begin()->second;
        const RowSet& rb = std::next(by_condition.begin())->second;
        std::set<std::string> pairs;
        json left_out = json::array();
        std::string why_unpaired;
        if (!col.participant) {
            why_unpaired = "no participant column";
        } else {
            std::set<std::string> everyone;
            for (const auto& [p, r] : rows_of[a]) everyone.insert(p);
            for (const auto& [p, r] : rows_of[bname]) everyone.insert(p);
            for (const std::string& p : everyone) {
                const bool in_a = rows_of[a].count(p), in_b = rows_of[bname].count(p);
                if (in_a && in_b) pairs.insert(p);
                else left_out.push_back({{"participant", p}, {"reason", "no kept rows in condition " + (in_a ? bname : a)}});
            }
            if (pairs.size() < 2)
                why_unpaired = std::to_string(pairs.size()) + " participant(s) with rows in both conditions, 2 needed to pair";
        }
        const bool paired = why_unpaired.empty();
        if (paired)
            for (const auto& l : left_out)
                warnings.push_back("participant " + l["participant"].get<std::string>() + " left out of the paired tests: " +
                                   l["reason"].get<std::string>());
        // binary: the measure is a proportion of trials (trial_value 1 or 0, NaN for none):
        // binary_tests.hpp's permutation test and participant bootstrap go beside the t test.
        auto compare = [&](const std::string& measure, auto participant_value, auto trial_value, bool binary = false) {
            std::vector<double> va, vb;
            json out_here = paired ? left_out : json::array();
            TTest r;
            if (paired) {
                for (const std::string& p : pairs) {
                    const double x = participant_value(a, p), y = participant_value(bname, p);
                    if (std::isfinite(x) && std::isfinite(y)) {
                        va.push_back(x);
                        vb.push_back(y);
                    } else {
                        out_here.push_back({{"participant", p}, {"reason", "no value of " + measure + " in " + (std::isfinite(x) ? bname : a)}});
                    }
                }
                r = paired_t_test(va, vb, o.confidence);
            } else {
                for (std::size_t i : ra)
                    if (const double x = trial_value(i); std::isfinite(x)) va.push_back(x);
                for (std::size_t i : rb)
                    if (const double x = trial_value(i); std::isfinite(x)) vb.push_back(x);
                r = welch_t_test(va, vb, o.confidence);
            }
            json j = test_json(r, measure);
            j["a"] = a;
            j["b"] = bname;
            j["test"] = {{"kind", paired ? "paired" : "welch"},
                         {"rule", kPairingRule},
                         {"because", paired ? std::to_string(va.size()) + " participants with a value in both conditions"
                                            : why_unpaired},
                         {"left_out", out_here}};
            if (binary && paired) {
                std::vector<BinaryPair> counts;
                for (const std::string& p : pairs) {
                    BinaryPair c;
                    for (auto [cond, k, n] : {std::tuple{&a, &c.k_a, &c.n_a}, std::tuple{&bname, &c.k_b, &c.n_b}})
                        for (std::size_t i : rows_of[*cond][p])
                            if (const double v = trial_value(i); std::isfinite(v)) *k += v != 0.0, ++*n;
                    counts.push_back(c);
                }
                j["binary"] = binary_json(compare_binary(counts, o.confidence));
            } else if (binary) {
                j["binary"] = {{"undefined", "not computed: the test pairs participants, and these rows are not paired (" + why_unpaired + ")"}};
            }
            comparisons.push_back(std::move(j));
        };
        auto figure_of = [&](const char* key, const char* sub = nullptr) {
            return [&, key, sub](const std::string& c, const std::string& p) { return get(per_participant[c][p], key, sub); };
        };
        auto right_of = [&](std::size_t i) { return right(t, col, i); };
        if (col.stimulus && col.response && conditions[a].contains("proportion_correct")) {
            compare("proportion_correct", figure_of("proportion_correct"), right_of, true);
            if (paired) compare("it_est_bits", figure_of("it_est_bits"), right_of);
        }
        if (bumps) {
            // Seed 002 Fig. 6: accuracy on stimuli with small bumps only, and large only.
            for (const auto& [measure, keep] : {std::pair{"proportion_correct_small_only", &small_only},
                                                std::pair{"proportion_correct_large_only", &large_only}}) {
                compare(
                    measure,
                    [&, keep = keep](const std::string& c, const std::string& p) { return mean_of(b.where(rows_of[c][p], keep), right_of); },
                    [&, keep = keep](std::size_t i) { return keep(b.small(i), b.large(i)) ? right_of(i) : NAN; }, true);
            }
        }
        if (col.time) {
            auto time = [&](std::size_t i) {
                if ((col.failed && truthy(t, i, *col.failed)) || t.rows[i][*col.time].empty()) return static_cast<double>(NAN);
                return t.number(i, *col.time);
            };
            bool any = false;
            for (const RowSet* rs : {&ra, &rb})
                for (std::size_t i : *rs) any = any || std::isfinite(time(i));
            if (any) compare("time_s", figure_of("time_s", "mean"), time);
            else not_compared.push_back({{"measure", "time_s"}, {"reason", "no kept trial records a time (a model observer records none)"}});
        }
        if (col.failed) {
            auto failed = [&](std::size_t i) { return truthy(t, i, *col.failed) ? 1.0 : 0.0; };
            compare("failure_proportion", figure_of("failure_proportion"), failed, true);
        }
        // The movement's measures (seed 002 found neither differing between its conditions).
        for (const auto& [measure, c] : {std::pair{"contact_fraction", col.fraction}, std::pair{"contact_breaks", col.breaks}}) {
            if (!c) continue;
            auto cell = [&, c = *c](std::size_t i) { return t.rows[i][c].empty() ? static_cast<double>(NAN) : t.number(i, c); };
            bool any = false;
            for (const RowSet* rs : {&ra, &rb})
                for (std::size_t i : *rs) any = any || std::isfinite(cell(i));
            if (any) compare(measure, figure_of(measure, "mean"), cell);
            else not_compared.push_back({{"measure", measure}, {"reason", "no kept trial records it (a model observer records none)"}});
        }
    }
    result["comparisons"] = comparisons;
    if (!not_compared.empty()) result["not_compared"] = not_compared;
    result["warnings"] = warnings;
    return result;
}

}  // namespace contactlab::experiments
