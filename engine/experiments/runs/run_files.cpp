// run_files.cpp — claiming, cleaning and locking a run's files (run_files.hpp).
#include "engine/experiments/runs/run_files.hpp"

#include "engine/experiments/base/results_table.hpp"
#include "engine/experiments/runs/run_meta.hpp"

#include <cerrno>
#include <cstring>
#include <filesystem>

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

namespace contactlab::experiments {
namespace {

namespace fs = std::filesystem;

// write_file_atomically's temporaries: NAME.tmp-XXXXXX (mkstemp's six characters).
bool is_temp_of(const std::string& name, const std::string& target) {
    const std::string stem = target + ".tmp-";
    return name.size() == stem.size() + 6 && name.compare(0, stem.size(), stem) == 0;
}
bool is_temp(const std::string& name) { return name.size() > 11 && name.compare(name.size() - 11, 5, ".tmp-") == 0; }

std::string overwrite_hint() { return "; give --overwrite to replace it (its traces too), or another --output"; }

}  // namespace

RunFiles::RunFiles(std::string output)
    : output_(std::move(output)), parts_(output_ + ".parts"), traces_(output_ + ".traces"), lock_(output_ + ".lock") {}

RunFiles::~RunFiles() { unlock(); }

std::string RunFiles::part(const std::string& participant) const { return parts_ + "/" + participant + ".csv"; }

std::string RunFiles::sums(const std::string& participant) const { return parts_ + "/" + participant + ".sums"; }

std::string RunFiles::trace(const std::string& participant, const std::string& condition, int trial) const {
    return traces_ + "/" + participant + "-" + condition + "-" + std::to_string(trial) + ".csv";
}

RunState RunFiles::claim(const nlohmann::json& now_meta, bool overwrite) {
    // The lock first: nothing below looks at the files (the meta, the parts folder, what
    // --overwrite removes) until this process is the one run that may. When the lock lived on the
    // parts folder it was taken after those looks, so a second run started with the first was told
    // that the folder "exists without R.csv.meta.json", or with --overwrite removed a live run's
    // folder and locked a new one beside it.
    lock();
    RunState st;
    std::error_code ec;
    if (overwrite) {
        // This run's files, and only these, are cleared: the results, meta, parts and traces.
        fs::remove(output_, ec);
        fs::remove(meta_path(output_), ec);
        fs::remove_all(parts_, ec);
        fs::remove_all(traces_, ec);
    } else if (const auto old = read_meta(output_)) {
        if (const std::string why = identity_difference(*old, now_meta); !why.empty())
            throw ExperimentError(output_ + ": written by another run: " + why + overwrite_hint());
        st.meta = *old;
        st.complete = !(*old)["finished_utc"].is_null() && !fs::exists(parts_);
        st.resuming = !st.complete;
    } else {
        for (const std::string& f : {output_, parts_, traces_})
            if (fs::exists(f))
                throw ExperimentError(f + ": exists without " + fs::path(meta_path(output_)).filename().string() +
                                      " (left by an older ContactLab or another program: which run made it cannot be told)" +
                                      overwrite_hint());
    }
    if (st.complete) return st;
    fs::create_directories(parts_);
    remove_temps();
    if (now_meta.value("traces", true)) fs::create_directories(traces_);
    return st;
}

void RunFiles::lock() {
    // RESULTS.csv.lock, beside the results: it outlives --overwrite (which removes the parts
    // folder) and is there before the parts are. Removed by its holder when done, so a finished
    // run leaves only its results; whoever opened it just before that removal finds the file it
    // locked gone (or another in its place) and opens it again.
    std::error_code ec;
    const fs::path out(output_);
    if (out.has_parent_path()) fs::create_directories(out.parent_path(), ec);
    for (int attempt = 0; attempt < 100; ++attempt) {
        const int fd = ::open(lock_.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
        if (fd < 0) throw ExperimentError(lock_ + ": cannot open (" + std::strerror(errno) + ")");
        if (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
            const int err = errno;
            ::close(fd);
            if (err == EWOULDBLOCK)
                throw ExperimentError(output_ + ": another contactlab run is writing it now (" + lock_ +
                                      " is locked); wait for it to finish, or give another --output");
            throw ExperimentError(lock_ + ": cannot lock (" + std::strerror(err) + ")");
        }
        struct stat held {}, named {};
        if (::fstat(fd, &held) == 0 && ::stat(lock_.c_str(), &named) == 0 && held.st_dev == named.st_dev &&
            held.st_ino == named.st_ino) {
            lock_fd_ = fd;
            return;
        }
        ::close(fd);  // removed by the run that held it: open the name again
    }
    throw ExperimentError(lock_ + ": cannot lock (it keeps being replaced)");
}

void RunFiles::unlock() {
    if (lock_fd_ < 0) return;
    // Removed while still held (see lock()), then released.
    ::unlink(lock_.c_str());
    ::close(lock_fd_);
    lock_fd_ = -1;
}

void RunFiles::remove_temps() const {
    // A killed run may have died inside write_file_atomically: its temporaries are removed (the
    // target they were replacing is whole: the old version or the new one).
    std::error_code ec;
    const fs::path out(output_);
    const fs::path dir = out.has_parent_path() ? out.parent_path() : fs::path(".");
    const std::string name = out.filename().string(), meta = fs::path(meta_path(output_)).filename().string();
    for (const auto& e : fs::directory_iterator(dir, ec)) {
        const std::string n = e.path().filename().string();
        if (is_temp_of(n, name) || is_temp_of(n, meta)) fs::remove(e.path(), ec);
    }
    for (const std::string& d : {parts_, traces_})
        if (fs::is_directory(d))
            for (const auto& e : fs::directory_iterator(d, ec))
                if (is_temp(e.path().filename().string())) fs::remove(e.path(), ec);
}

std::vector<std::vector<std::string>> RunFiles::done_rows(const std::vector<std::string>& columns,
                                                          const std::string& participant) const {
    const bool from_part = fs::exists(part(participant));
    if (!from_part && !fs::exists(output_)) return {};
    const ResultsTable t = read_results_csv(from_part ? part(participant) : output_);
    if (t.columns != columns) throw ExperimentError(t.origin + ": not this protocol's results columns" + overwrite_hint());
    std::vector<std::vector<std::string>> rows;
    for (const auto& r : t.rows)
        if (r[0] == participant) rows.push_back(r);
    return rows;
}

void RunFiles::finish() {
    std::error_code ec;
    fs::remove_all(parts_, ec);
    unlock();
}

}  // namespace contactlab::experiments
