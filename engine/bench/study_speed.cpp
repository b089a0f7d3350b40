// study_speed.cpp — a simulated participant of a shipped protocol, timed by stage (study_speed.hpp).
#include "engine/bench/study_speed.hpp"

#include "engine/experiments/runs/experiment_run.hpp"
#include "engine/experiments/protocol/protocol.hpp"

#include <cstdlib>
#include <filesystem>
#include <stdexcept>
#include <string>

namespace contactlab::bench {

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
        s.skipped.clear();
    } catch (const std::exception& e) {
        // A relative path is found from the checkout's root or in an installed tree's share/.
        s.skipped = std::string(e.what()) + " (run bench from the checkout's root, or install ContactLab)";
    }
    fs::remove_all(dir, ec);
    return s;
}

}  // namespace contactlab::bench
