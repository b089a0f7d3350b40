// part_writer.cpp — a participant's part written off the trials' thread (part_writer.hpp).
#include "engine/experiments/runs/part_writer.hpp"

#include "haptics/atomic_file.hpp"

#include <stdexcept>
#include <utility>

namespace contactlab::experiments {

PartWriter::PartWriter(std::string sums_path, std::string part_path)
    : sums_path_(std::move(sums_path)), part_path_(std::move(part_path)), thread_([this] { run(); }) {}

PartWriter::~PartWriter() {
    {
        std::lock_guard<std::mutex> g(lock_);
        stop_ = true;
    }
    changed_.notify_all();
    thread_.join();
}

void PartWriter::rethrow_locked() {
    if (!error_.empty()) throw std::runtime_error(error_);
}

void PartWriter::commit(const std::string& sums, const std::string& part) {
    {
        std::lock_guard<std::mutex> g(lock_);
        rethrow_locked();
        sums_ = sums;
        part_ = part;
        waiting_ = true;
    }
    changed_.notify_all();
}

void PartWriter::finish() {
    std::unique_lock<std::mutex> g(lock_);
    changed_.wait(g, [&] { return (!waiting_ && !writing_) || !error_.empty(); });
    rethrow_locked();
}

void PartWriter::run() {
    std::string sums, part;
    std::unique_lock<std::mutex> g(lock_);
    for (;;) {
        changed_.wait(g, [&] { return waiting_ || stop_; });
        if (!waiting_) return;  // stopped with nothing in hand
        sums.swap(sums_);
        part.swap(part_);
        waiting_ = false;
        writing_ = true;
        g.unlock();
        std::string failed;
        try {
            write_file_atomically(sums_path_, sums);  // the checksums first: a row on disk has its own
            write_file_atomically(part_path_, part);
        } catch (const std::exception& e) {
            failed = e.what();
        }
        g.lock();
        writing_ = false;
        if (!failed.empty() && error_.empty()) error_ = failed;
        changed_.notify_all();
        if (!error_.empty()) {
            waiting_ = false;  // nothing more is written after a failure
            if (stop_) return;
        }
    }
}

}  // namespace contactlab::experiments
