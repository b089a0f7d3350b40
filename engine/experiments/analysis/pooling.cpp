// pooling.cpp — several results files as one table (pooling.hpp).
#include "engine/experiments/analysis/pooling.hpp"

#include "engine/experiments/runs/run_meta.hpp"

#include <map>
#include <set>

namespace contactlab::experiments {

PooledResults pool_results(const std::vector<std::string>& paths, bool pool_protocols) {
    if (paths.empty()) throw ExperimentError("no results file");
    PooledResults out;
    out.provenance = nlohmann::json::object();
    std::string first_protocol, first_with_protocol;
    std::map<std::string, std::string> participant_file;  // participant -> the first file it is in
    std::set<std::string> repeated;
    for (std::size_t f = 0; f < paths.size(); ++f) {
        const std::string& path = paths[f];
        ResultsTable t = read_results_csv(path);
        const auto meta = read_meta(path);
        out.provenance[path] = meta ? *meta : nlohmann::json(nullptr);
        if (!meta) {
            out.warnings.push_back(path + ": no " + meta_path(path) + ": which program, protocol and seed made it is unknown");
        } else {
            if (meta->value("finished_utc", nlohmann::json()).is_null())
                out.warnings.push_back(path + ": an unfinished run (finished_utc is null): its rows are part of the run");
            const std::string sha = meta->value("protocol_sha256", std::string());
            if (first_with_protocol.empty()) {
                first_protocol = sha;
                first_with_protocol = path;
            } else if (sha != first_protocol) {
                const std::string what = path + " and " + first_with_protocol + " come from different protocols (sha256 " +
                                         sha.substr(0, 12) + "... from " + meta->value("protocol_path", std::string("?")) + ", " +
                                         first_protocol.substr(0, 12) + "... from " +
                                         out.provenance[first_with_protocol].value("protocol_path", std::string("?")) + ")";
                if (!pool_protocols) throw ExperimentError(what + "; give --pool-protocols to pool them anyway");
                out.warnings.push_back(what + ": pooled as asked (--pool-protocols)");
            }
        }
        if (f == 0) {
            out.table = std::move(t);
            out.table.origin = path;
            out.table.files = {path};
            out.table.file_of.assign(out.table.rows.size(), 0);
        } else {
            // The same columns in any order: each row is rearranged into the first file's order.
            std::vector<std::size_t> from;
            for (const std::string& c : out.table.columns) {
                const auto i = t.column(c);
                if (!i || t.columns.size() != out.table.columns.size())
                    throw ExperimentError(path + ": line 1: its columns are not " + paths.front() + "'s (pooled files need the same columns)");
                from.push_back(*i);
            }
            out.table.files.push_back(path);
            for (std::size_t r = 0; r < t.rows.size(); ++r) {
                std::vector<std::string> row;
                for (std::size_t i : from) row.push_back(std::move(t.rows[r][i]));
                out.table.rows.push_back(std::move(row));
                out.table.lines.push_back(t.line(r));
                out.table.file_of.push_back(f);
            }
            out.table.origin += ", " + path;
        }
        if (const auto pc = out.table.column("participant"))
            for (std::size_t r = 0; r < out.table.rows.size(); ++r) {
                if (out.table.file_of[r] != f) continue;
                const std::string& p = out.table.rows[r][*pc];
                const auto [it, fresh] = participant_file.emplace(p, path);
                if (!fresh && it->second != path && repeated.insert(p).second)
                    out.warnings.push_back("participant " + p + " is in " + it->second + " and " + path + ": pooled as one participant");
            }
    }
    return out;
}

}  // namespace contactlab::experiments
