// record_writer.cpp — writer thread for simulation output and recordings.
#include "drivers/record_writer.hpp"

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <unistd.h>

namespace contactlab::drivers {

RecordWriter::RecordWriter(SpscRing<TickRecord>& ring, const std::string& output_path, const std::string& record_path)
    : ring_(ring) {
    open(out_, output_path, kSimulateHeader);
    try {
        open(rec_, record_path, kRecordingHeader);
    } catch (...) {
        if (out_.f) {  // the output may not be asked for (recording only): fclose(nullptr) crashes
            std::fclose(out_.f);
            ::unlink(out_.tmp.c_str());
        }
        throw;
    }
    thread_ = std::thread([this] { run(); });
}

RecordWriter::~RecordWriter() {
    if (!finished_) {
        stop_.store(true);
        if (thread_.joinable()) thread_.join();
        for (File* f : {&out_, &rec_})
            if (f->f) {
                std::fclose(f->f);
                ::unlink(f->tmp.c_str());
            }
    }
}

void RecordWriter::open(File& file, const std::string& path, const char* header) {
    if (path.empty()) return;
    file.path = path;
    file.tmp = path + ".tmp-XXXXXX";
    const int fd = ::mkstemp(file.tmp.data());
    if (fd < 0) throw std::runtime_error(path + ": cannot create (" + std::strerror(errno) + ")");
    file.f = ::fdopen(fd, "w");
    if (!file.f) {
        ::close(fd);
        ::unlink(file.tmp.c_str());
        throw std::runtime_error(path + ": cannot open for writing");
    }
    std::fprintf(file.f, "%s\n", header);
}

void RecordWriter::write(const TickRecord& r) {
    const int state = static_cast<int>(r.state);
    if (out_.f) {
        std::fprintf(out_.f,
                     "%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%d,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%d,",
                     r.t, r.finger.x, r.finger.y, r.phi, r.proxy.x, r.proxy.y, r.contact ? 1 : 0, r.depth, r.force.x,
                     r.force.y, r.l_d, r.roller_l, r.roller_target, r.period, r.roller_drive, state);
        const EnergyTerms& e = r.energy;
        std::fprintf(out_.f, "%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g\n", e.hold, e.field, e.turn,
                     e.edit, e.proxy, e.friction, e.damping, e.generated(), r.observer_energy, r.observer_margin);
    }
    if (rec_.f) {
        std::fprintf(rec_.f, "%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%d,%d\n", r.t, r.finger.x, r.finger.y,
                     r.phi, r.roller_l, r.force.x, r.force.y, r.roller_drive, state, static_cast<int>(r.fault));
    }
    ++summary_.rows;
    summary_.contact_rows += r.contact ? 1 : 0;
    summary_.fault_rows += r.state == ServoState::fault ? 1 : 0;
    summary_.max_force = std::max(summary_.max_force, std::hypot(r.force.x, r.force.y));
    if (r.contact && r.state == ServoState::engaged)
        summary_.max_roller_error = std::max(summary_.max_roller_error, std::abs(r.roller_target - r.roller_l));
}

void RecordWriter::run() {
    TickRecord r;
    for (;;) {
        bool any = false;
        while (ring_.try_pop(r)) {
            write(r);
            any = true;
        }
        if (!any) {
            if (stop_.load(std::memory_order_acquire) && ring_.empty()) return;
            std::this_thread::sleep_for(std::chrono::microseconds(500));
        }
    }
}

RecordSummary RecordWriter::finish() {
    stop_.store(true, std::memory_order_release);
    if (thread_.joinable()) thread_.join();
    finished_ = true;
    std::string error;
    for (File* f : {&out_, &rec_}) {
        if (!f->f) continue;
        const bool ok = std::fflush(f->f) == 0 && ::fsync(::fileno(f->f)) == 0 && !std::ferror(f->f);
        const bool closed = std::fclose(f->f) == 0;
        f->f = nullptr;
        if (!ok || !closed || ::rename(f->tmp.c_str(), f->path.c_str()) != 0) {
            ::unlink(f->tmp.c_str());
            if (error.empty()) error = f->path + ": write failed (" + std::strerror(errno) + ")";
        }
    }
    if (!error.empty()) throw std::runtime_error(error);
    return summary_;
}

}  // namespace contactlab::drivers
