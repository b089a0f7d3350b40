// record_writer.hpp — the writer thread: drains TickRecords from the servo's SPSC ring and writes
//
//  * the simulation output (`contactlab simulate --output`): the `contactlab trace` columns
//      t,x,y,phi,proxy_x,proxy_y,contact,depth,fx,fy,l_d
//    then roller_l,roller_target,period,roller_drive,state
//    (fx,fy: the force commanded to the device after safety; state: 0 idle, 1 arming, 2 ramping,
//    3 engaged, 4 fault), then the tick's energy balance (J, haptics/energy_balance.hpp)
//      e_hold,e_field,e_turn,e_edit,e_proxy,e_friction,e_damping,e_generated,observer_energy,observer_margin;
//  * the recording (`--record`), format "contactlab recording v1": CSV with the header
//      t,x,y,phi,roller_l,fx,fy,roller_drive,state,fault
//    one row per tick: the device reading (t s, x y m, phi rad, roller_l m) and the command sent
//    (fx fy N, roller_drive V), state as above, fault as ServoFault's number. ReplayDevice plays
//    it back.
// Numbers are printed with 17 significant digits (they read back to the same doubles). Files
// are written to a temporary name beside the target and renamed into place by finish().
#pragma once

#include "drivers/tick_record.hpp"
#include "haptics/spsc_ring.hpp"

#include <atomic>
#include <cstdio>
#include <string>
#include <thread>

namespace contactlab::drivers {

inline constexpr const char* kSimulateHeader =
    "t,x,y,phi,proxy_x,proxy_y,contact,depth,fx,fy,l_d,roller_l,roller_target,period,roller_drive,state,"
    "e_hold,e_field,e_turn,e_edit,e_proxy,e_friction,e_damping,e_generated,observer_energy,observer_margin";
inline constexpr const char* kRecordingHeader = "t,x,y,phi,roller_l,fx,fy,roller_drive,state,fault";

struct RecordSummary {
    std::uint64_t rows = 0;
    std::uint64_t contact_rows = 0;
    double max_force = 0.0;          // N
    double max_roller_error = 0.0;   // m, |roller_target - roller_l| while engaged and in contact
    std::uint64_t fault_rows = 0;
};

class RecordWriter {
public:
    // Either path may be empty (not written). Throws std::runtime_error if a file cannot be
    // created.
    RecordWriter(SpscRing<TickRecord>& ring, const std::string& output_path, const std::string& record_path);
    ~RecordWriter();
    RecordWriter(const RecordWriter&) = delete;
    RecordWriter& operator=(const RecordWriter&) = delete;

    // Drains what is left, stops the thread, flushes and renames the files into place.
    RecordSummary finish();

private:
    struct File {
        std::string path, tmp;
        std::FILE* f = nullptr;
    };
    void open(File& file, const std::string& path, const char* header);
    void run();
    void write(const TickRecord& r);

    SpscRing<TickRecord>& ring_;
    File out_, rec_;
    RecordSummary summary_;
    std::atomic<bool> stop_{false};
    std::thread thread_;
    bool finished_ = false;
};

}  // namespace contactlab::drivers
