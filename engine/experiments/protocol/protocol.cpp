// protocol.cpp — strict reading of protocol files (protocol.hpp).
#include "engine/experiments/protocol/protocol.hpp"

#include "engine/experiments/base/path_name.hpp"
#include "engine/experiments/base/results_table.hpp"
#include "engine/experiments/base/sha256.hpp"
#include "engine/experiments/base/random_stream.hpp"
#include "haptics/parameter_limits.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <set>
#include <optional>
#include <sstream>
#include <utility>
#include <vector>

namespace contactlab::experiments {
namespace {

using nlohmann::json;

struct Reader {
    std::string origin;

    [[noreturn]] void fail(const std::string& path, const std::string& why) const {
        throw ExperimentError(origin + ": " + (path.empty() ? std::string() : path + ": ") + why);
    }
    static std::string join(const std::string& path, const std::string& key) { return path.empty() ? key : path + "." + key; }

    void only(const json& j, const std::string& path, std::set<std::string> keys) const {
        if (!j.is_object()) fail(path, "expected an object");
        for (const auto& [k, v] : j.items())
            if (!keys.count(k)) fail(join(path, k), "unknown key");
    }
    const json& need(const json& j, const std::string& path, const char* key) const {
        if (!j.contains(key)) fail(join(path, key), "missing");
        return j[key];
    }
    // The value as the file gave it, for a message: JSON's shortest exact form ("20.0000001", where
    // an ostream's default precision printed "20"; an integer with all its digits).
    static std::string shown(const json& j) {
        if (j.is_number_float() && !std::isfinite(j.get<double>())) return "a number beyond a double's range";
        return j.dump();
    }
    double number(const json& j, const std::string& path, double lo, double hi, const char* unit) const {
        if (!j.is_number()) fail(path, "expected a number");
        const double v = j.get<double>();
        if (!std::isfinite(v) || v < lo || v > hi)
            fail(path, "must lie in [" + number_text(lo) + ", " + number_text(hi) + "]" + (unit[0] ? " " : "") + unit + ", got " +
                           shown(j));
        return v;
    }
    double number(const json& obj, const std::string& path, const char* key, double lo, double hi, const char* unit,
                  double fallback) const {
        return obj.contains(key) ? number(obj[key], join(path, key), lo, hi, unit) : fallback;
    }
    int integer(const json& obj, const std::string& path, const char* key, int lo, int hi, int fallback) const {
        if (!obj.contains(key)) return fallback;
        const json& j = obj[key];
        const std::string range = "[" + std::to_string(lo) + ", " + std::to_string(hi) + "]";
        if (!j.is_number_integer())
            fail(join(path, key), "expected a whole number in " + range + (j.is_number() ? ", got " + shown(j) : std::string()));
        // Unsigned beyond a long long (18446744073709551615) is compared as unsigned, never wrapped to -1.
        const bool inside = j.is_number_unsigned() ? j.get<std::uint64_t>() <= static_cast<std::uint64_t>(std::max(hi, 0)) &&
                                                         static_cast<long long>(j.get<std::uint64_t>()) >= lo
                                                   : j.get<long long>() >= lo && j.get<long long>() <= hi;
        if (!inside) fail(join(path, key), "must lie in " + range + ", got " + shown(j));
        return static_cast<int>(j.get<long long>());
    }
    std::string text(const json& j, const std::string& path) const {
        if (!j.is_string()) fail(path, "expected a string");
        return j.get<std::string>();
    }
    bool flag(const json& obj, const std::string& path, const char* key, bool fallback) const {
        if (!obj.contains(key)) return fallback;
        if (!obj[key].is_boolean()) fail(join(path, key), "expected true or false");
        return obj[key].get<bool>();
    }
};

// The first key an object names twice and the object's path ("conditions[1]"; "" at the top):
// nlohmann::json keeps the last of two silently, so a protocol with "trials" twice would run with
// one of them and the reader would never see the other.
class DuplicateKeys : public json::json_sax_t {
public:
    std::optional<std::pair<std::string, std::string>> found;  // (object's path, key)

