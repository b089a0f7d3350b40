// finished_run.cpp — a finished results file read and checked as a whole (finished_run.hpp).
#include "engine/experiments/runs/finished_run.hpp"

#include "engine/experiments/runs/run_meta.hpp"

#include <algorithm>
#include <set>

namespace contactlab::experiments {

using nlohmann::json;

FinishedRun read_finished_run(const std::string& path) {
    FinishedRun s;
    s.path = path;
    s.bytes = read_file_bytes(path);
    const auto meta = read_meta(path);
    if (!meta) throw ExperimentError(path + ": no " + meta_path(path) + ": which run made it is unknown, so it cannot be used");
    s.meta = *meta;
    if (s.meta.value("finished_utc", json()).is_null())
        throw ExperimentError(path + ": an unfinished run (its meta has no finished_utc): finish it (run the same command "
                                     "again) first");
    s.table = parse_results_csv(s.bytes, path);
    const json rows = s.meta.value("rows", json());
    if (!rows.is_number_unsigned() || rows.get<std::size_t>() != s.table.rows.size())
        throw ExperimentError(path + ": holds " + std::to_string(s.table.rows.size()) + " rows where its meta says " + rows.dump() +
                              " (a truncated or edited file)");
    // The run wrote each row as csv_line: the same bytes again, or the file is not a run's.
    std::string again = csv_line(s.table.columns) + "\n";
    for (const auto& r : s.table.rows) again += csv_line(r) + "\n";
    if (again != s.bytes)
        throw ExperimentError(path + ": not as `experiment run` wrote it (its bytes differ from its rows written again)");
    const auto col = s.table.column("participant");
    if (!col) throw ExperimentError(path + ": no participant column");
    for (const auto& r : s.table.rows) {
        auto& rows = s.rows_of[r[*col]];
        if (rows.empty()) s.participants.push_back(r[*col]);
        rows.push_back(csv_line(r));
    }
    return s;
}

FinishedRun read_pool_run(const std::string& path, const Protocol& protocol, std::size_t needed, const std::string& option) {
    FinishedRun run = read_finished_run(path);
    const json sha = run.meta.value("protocol_sha256", json());
    if (sha != protocol.sha256)
        throw ExperimentError(option + " " + path + ": a run of another protocol (sha256 " +
                              (sha.is_string() ? sha.get<std::string>().substr(0, 12) : std::string("none")) + "... in its meta, " +
                              protocol.sha256.substr(0, 12) + "... for " + protocol.origin + ")");
    if (run.rows_of.size() < needed)
        throw ExperimentError(option + " " + path + ": holds " + std::to_string(run.rows_of.size()) + " participants, " +
                              std::to_string(needed) + " asked");
    return run;
}

ResultsTable first_participants(const FinishedRun& run, std::size_t n) {
    const std::set<std::string> kept(run.participants.begin(), run.participants.begin() + std::min(n, run.participants.size()));
    const std::size_t col = *run.table.column("participant");
    ResultsTable t = run.table;
    t.rows.clear();
    t.lines.clear();
    for (std::size_t i = 0; i < run.table.rows.size(); ++i)
        if (kept.count(run.table.rows[i][col])) {
            t.rows.push_back(run.table.rows[i]);
            t.lines.push_back(run.table.lines[i]);
        }
    return t;
}

}  // namespace contactlab::experiments
