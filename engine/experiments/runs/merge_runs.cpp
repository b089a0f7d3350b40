// merge_runs.cpp — one results file from runs split by participants (merge_runs.hpp).
#include "engine/experiments/runs/merge_runs.hpp"

#include "engine/experiments/base/results_table.hpp"
#include "engine/experiments/base/sha256.hpp"
#include "engine/experiments/runs/finished_run.hpp"
#include "engine/experiments/runs/run_meta.hpp"
#include "haptics/atomic_file.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <filesystem>
#include <map>

namespace contactlab::experiments {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

using Source = FinishedRun;

// "" when b comes from the same study as a (all but the participants), else what differs.
std::string study_difference(const Source& a, const Source& b) {
    auto sha = [](const json& v) { return v.is_string() ? v.get<std::string>().substr(0, 12) + "..." : std::string("none"); };
    if (a.meta.value("protocol_sha256", json()) != b.meta.value("protocol_sha256", json()))
        return "another protocol (sha256 " + sha(b.meta.value("protocol_sha256", json())) + " against " +
               sha(a.meta.value("protocol_sha256", json())) + " in " + a.path + ")";
    for (const char* key : {"seed", "hand", "device", "servo_rate_hz", "traces", "contactlab_version", "commit"})
        if (a.meta.value(key, json()) != b.meta.value(key, json()))
            return std::string("another ") + key + " (" + b.meta.value(key, json()).dump() + " against " +
                   a.meta.value(key, json()).dump() + " in " + a.path + ")";
    if (a.table.columns != b.table.columns) return "other columns than " + a.path;
    return "";
}

// "sim12" -> ("sim", 12); ids without a trailing number sort after, by name.
std::pair<std::string, long long> id_order(const std::string& id) {
    std::size_t digits = id.size();
    while (digits > 0 && id[digits - 1] >= '0' && id[digits - 1] <= '9') --digits;
    if (digits == id.size() || id.size() - digits > 18) return {id, -1};
    return {id.substr(0, digits), std::stoll(id.substr(digits))};
}

}  // namespace

MergeSummary merge_runs(const std::vector<std::string>& paths, const std::string& output, const std::string& command,
                        bool overwrite) {
    if (paths.empty()) throw ExperimentError("experiment merge: no results files to merge");
    std::vector<Source> sources;
    for (const std::string& p : paths) {
        if (fs::weakly_canonical(p) == fs::weakly_canonical(output))
            throw ExperimentError(p + ": is also the output (-o); merge into a new file");
        sources.push_back(read_finished_run(p));
    }
    for (std::size_t i = 1; i < sources.size(); ++i)
        if (const std::string d = study_difference(sources[0], sources[i]); !d.empty())
            throw ExperimentError(sources[i].path + ": from " + d + ": only runs of one study merge");
    if (!overwrite && (fs::exists(output) || fs::exists(meta_path(output)) || fs::exists(output + ".traces")))
        throw ExperimentError(output + ": exists; give --overwrite to replace it");

    // Each participant once: from the first source holding it, the others' rows the same bytes.
    MergeSummary out;
    std::map<std::string, std::size_t> owner;  // participant -> source
    for (std::size_t i = 0; i < sources.size(); ++i)
        for (const auto& [id, lines] : sources[i].rows_of) {
            const auto [it, fresh] = owner.emplace(id, i);
            if (fresh) continue;
            if (sources[it->second].rows_of.at(id) != lines)
                throw ExperimentError(sources[i].path + ": participant " + id + " is also in " + sources[it->second].path +
                                      " with other rows: the same participant run twice differently cannot be merged");
            ++out.duplicates;
        }
    for (const auto& [id, i] : owner) out.participants.push_back(id);
    std::stable_sort(out.participants.begin(), out.participants.end(),
                     [](const std::string& a, const std::string& b) { return id_order(a) < id_order(b); });

    std::string csv = csv_line(sources[0].table.columns) + "\n";
    for (const std::string& id : out.participants)
        for (const std::string& line : sources[owner.at(id)].rows_of.at(id)) {
            csv += line + "\n";
            ++out.rows;
        }

    // Traces first (the results file and its meta name a finished run only once all is there).
    const bool traces = sources[0].meta.value("traces", false);
    const fs::path trace_dir = output + ".traces";
    if (overwrite) fs::remove_all(trace_dir);
    if (traces) {
        fs::create_directories(trace_dir);
        for (const std::string& id : out.participants) {
            const fs::path from = sources[owner.at(id)].path + ".traces";
            std::error_code ec;
            for (const auto& e : fs::directory_iterator(from, ec)) {
                const std::string name = e.path().filename().string();
                if (name.rfind(id + "-", 0) != 0) continue;
                fs::copy_file(e.path(), trace_dir / name, fs::copy_options::overwrite_existing);
                ++out.traces;
            }
            if (ec) throw ExperimentError(from.string() + ": cannot read its traces (" + ec.message() + ")");
        }
    }

    json meta = sources[0].meta;
    meta["participants"] = out.participants;
    meta["command"] = command;
    meta["started_utc"] = utc_now();
    meta["resumed"] = json::array();
    meta["merged_from"] = json::array();
    for (const Source& s : sources)
        meta["merged_from"].push_back({{"file", s.path},
                                       {"sha256", sha256_hex(s.bytes)},
                                       {"participants", s.meta.value("participants", json::array())},
                                       {"command", s.meta.value("command", json())},
                                       {"host", s.meta.value("host", json())},
                                       {"started_utc", s.meta.value("started_utc", json())},
                                       {"finished_utc", s.meta.value("finished_utc", json())}});
    meta["host"] = host_name();
    finish_meta(meta, out.rows);
    write_file_atomically(output, csv);
    write_meta(output, meta);
    return out;
}

}  // namespace contactlab::experiments
