// simulate_command.hpp — `contactlab simulate`: the servo loop against a device (simulated CLD rig
// held by a scripted hand, or a replayed recording), in virtual or real time.
#pragma once

#include "engine/app/scene_overrides.hpp"
#include "engine/app/trace_command.hpp"

#include <limits>
#include <string>

namespace contactlab::app {

struct SimulateOptions {
    std::string scene_path;
    std::string device = "sim-cld";   // "sim-cld", "replay:FILE", "usb:hapio", "usb:falcon" or "usb:haply"
    std::string firmware;             // usb:falcon: firmware file to upload (never shipped)
    int haply_hardware = 3;           // usb:haply: the 2DIY's board generation, 2 or 3
    std::string haply_port;           // usb:haply: its tty ("" finds it by USB id)
    std::string device_file;          // usb:*: what the user declares (effective mass), JSON
    std::string hand;                 // HAND.csv (t,x,y,phi), or empty with task
    std::string task;                 // "contour-block", "roller-bandwidth", or seed 003's "wearable-step",
                                      // "wearable-bandwidth", "curvature-arc" (--device sim-wearable)
    double task_speed = 0.05;         // m/s, hand speed on the built-in task
    double rate = 1000.0;             // Hz, 100..20000
    double duration = -1.0;           // s; < 0: the path's (or recording's) length
    // m, total roller travel the servo may use, centred on the pad (seed 002: 18 mm "constrained in
    // software"); NaN: the device's full travel (sim-cld: 20 mm, seed 000).
    double roller_travel = std::numeric_limits<double>::quiet_NaN();
    bool roller_travel_set = false;
    bool realtime = false;
    std::string output;               // OUT.csv
    std::string record;               // recording file, optional
    std::string json;                 // wearable tasks: summary JSON, optional
    std::string wearable_fit = "seed";  // wearable tasks: "seed" (45 ms reference shaping) or "none"
    double fsr_noise = 0.003;         // N, wearable tasks: FSR noise standard deviation
    SceneOverrides overrides;
};

// Runs it; prints a summary to stderr. Throws BadInput for bad options.
int run_simulate(const SimulateOptions& o);

}  // namespace contactlab::app