    bool null() override { return value(); }
    bool boolean(bool) override { return value(); }
    bool number_integer(number_integer_t) override { return value(); }
    bool number_unsigned(number_unsigned_t) override { return value(); }
    bool number_float(number_float_t, const string_t&) override { return value(); }
    bool string(string_t&) override { return value(); }
    bool binary(binary_t&) override { return value(); }
    bool start_object(std::size_t) override {
        stack_.push_back({true, here(), {}, {}, 0});
        return true;
    }
    bool key(string_t& k) override {
        Frame& f = stack_.back();
        if (!f.keys.insert(k).second) {
            found = {f.path, k};
            return false;  // the first is enough
        }
        f.key = k;
        return true;
    }
    bool end_object() override { return close(); }
    bool start_array(std::size_t) override {
        stack_.push_back({false, here(), {}, {}, 0});
        return true;
    }
    bool end_array() override { return close(); }
    bool parse_error(std::size_t, const std::string&, const nlohmann::detail::exception&) override { return false; }

private:
    struct Frame {
        bool object;
        std::string path;            // of this object or array
        std::set<std::string> keys;  // an object's keys so far
        std::string key;             // an object's current key
        std::size_t index;           // an array's current element
    };
    std::vector<Frame> stack_;

    // The path of the value that starts now.
    std::string here() const {
        if (stack_.empty()) return "";
        const Frame& f = stack_.back();
        return f.object ? Reader::join(f.path, f.key) : f.path + "[" + std::to_string(f.index) + "]";
    }
    bool value() {
        if (!stack_.empty() && !stack_.back().object) ++stack_.back().index;
        return true;
    }
    bool close() {
        stack_.pop_back();
        return value();
    }
};

Task task_of(const Reader& r, const std::string& name) {
    if (name == "contour-following") return Task::contour_following;
    if (name == "bump-counting") return Task::bump_counting;
    if (name == "curvature") return Task::curvature;
    if (name == "surface-orientation") return Task::surface_orientation;
    if (name == "edge-sharpness") return Task::edge_sharpness;
    r.fail("task", "unknown task \"" + name + "\" (contour-following, bump-counting, curvature, surface-orientation, edge-sharpness)");
}

// What each task can answer (the simulated participant's answers and the grading rule) fixes
// what its answer set may be: a protocol whose answers the task cannot produce, or whose grading
// would be arbitrary, is refused when it loads rather than graded wrongly at every trial.
void check_answers(const Reader& r, const Protocol& p) {
    std::set<std::string> seen;
    for (std::size_t i = 0; i < p.answers.size(); ++i) {
        const std::string path = "answers[" + std::to_string(i) + "]";
        if (p.answers[i].empty() || p.answers[i].find_first_of("\n\r") != std::string::npos)
            r.fail(path, "an answer is a non-empty label on one line");
        if (!seen.insert(p.answers[i]).second) r.fail(path, "\"" + p.answers[i] + "\" appears twice (every answer must be told apart)");
    }
    switch (p.task) {
        case Task::contour_following: break;
        case Task::bump_counting: {
            // The count of bumps felt: 0, 1, ..., N in that order, N at least the largest
            // stimulus (or the right answer could not be given) and at most 4 (seed 002).
            const double most = *std::max_element(p.stimuli.begin(), p.stimuli.end());
            if (p.answers.size() > 5 || static_cast<double>(p.answers.size()) - 1.0 < most)
                r.fail("answers", "bump counting answers are the counts \"0\" .. \"N\", N from the largest stimulus (" +
                                      stimulus_label(p, most) + ") to 4");
            for (std::size_t i = 0; i < p.answers.size(); ++i)
                if (p.answers[i] != std::to_string(i))
                    r.fail("answers[" + std::to_string(i) + "]", "expected \"" + std::to_string(i) + "\" (bump counting answers are the counts 0 .. N in order), got \"" + p.answers[i] + "\"");
            break;
        }
        case Task::curvature: {
            // The answer is the height felt, in mm as the stimulus column writes it: the answer
            // set is the stimuli's labels, each once.
            std::set<std::string> labels;
            for (std::size_t i = 0; i < p.stimuli.size(); ++i)
                if (!labels.insert(stimulus_label(p, p.stimuli[i])).second)
                    r.fail("stimuli[" + std::to_string(i) + "]", "h = " + stimulus_label(p, p.stimuli[i]) + " mm twice (heights are told apart to 0.1 mm)");
            if (labels != seen) {
                std::string want;
                for (const std::string& l : labels) want += (want.empty() ? "\"" : ", \"") + l + "\"";
                r.fail("answers", "curvature answers are the stimuli's heights in mm: " + want);
            }
            break;
        }
        case Task::surface_orientation:
            if (p.answers.size() != 2) r.fail("answers", "two answers: template A (0 < alpha < 90 deg), then B (90 < alpha < 180 deg)");
            break;
        case Task::edge_sharpness:
            if (p.answers.size() != 2) r.fail("answers", "two answers: the first edge felt sharper, then the second");
            break;
    }
}

// "procedure": {"type": ...} (protocol.hpp, Procedure). Every key but `type` has a default; a
// key that does not belong to the type is refused, like any unknown key.
Procedure read_procedure(const Reader& r, const json& j, const std::vector<double>& stimuli) {
    const std::string path = "procedure";
    if (!j.is_object()) r.fail(path, "expected an object such as {\"type\": \"staircase\"}");
    Procedure pr;
    pr.lo = *std::min_element(stimuli.begin(), stimuli.end());
    pr.hi = *std::max_element(stimuli.begin(), stimuli.end());
    const std::string type = r.text(r.need(j, path, "type"), path + ".type");
    const double span = pr.hi - pr.lo;
    if (type == "constant") {
        r.only(j, path, {"type"});
        return pr;
    }
    if (span <= 0.0) r.fail("stimuli", "an adaptive procedure needs a range: give at least two different stimuli (the smallest and largest bound it)");
    if (type == "staircase") {
        pr.type = ProcedureType::staircase;
        r.only(j, path, {"type", "rule", "start", "step", "halve_at", "reversals", "estimate_reversals", "max_trials"});
        if (j.contains("rule")) {
            // Exactly "1-up-N-down", N one plain digit 1..5: sscanf("%d-up-%d-down%c") took
            // "1-up-2.5-down" and "1-up-2abc" for 1-up-2-down, and " 2", "+2" and "02" for 2.
            const std::string rule = r.text(j["rule"], path + ".rule");
            const std::string head = "1-up-", tail = "-down";
            const bool form = rule.size() == head.size() + 1 + tail.size() && rule.compare(0, head.size(), head) == 0 &&
                              rule.compare(head.size() + 1, tail.size(), tail) == 0;
            const char n = form ? rule[head.size()] : '0';
            if (n < '1' || n > '5')
                r.fail(path + ".rule", "expected \"1-up-N-down\" with N from 1 to 5, one digit (e.g. \"1-up-2-down\", 70.7 % correct), got \"" + rule + "\"");
            pr.down = n - '0';
        }
        pr.start = r.number(j, path, "start", pr.lo, pr.hi, "(within the stimuli's range)", pr.hi);
        pr.step = r.number(j, path, "step", span * 1e-3, span, "(stimulus units, at most the stimuli's range)", span / 8.0);
        if (j.contains("halve_at")) {
            const json& h = j["halve_at"];
            if (!h.is_array()) r.fail(path + ".halve_at", "expected an array of reversal numbers, e.g. [2, 4]");
            pr.halve_at.clear();
            for (std::size_t i = 0; i < h.size(); ++i) {
                const std::string hp = path + ".halve_at[" + std::to_string(i) + "]";
                // JSON reads 0 and up as unsigned: compared as such, never wrapped.
                if (!h[i].is_number_unsigned() || h[i].get<std::uint64_t>() < 1 || h[i].get<std::uint64_t>() > 100)
                    r.fail(hp, "expected a reversal number from 1 to 100, got " + Reader::shown(h[i]));
                const int v = static_cast<int>(h[i].get<std::uint64_t>());
                if (!pr.halve_at.empty() && v <= pr.halve_at.back()) r.fail(hp, "reversal numbers must increase");
                pr.halve_at.push_back(v);
            }
        }
        pr.reversals = r.integer(j, path, "reversals", 2, 200, pr.reversals);
        pr.estimate_reversals = r.integer(j, path, "estimate_reversals", 1, 200, std::min(pr.estimate_reversals, pr.reversals));
        if (pr.estimate_reversals > pr.reversals)
            r.fail(path + ".estimate_reversals", "more than the " + std::to_string(pr.reversals) + " reversals the staircase runs for");
        pr.max_trials = r.integer(j, path, "max_trials", 2, 10000, pr.max_trials);
        return pr;
    }
    if (type == "quest+") {
        pr.type = ProcedureType::quest_plus;
        r.only(j, path, {"type", "function", "guess", "thresholds", "scales", "scale_min", "scale_max", "lapses", "lapse_max",
                         "levels", "trials", "stop_width"});
        if (j.contains("function") && !parse_psy_function(r.text(j["function"], path + ".function"), pr.function))
            r.fail(path + ".function", "expected \"logistic\", \"weibull\" or \"cumulative-normal\"");
        if (pr.function == PsyFunction::weibull && pr.lo <= 0.0) r.fail("stimuli", "the Weibull function needs positive stimuli");
        pr.guess = r.number(j, path, "guess", 0.0, 0.9, "", pr.guess);
        pr.thresholds = r.integer(j, path, "thresholds", 2, 400, pr.thresholds);
        pr.scales = r.integer(j, path, "scales", 1, 100, pr.scales);
        pr.lapses = r.integer(j, path, "lapses", 1, 20, pr.lapses);
        pr.levels = r.integer(j, path, "levels", 2, 400, pr.levels);
        const bool weib = pr.function == PsyFunction::weibull;
        pr.scale_min = r.number(j, path, "scale_min", 1e-9, 1e9, "", weib ? 1.0 : span / 40.0);
        pr.scale_max = r.number(j, path, "scale_max", 1e-9, 1e9, "", weib ? 8.0 : span / 2.0);
        if (pr.scale_max < pr.scale_min) r.fail(path + ".scale_max", "below scale_min");
        pr.lapse_max = r.number(j, path, "lapse_max", 0.0, 0.5, "", pr.lapse_max);
        if (pr.guess + pr.lapse_max >= 1.0) r.fail(path + ".lapse_max", "guess + lapse_max must stay below 1");
        pr.trials = r.integer(j, path, "trials", 1, 10000, pr.trials);
        pr.stop_width = r.number(j, path, "stop_width", 0.0, 1e9, "(stimulus units)", pr.stop_width);
        return pr;
    }
    r.fail(path + ".type", "unknown procedure \"" + type + "\" (constant, staircase, quest+)");
}

}  // namespace

const char* stimulus_unit(Task t) {
    switch (t) {
        case Task::contour_following: return "m";
        case Task::bump_counting: return "bumps";
        case Task::curvature: return "mm";
        case Task::surface_orientation: return "deg";
        case Task::edge_sharpness: return "mm";
    }
    return "";
}

int comparison_interval(std::uint64_t trial_seed) { return static_cast<int>(mix64(trial_seed ^ 0x2AFC2AFCull) & 1u) + 1; }

const char* to_string(HandModel h) { return h == HandModel::feel ? "feel" : "scripted"; }

const std::vector<HandField>& hand_population_fields() {
    using H = HandPopulation;
    static const std::vector<HandField> f = {
        {"delay_mean_s", &H::delay_mean_s, 0.02, 0.5, "s"},
        {"delay_sd_s", &H::delay_sd_s, 0.0, 0.2, "s"},
        {"delay_min_s", &H::delay_min_s, 0.01, 0.5, "s"},
        {"delay_max_s", &H::delay_max_s, 0.01, 1.0, "s"},
        {"press_median_n", &H::press_median_n, 0.05, 1.4, "N"},
        {"press_log_sd", &H::press_log_sd, 0.0, 1.0, ""},
        {"pace_log_sd", &H::pace_log_sd, 0.0, 1.0, ""},
        {"trial_pace_log_sd", &H::trial_pace_log_sd, 0.0, 1.0, ""},
        {"force_noise_cv_mean", &H::force_noise_cv_mean, 0.0, 1.0, ""},
        {"force_noise_cv_sd", &H::force_noise_cv_sd, 0.0, 0.5, ""},
        {"speed_noise_cv_mean", &H::speed_noise_cv_mean, 0.0, 1.0, ""},
        {"speed_noise_cv_sd", &H::speed_noise_cv_sd, 0.0, 0.5, ""},
        {"slide_speed_mps", &H::slide_speed_mps, 0.005, 0.3, "m/s"},
        {"hold_back", &H::hold_back, 1.1, 10.0, ""},
        {"angle_drift_rad_sqrt_m", &H::angle_drift_rad_sqrt_m, 0.0, 3.0, "rad/sqrt(m)"},
        {"angle_threshold_sd_deg", &H::angle_threshold_sd_deg, 0.0, 10.0, "deg"},
    };
    return f;
}

bool parse_hand_model(const std::string& name, HandModel& out) {
    if (name == "scripted") out = HandModel::scripted;
    else if (name == "feel") out = HandModel::feel;
    else return false;
    return true;
}

bool task_has_feel_hand(Task task) { return task == Task::contour_following || task == Task::bump_counting; }

std::string no_feel_hand_reason(Task task) {
    return std::string("a ") + to_string(task) +
           " protocol, whose simulated person has no hand that moves by feel (contour-following and bump-counting "
           "have one)";
}

void apply_hand_option(Protocol& p, const std::string& name) {
    HandModel h = HandModel::scripted;
    if (!parse_hand_model(name, h)) throw ExperimentError("--hand: expected scripted or feel, got \"" + name + "\"");
    if (h == HandModel::feel && !task_has_feel_hand(p.task))
        throw ExperimentError("--hand feel: " + p.origin + " is " + no_feel_hand_reason(p.task));
    p.hand_model = h;
}

const char* to_string(ProcedureType t) {
    switch (t) {
        case ProcedureType::constant: return "constant";
        case ProcedureType::staircase: return "staircase";
        case ProcedureType::quest_plus: return "quest+";
    }
    return "?";
}

double Procedure::target_p() const {
    switch (type) {
        case ProcedureType::staircase: return std::pow(0.5, 1.0 / down);
        case ProcedureType::quest_plus: return guess + (1.0 - guess) * 0.5;
        case ProcedureType::constant: break;
    }
    return NAN;
}

std::string Procedure::label() const {
    if (type == ProcedureType::staircase) return "staircase 1-up-" + std::to_string(down) + "-down";
    return to_string(type);
}

int orientation_template(double alpha_deg) { return alpha_deg < 90.0 ? 0 : 1; }

std::string stimulus_label(const Protocol& p, double stimulus) {
    char buf[32];
    if (p.task == Task::curvature) std::snprintf(buf, sizeof buf, "%g", std::round(stimulus * 1e4) / 10.0);  // mm
    else std::snprintf(buf, sizeof buf, "%g", stimulus);
    return buf;
}

const char* to_string(Task t) {
    switch (t) {
        case Task::contour_following: return "contour-following";
        case Task::bump_counting: return "bump-counting";
        case Task::curvature: return "curvature";
        case Task::surface_orientation: return "surface-orientation";
        case Task::edge_sharpness: return "edge-sharpness";
    }
    return "?";
}

Protocol parse_protocol(const std::string& text, const std::string& origin) {
    const Reader r{origin};
    json root;
    try {
        root = json::parse(text);
    } catch (const json::exception& e) {
        r.fail("", std::string("invalid JSON: ") + e.what());
    }
    DuplicateKeys duplicates;
    json::sax_parse(text, &duplicates);
    if (duplicates.found)
        r.fail(duplicates.found->first, "key \"" + duplicates.found->second +
                                            "\" given twice (a key appears once in its object: JSON readers keep either one)");
    r.only(root, "", {"format", "version", "name", "seed", "task", "conditions", "stimuli", "repetitions", "trials", "warmup",
                      "repeat_invalid", "answers", "hand", "finger", "force", "curves", "bumps", "arc", "block", "edge", "procedure", "participant",
                      "device"});
    if (r.text(r.need(root, "", "format"), "format") != "contactlab experiment protocol")
        r.fail("format", "expected \"contactlab experiment protocol\"");
    if (r.integer(root, "", "version", 1, 1, 0) != 1) r.fail("version", "missing (this ContactLab reads version 1)");
    Protocol p;
    p.origin = origin;
    p.text = text;
    p.sha256 = sha256_hex(text);
    p.name = r.text(r.need(root, "", "name"), "name");
    p.seed_paper = r.text(r.need(root, "", "seed"), "seed");
    p.task = task_of(r, r.text(r.need(root, "", "task"), "task"));
    if (root.contains("device")) {
        p.device = r.text(root["device"], "device");
        if (p.device != "sim-cld" && p.device != "sim-wearable")
            r.fail("device", "expected \"sim-cld\" (the contact location display rig) or \"sim-wearable\" (seed 003's platform)");
        if (p.device == "sim-wearable" && p.task != Task::curvature)
            r.fail("device", "sim-wearable runs the curvature task only (seed 003's platform displays an arc's slope)");
    }

    const json& conds = r.need(root, "", "conditions");
    if (!conds.is_array() || conds.empty()) r.fail("conditions", "expected a non-empty array");
    std::set<std::string> names;
    for (std::size_t i = 0; i < conds.size(); ++i) {
        const std::string path = "conditions[" + std::to_string(i) + "]";
        r.only(conds[i], path, {"name", "contact_location", "motion", "eccentricity", "total_stiffness"});
        Condition c;
        c.name = r.text(r.need(conds[i], path, "name"), path + ".name");
        if (c.name.empty() || c.name.find_first_of(",\"\n") != std::string::npos)
            r.fail(path + ".name", "must be non-empty, without commas, quotes or line breaks (it is a CSV field)");
        // It names trace files (PARTICIPANT-CONDITION-TRIAL.csv): checked here, not when a run writes.
        if (const std::string why = path_name_problem(c.name); !why.empty())
            r.fail(path + ".name", why + " (it is part of the traces' file names), got \"" + escaped_name(c.name) + "\"");
        if (!names.insert(c.name).second) r.fail(path + ".name", "\"" + c.name + "\" appears twice");
        c.contact_location = r.flag(conds[i], path, "contact_location", true);
        if (p.task == Task::curvature) {
            c.motion = r.text(r.need(conds[i], path, "motion"), path + ".motion");
            if (c.motion != "A" && c.motion != "B") r.fail(path + ".motion", "expected \"A\" or \"B\" (seed 003's tasks)");
        } else if (conds[i].contains("motion")) {
            r.fail(path + ".motion", "only for the curvature task");
        }
        if (p.task == Task::surface_orientation) {
            c.eccentricity = r.number(r.need(conds[i], path, "eccentricity"), path + ".eccentricity", 0.01, 100.0, "");
            c.total_stiffness = r.number(r.need(conds[i], path, "total_stiffness"), path + ".total_stiffness", 10.0, 1e5, "N/m");
        } else if (conds[i].contains("eccentricity") || conds[i].contains("total_stiffness")) {
            r.fail(path, "eccentricity and total_stiffness are only for the surface-orientation task");
        }
        p.conditions.push_back(c);
    }

    const json& stim = r.need(root, "", "stimuli");
    if (!stim.is_array() || stim.empty()) r.fail("stimuli", "expected a non-empty array of numbers");
    for (std::size_t i = 0; i < stim.size(); ++i) {
        const std::string path = "stimuli[" + std::to_string(i) + "]";
        double lo = 0.0, hi = 0.0;
        const char* unit = "";
        switch (p.task) {
            case Task::contour_following: lo = 0.01, hi = 0.15, unit = "m (d, the start line's distance from the edge)"; break;
            case Task::bump_counting: lo = 0.0, hi = 4.0, unit = "bumps"; break;
            case Task::curvature: lo = 0.001, hi = 0.1, unit = "m (the arc's height)"; break;
            case Task::surface_orientation: lo = 0.0, hi = 180.0, unit = "deg (the compliant axis from the surface)"; break;
            case Task::edge_sharpness: lo = 0.0, hi = 20.0, unit = "mm (the comparison's radius less the reference's)"; break;
        }
        const double v = r.number(stim[i], path, lo, hi, unit);
        if (p.task == Task::bump_counting && v != std::floor(v)) r.fail(path, "a bump count is a whole number");
        if (p.task == Task::surface_orientation && (v == 0.0 || v == 90.0 || v == 180.0))
            r.fail(path, "the compliant axis at 0, 90 or 180 deg is tilted neither way: neither template A (0 < alpha < 90) "
                         "nor B (90 < alpha < 180) is right");
        if (p.task == Task::edge_sharpness && v <= 0.0)
            r.fail(path, "the comparison must be blunter than the reference (a difference above 0 mm), or no answer is right");
        p.stimuli.push_back(v);
    }
    if (root.contains("procedure")) p.procedure = read_procedure(r, root["procedure"], p.stimuli);
    p.repetitions = r.integer(root, "", "repetitions", 1, 1000, 1);
    // Absent (0 here): repetitions x stimuli. Given, at least 1: "trials": 0 is no design.
    p.trials = r.integer(root, "", "trials", 1, 100000, 0);
    p.warmup = r.integer(root, "", "warmup", 0, 1000, 0);
    p.repeat_invalid = r.flag(root, "", "repeat_invalid", true);
    // Adaptive procedures: `warmup` practice trials per condition, at the procedure's easy end,
    // before its own trials.
    const int per_condition = p.procedure.type != ProcedureType::constant ? p.warmup + 1
                              : p.trials > 0                               ? p.trials
                                                                            : p.repetitions * static_cast<int>(p.stimuli.size());
    if (p.warmup >= per_condition) r.fail("warmup", "leaves no trial to analyse (" + std::to_string(per_condition) + " per condition)");

    if (root.contains("answers")) {
        const json& a = root["answers"];
        if (!a.is_array()) r.fail("answers", "expected an array of strings");
        for (std::size_t i = 0; i < a.size(); ++i) p.answers.push_back(r.text(a[i], "answers[" + std::to_string(i) + "]"));
    }
    if (p.task != Task::contour_following && p.answers.size() < 2) r.fail("answers", "a judgement task needs at least two answers");
    if (p.task == Task::contour_following && !p.answers.empty()) r.fail("answers", "the contour-following task is timed, not answered");
    check_answers(r, p);

    if (root.contains("hand")) {
        r.only(root["hand"], "hand", {"speed", "press", "model"});
        if (root["hand"].contains("model") &&
            !parse_hand_model(r.text(root["hand"]["model"], "hand.model"), p.hand_model))
            r.fail("hand.model", "expected \"scripted\" or \"feel\"");
        if (p.hand_model == HandModel::feel && !task_has_feel_hand(p.task))
            r.fail("hand.model", "\"feel\": this is " + no_feel_hand_reason(p.task) + "; use \"scripted\"");
        p.hand_speed = r.number(root["hand"], "hand", "speed", 0.005, 1.0, "m/s", p.hand_speed);
        p.hand_press = r.number(root["hand"], "hand", "press", 0.0, 0.02, "m", p.hand_press);
    }
    if (root.contains("finger")) {
        r.only(root["finger"], "finger", {"radius", "length"});
        p.finger_radius = r.number(root["finger"], "finger", "radius", 0.005, 0.1, "m", p.finger_radius);
        p.pad_length = r.number(root["finger"], "finger", "length", 0.002, 0.1, "m", p.pad_length);
        if (p.pad_length >= 2.0 * 3.14159265358979 * p.finger_radius) r.fail("finger.length", "longer than the finger's circle");
    }
    if (root.contains("force")) {
        r.only(root["force"], "force", {"stiffness", "max_force"});
        p.stiffness = r.number(root["force"], "force", "stiffness", 10.0, 1e5, "N/m", p.stiffness);
        p.max_force = r.number(root["force"], "force", "max_force", 0.01, 100.0, "N", p.max_force);
    }
    if (root.contains("curves")) {
        r.only(root["curves"], "curves", {"mode", "tolerance"});
        const nlohmann::json& c = root["curves"];
        const std::string mode = r.text(r.need(c, "curves", "mode"), "curves.mode");
        const std::optional<CurveMode> named = curve_mode_named(mode);  // the scene format's names
        if (!named) r.fail("curves.mode", "unknown curve mode \"" + mode + "\" (expected \"exact\" or \"flatten\")");
        p.curves.mode = *named;
        p.curves.tolerance = r.number(c, "curves", "tolerance", limits::kMinCurveTolerance, limits::kMaxCurveTolerance, "m", p.curves.tolerance);
    }
    auto only_for = [&](const char* key, Task t) {
        if (root.contains(key) && p.task != t) r.fail(key, std::string("only for the ") + to_string(t) + " task");
    };
    only_for("bumps", Task::bump_counting);
    only_for("arc", Task::curvature);
    only_for("block", Task::contour_following);
    only_for("edge", Task::edge_sharpness);
    if (root.contains("edge")) {
        r.only(root["edge"], "edge", {"reference_radius", "slope_deg"});
        p.reference_radius = r.number(root["edge"], "edge", "reference_radius", 0.0001, 0.05, "m", p.reference_radius);
        p.edge_slope_deg = r.number(root["edge"], "edge", "slope_deg", 5.0, 60.0, "deg", p.edge_slope_deg);
    }
    if (root.contains("bumps")) {
        r.only(root["bumps"], "bumps", {"small", "large", "length", "base_span"});
        p.small_bump = r.number(root["bumps"], "bumps", "small", 0.0005, 0.05, "m", p.small_bump);
        p.large_bump = r.number(root["bumps"], "bumps", "large", 0.0005, 0.05, "m", p.large_bump);
        p.traced_length = r.number(root["bumps"], "bumps", "length", 0.05, 1.0, "m", p.traced_length);
        p.base_span = r.number(root["bumps"], "bumps", "base_span", 0.0, 1.0, "m", p.base_span);
    }
    if (root.contains("arc")) {
        r.only(root["arc"], "arc", {"chord"});
        p.chord = r.number(root["arc"], "arc", "chord", 0.02, 1.0, "m", p.chord);
    }
    if (root.contains("block")) {
        r.only(root["block"], "block", {"finish_depth"});
        p.finish_depth = r.number(root["block"], "block", "finish_depth", 0.01, 0.09, "m", p.finish_depth);
    }
    if (root.contains("participant")) {
        const json& m = root["participant"];
        r.only(m, "participant", {"force_angle_threshold_deg", "force_angle_noise_deg", "location_threshold_mm",
                                  "location_noise_mm", "stiffness_noise", "reaction_time_s", "reaction_time_sd_s", "stop_time_s",
                                  "lapse_rate_hz", "lapse_duration_s", "tilt_range_noise", "edge_rate_noise",
                                  "path_threshold_mm", "path_noise_mm", "hand"});
        ParticipantModel& pm = p.participant;
        pm.force_angle_threshold_deg = r.number(m, "participant", "force_angle_threshold_deg", 0.0, 90.0, "deg", pm.force_angle_threshold_deg);
        pm.force_angle_noise_deg = r.number(m, "participant", "force_angle_noise_deg", 0.0, 90.0, "deg", pm.force_angle_noise_deg);
        pm.location_threshold_mm = r.number(m, "participant", "location_threshold_mm", 0.0, 50.0, "mm", pm.location_threshold_mm);
        pm.location_noise_mm = r.number(m, "participant", "location_noise_mm", 0.0, 50.0, "mm", pm.location_noise_mm);
        pm.stiffness_noise = r.number(m, "participant", "stiffness_noise", 0.0, 10.0, "", pm.stiffness_noise);
        pm.reaction_time_s = r.number(m, "participant", "reaction_time_s", 0.0, 5.0, "s", pm.reaction_time_s);
        pm.reaction_time_sd_s = r.number(m, "participant", "reaction_time_sd_s", 0.0, 1.0, "s", pm.reaction_time_sd_s);
        pm.stop_time_s = r.number(m, "participant", "stop_time_s", 0.0, 10.0, "s", pm.stop_time_s);
        pm.lapse_rate_hz = r.number(m, "participant", "lapse_rate_hz", 0.0, 10.0, "Hz", pm.lapse_rate_hz);
        pm.lapse_duration_s = r.number(m, "participant", "lapse_duration_s", 0.0, 5.0, "s", pm.lapse_duration_s);
        pm.tilt_range_noise = r.number(m, "participant", "tilt_range_noise", 0.0, 1.0, "", pm.tilt_range_noise);
        pm.edge_rate_noise = r.number(m, "participant", "edge_rate_noise", 0.0, 10.0, "", pm.edge_rate_noise);
        pm.path_threshold_mm = r.number(m, "participant", "path_threshold_mm", 0.0, 50.0, "mm", pm.path_threshold_mm);
        pm.path_noise_mm = r.number(m, "participant", "path_noise_mm", 0.0, 50.0, "mm", pm.path_noise_mm);
        if (m.contains("hand")) {
            std::set<std::string> keys;
            for (const HandField& f : hand_population_fields()) keys.insert(f.name);
            r.only(m["hand"], "participant.hand", keys);
            for (const HandField& f : hand_population_fields())
                pm.hand.*f.member = r.number(m["hand"], "participant.hand", f.name, f.lo, f.hi, f.unit, pm.hand.*f.member);
            if (!(pm.hand.delay_min_s <= pm.hand.delay_max_s)) r.fail("participant.hand", "delay_min_s must not exceed delay_max_s");
        }
    }
    return p;
}

Protocol load_protocol(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw ExperimentError(path + ": cannot open (" + std::strerror(errno) + ")");
    std::ostringstream s;
    s << in.rdbuf();
    return parse_protocol(s.str(), path);
}

}  // namespace contactlab::experiments
