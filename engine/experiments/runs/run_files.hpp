// run_files.hpp — the files of one batch run and who owns them: RESULTS.csv, its meta
// (run_meta.hpp), RESULTS.csv.parts/ (each participant's finished trials while the run is
// unfinished) and RESULTS.csv.traces/. claim() first locks RESULTS.csv.lock (flock; removed
// when the run is done) so that two processes never write one run, and only then decides, from
// the meta, whether the files are this run's to resume, another run's to refuse, or (overwrite)
// to clear; it removes what a killed run left half-written (write_file_atomically's
// NAME.tmp-XXXXXX).
#pragma once

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace contactlab::experiments {

struct RunState {
    bool resuming = false;   // the same run, unfinished: carry on from its parts
    bool complete = false;   // the same run, finished: nothing to do
    nlohmann::json meta;     // the meta found (resuming or complete)
};

class RunFiles {
public:
    explicit RunFiles(std::string output);
    ~RunFiles();
    RunFiles(const RunFiles&) = delete;
    RunFiles& operator=(const RunFiles&) = delete;

    // Throws ExperimentError saying why the files are not this run's (and naming --overwrite), or
    // that another process is writing them now (whatever the files on disk look like).
    RunState claim(const nlohmann::json& now_meta, bool overwrite);

    std::string part(const std::string& participant) const;
    // The participant's checksums (RESULTS.csv.parts/P.sums): one line per committed row,
    // "ROW_SHA256 TRACE_SHA256" ("-" for no trace), written before the row joins the part, so a
    // resume can tell a row or trace changed or lost since from one the run wrote.
    std::string sums(const std::string& participant) const;
    std::string trace(const std::string& participant, const std::string& condition, int trial) const;
    // The participant's rows already on disk, in order: from its part, else from RESULTS.csv
    // (an interrupted run whose parts were removed by hand). Cells checked against `columns`.
    std::vector<std::vector<std::string>> done_rows(const std::vector<std::string>& columns, const std::string& participant) const;
    // The run is in RESULTS.csv: remove the parts, release the lock.
    void finish();

private:
    void lock();
    void unlock();
    void remove_temps() const;

    std::string output_, parts_, traces_, lock_;
    int lock_fd_ = -1;
};

}  // namespace contactlab::experiments
