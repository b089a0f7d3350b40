// run_meta.cpp — provenance files (run_meta.hpp).
#include "engine/experiments/runs/run_meta.hpp"

#include "engine/experiments/base/results_table.hpp"
#include "haptics/atomic_file.hpp"

#include <contactlab/version.hpp>

#include <cerrno>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <unistd.h>

namespace contactlab::experiments {

using nlohmann::json;

std::string meta_path(const std::string& results_path) { return results_path + ".meta.json"; }

std::string utc_now() {
    const std::time_t now = std::time(nullptr);
    std::tm tm{};
    gmtime_r(&now, &tm);
    char buf[32];
    std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", &tm);
    return buf;
}

std::string host_name() {
    char buf[256] = {};
    if (gethostname(buf, sizeof buf - 1) != 0) return "";
    return buf;
}

json make_meta(const RunIdentity& id, const std::string& command) {
    json m;
    m["format"] = kMetaFormat;
    m["version"] = 1;
    m["contactlab_version"] = CONTACTLAB_VERSION;
    // Only when built from git: a tarball build has no commit to name.
    if (*CONTACTLAB_GIT_COMMIT) m["commit"] = CONTACTLAB_GIT_COMMIT;
    m["protocol_path"] = id.protocol_path;
    m["protocol_sha256"] = id.protocol->sha256;
    // The content as JSON (the file parsed, so it reads as the protocol did), its name and task
    // at hand for a reader that does not open it.
    m["protocol"] = json::parse(id.protocol->text);
    m["task"] = to_string(id.protocol->task);
    // The simulated person's hand (the protocol's hand.model, or experiment run --hand): the same
    // protocol file run with another hand is another study.
    m["hand"] = to_string(id.protocol->hand_model);
    m["seed"] = id.seed;
    m["participants"] = id.participants;
    m["device"] = id.device;
    m["servo_rate_hz"] = id.servo_rate_hz;
    m["traces"] = id.traces;
    m["started_utc"] = utc_now();
    m["finished_utc"] = nullptr;
    m["rows"] = nullptr;
    m["command"] = command;
    m["host"] = host_name();  // where it ran: runs split over a cluster's nodes are merged later
    m["resumed"] = json::array();
    return m;
}

void finish_meta(json& meta, std::size_t rows) {
    meta["finished_utc"] = utc_now();
    meta["rows"] = rows;
}

void note_resume(json& meta, const std::string& command) {
    if (!meta.contains("resumed") || !meta["resumed"].is_array()) meta["resumed"] = json::array();
    meta["resumed"].push_back({{"utc", utc_now()}, {"command", command}});
}

std::optional<json> read_meta(const std::string& results_path) {
    const std::string path = meta_path(results_path);
    if (!std::filesystem::exists(path)) return std::nullopt;
    std::ifstream in(path, std::ios::binary);
    if (!in) throw ExperimentError(path + ": cannot open (" + std::strerror(errno) + ")");
    std::ostringstream s;
    s << in.rdbuf();
    json m;
    try {
        m = json::parse(s.str());
    } catch (const json::exception& e) {
        throw ExperimentError(path + ": not a results meta file (invalid JSON: " + e.what() + ")");
    }
    if (!m.is_object() || m.value("format", "") != kMetaFormat)
        throw ExperimentError(path + ": not a results meta file (\"format\" is not \"" + kMetaFormat + "\")");
    return m;
}

std::string identity_difference(const json& old_meta, const json& now) {
    auto short_sha = [](const json& v) { return v.is_string() ? v.get<std::string>().substr(0, 12) : std::string("none"); };
    if (old_meta.value("protocol_sha256", json()) != now["protocol_sha256"])
        return "another protocol (sha256 " + short_sha(now["protocol_sha256"]) + "... now, " +
               short_sha(old_meta.value("protocol_sha256", json())) + "... in the file, from " +
               old_meta.value("protocol_path", std::string("?")) + ")";
    if (old_meta.value("seed", json()) != now["seed"])
        return "another seed (" + now["seed"].dump() + " now, " + old_meta.value("seed", json()).dump() + " in the file)";
    if (old_meta.value("participants", json()) != now["participants"])
        return "other participants (" + now["participants"].dump() + " now, " + old_meta.value("participants", json()).dump() +
               " in the file)";
    // A rebuilt program may perform the same trials differently: a run is resumed by the build
    // that started it.
    for (const char* key : {"hand", "device", "servo_rate_hz", "traces", "contactlab_version", "commit"})
        if (old_meta.value(key, json()) != now[key])
            return std::string("another ") + key + " (" + now[key].dump() + " now, " + old_meta.value(key, json()).dump() + " in the file)";
    return "";
}

void write_meta(const std::string& results_path, const json& meta) { write_file_atomically(meta_path(results_path), meta.dump(2) + "\n"); }

}  // namespace contactlab::experiments
