// part_writer.hpp — a participant's part file (its checksums, then its rows: run_files.hpp)
// written on a thread of its own, so that a trial never waits for the disk.
//
// Each finished trial hands over the whole texts as they now stand; the writer replaces the
// checksums and then the part atomically (write_file_atomically: a temporary, fsync, rename),
// the same two files in the same order as when the trial's own thread wrote them. A hand-over
// that finds the previous one still waiting replaces it: both texts only grow, so the newer
// holds everything the older did. The part on disk is therefore always a whole, checked prefix
// of the participant's rows, at most the trials finished since the write in progress began
// behind the computation (a SIGKILL loses those; the resume performs them again, to the same
// bytes). Before RESULTS.csv takes the participant's rows, finish() waits for the last texts.
//
// Why: each write flushes to disk (two fsyncs a trial), which on a shared machine cost 10-30 %
// of a simulated participant's wall time, none of it CPU.
#pragma once

#include <condition_variable>
#include <mutex>
#include <string>
#include <thread>

namespace contactlab::experiments {

class PartWriter {
public:
    PartWriter(std::string sums_path, std::string part_path);
    ~PartWriter();  // waits for the writes in hand; an error is reported by commit() or finish() only
    PartWriter(const PartWriter&) = delete;
    PartWriter& operator=(const PartWriter&) = delete;

    // The participant's checksums and part as they now stand. Throws the error (FileWriteError's
    // message, as std::runtime_error) of an earlier write that failed.
    void commit(const std::string& sums, const std::string& part);
    // Returns once the last texts handed over are on disk; throws as commit().
    void finish();

private:
    void run();
    void rethrow_locked();

    const std::string sums_path_, part_path_;
    std::mutex lock_;
    std::condition_variable changed_;
    std::string sums_, part_;  // the texts waiting to be written
    bool waiting_ = false;     // sums_ and part_ hold texts not yet taken
    bool writing_ = false;     // the writer is writing texts it took
    bool stop_ = false;
    std::string error_;        // the first failed write's message
    std::thread thread_;
};

}  // namespace contactlab::experiments
