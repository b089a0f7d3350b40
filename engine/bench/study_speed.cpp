// study_speed.cpp — a simulated participant of a shipped protocol, timed by stage (study_speed.hpp).
#include "engine/bench/study_speed.hpp"

#include "engine/experiments/runs/experiment_run.hpp"
#include "engine/experiments/protocol/protocol.hpp"
#include "engine/experiments/base/results_table.hpp"

#include <cstdlib>
#include <filesystem>
#include <stdexcept>
#include <string>

namespace contactlab::bench {
namespace {

// The results file's time_s column summed (s); an empty cell (not measured) counts nothing.
double rows_time_s(const std::string& results) {
    const experiments::ResultsTable t = experiments::read_results_csv(results);
    const auto col = t.column("time_s");
    if (!col) throw experiments::ExperimentError(results + ": no time_s column");
    double sum = 0.0;
    for (std::size_t r = 0; r < t.rows.size(); ++r)
        if (!t.rows[r][*col].empty()) sum += t.number(r, *col);
    return sum;
}

}  // namespace

StudySpeed study_speed(const std::string& protocol_path, bool quick) {
    StudySpeed s;
    if (protocol_path.empty()) {
        s.skipped = "no protocol file";
        return s;
    }
    namespace fs = std::filesystem;
    std::error_code ec;
    // The run's files (results, meta, parts) go to a folder of their own, removed afterwards.
    std::string tmpl = (fs::temp_directory_path(ec) / "contactlab-bench-study-XXXXXX").string();
    if (ec || !::mkdtemp(tmpl.data())) {
        s.skipped = "no temporary folder for the run's files";
        return s;
    }
    const fs::path dir = tmpl;
    try {
        experiments::Protocol p = experiments::load_protocol(protocol_path);
        s.protocol = p.name;
        if (quick) {
            if (p.trials > 0) p.trials = 10;  // seed 002: trials per condition drawn at random
            p.repetitions = 1;
            p.warmup = 0;
        }
        experiments::RunOptions o;
        o.participants = {1};
        o.output = (dir / "study.csv").string();
        o.traces = false;
        o.jobs = 1;
        o.profile = true;
        s.profile = experiments::run_experiment(p, o).profile;
        s.rows_time_s = rows_time_s(o.output);
        s.skipped.clear();
    } catch (const std::exception& e) {
        // A relative path is found from the checkout's root or in an installed tree's share/.
        s.skipped = std::string(e.what()) + " (run bench from the checkout's root, or install ContactLab)";
    }
    fs::remove_all(dir, ec);
    return s;
}

}  // namespace contactlab::bench
