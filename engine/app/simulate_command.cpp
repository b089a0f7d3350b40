// simulate_command.cpp — wiring for `contactlab simulate` (see simulate_command.hpp).
#include "engine/app/simulate_command.hpp"
#include "engine/app/simulate_wearable.hpp"
#include "engine/app/subcommands.hpp"
#include "haptics/parameter_limits.hpp"

#include "drivers/hand_path.hpp"
#include "engine/app/start_inside_warning.hpp"
#include "engine/app/task_scene_check.hpp"
#include "drivers/record_writer.hpp"
#include "drivers/replay_device.hpp"
#include "drivers/servo_loop.hpp"
#include "drivers/sim/roller_sine.hpp"
#include "drivers/sim/sim_cld_device.hpp"
#include "drivers/sim/sim_wearable_device.hpp"
#include "drivers/tasks.hpp"
#include "drivers/usb/device_file.hpp"
#include "drivers/usb/falcon_device.hpp"
#include "drivers/usb/hapio_device.hpp"
#include "drivers/usb/haply_device.hpp"
#include "haptics/scene_io.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <memory>

namespace contactlab::app {

using namespace contactlab::drivers;

namespace {

// s: a stall is a gap of more than a few periods (DESIGN.md), and never less than the 5 ms the
// servo and the simulated amplifiers use at 1 kHz and above.
double watchdog_timeout_for(double rate) { return std::max(0.005, 3.0 / rate); }
bool is_usb(const std::string& device) { return device.rfind("usb:", 0) == 0; }

std::unique_ptr<Device> make_device(const SimulateOptions& o, const Scene& scene, double& path_duration) {
    if (is_usb(o.device)) {
        // A real device: the user's hand moves it, so there is no path, and time is real.
        if (!o.hand.empty() || !o.task.empty()) throw BadInput("--device " + o.device + " takes no --hand or --task");
        if (o.duration < 0.0) throw BadInput("--device " + o.device + " needs --duration (s)");
        double mass = 0.0;  // kg, from the user's device file
        if (!o.device_file.empty()) {
            try {
                mass = read_device_file(o.device_file).effective_mass;
            } catch (const DeviceFileError& e) {
                throw BadInput(std::string("--device-file ") + e.what());
            }
        }
        if (o.device == "usb:hapio") {
            hapio::HapioOptions ho;
            ho.mass = mass;
            return std::make_unique<hapio::HapioDevice>(ho);
        }
        if (o.device == "usb:falcon") {
            falcon::FalconOptions fo;
            fo.firmware = o.firmware;
            fo.mass = mass;
            return std::make_unique<falcon::FalconDevice>(fo);
        }
        if (o.device == "usb:haply") {
            if (o.haply_hardware != 2 && o.haply_hardware != 3)
                throw BadInput("--haply-hardware must be 2 or 3 (the 2DIY's board generation), got " +
                               std::to_string(o.haply_hardware));
            haply::HaplyOptions ho;
            ho.generation = o.haply_hardware;
            ho.port = o.haply_port;
            ho.mass = mass;
            return std::make_unique<haply::HaplyDevice>(ho);
        }
        throw BadInput("--device: unknown USB device \"" + o.device + "\" (usb:hapio, usb:falcon, usb:haply; see contactlab devices)");
    }
    if (!o.device_file.empty()) throw BadInput("--device-file: only real devices (usb:...) take a device file");
    if (o.device.rfind("replay:", 0) == 0) {
        if (!o.hand.empty() || !o.task.empty()) throw BadInput("--device replay:FILE takes no --hand or --task");
        const std::string file = o.device.substr(7);
        std::vector<RecordedSample> samples;
        try {
            samples = read_recording_file(file);
        } catch (const RecordingError& e) {
            throw BadInput(e.what());
        }
        auto dev = std::make_unique<ReplayDevice>(std::move(samples));
        path_duration = static_cast<double>(dev->size()) / o.rate;
        return dev;
    }
    if (o.device == "sim-wearable") {
        // Seed 003's platform under a finger that follows --hand (the wearable pushes no hand).
        if (o.hand.empty() || !o.task.empty())
            throw BadInput("--device sim-wearable takes --hand HAND.csv, or one of its tasks (--task wearable-step, "
                           "wearable-bandwidth, curvature-arc)");
        HandPath path;
        try {
            path = read_hand_path_file(o.hand);
        } catch (const HandPathError& e) {
            throw BadInput(e.what());
        }
        path_duration = path.end() - path.start();
        sim::SimWearableParams wp;
        wp.watchdog_timeout = std::max(wp.watchdog_timeout, 3.0 / o.rate);
        return std::make_unique<sim::SimWearableDevice>(wp, std::move(path));
    }
    if (o.device != "sim-cld") throw BadInput("--device: unknown device \"" + o.device + "\" (sim-cld, sim-wearable, replay:FILE, usb:hapio, usb:falcon, usb:haply)");
    if (o.hand.empty() == o.task.empty()) throw BadInput("sim-cld needs exactly one of --hand HAND.csv or --task contour-block");
    HandPath path;
    if (!o.task.empty()) {
        if (o.task != "contour-block")
            throw BadInput("--task: unknown task \"" + o.task + "\" (contour-block, roller-bandwidth, wearable-step, "
                           "wearable-bandwidth, curvature-arc)");
        if (!(o.task_speed > 0.0 && o.task_speed <= 1.0)) throw BadInput("--task-speed: must be in (0, 1] m/s");
        BlockTaskParams bp;
        bp.finger_radius = scene.finger.radius;
        bp.speed = o.task_speed;
        check_block_task_scene(scene, bp);
        path = contour_block_task(bp);
    } else {
        try {
            path = read_hand_path_file(o.hand);
        } catch (const HandPathError& e) {
            throw BadInput(e.what());
        }
    }
    path_duration = path.end() - path.start();
    const PathPoint first = path.at(path.start());
    const std::string warning = start_inside_warning("simulate", scene, path.start(), first.x, first.phi);
    if (!warning.empty()) std::fprintf(stderr, "%s\n", warning.c_str());
    sim::SimCldParams sp;
    // The amplifiers' watchdog must outlast a period: at 100 Hz a tick comes every 10 ms.
    sp.watchdog_timeout = watchdog_timeout_for(o.rate);
    return std::make_unique<sim::SimCldDevice>(sp, std::move(path));
}

// Why "passivity": "control" cannot run on this device: it declares no effective mass, so the
// controller could add no damping and the loop would fault as with "fault" (never silently).
std::string passivity_refusal(const Device& dev, const SimulateOptions& o) {
    std::string why = std::string("the scene asks for \"passivity\": \"control\", but device ") + dev.name() +
                      " declares no effective mass, so the passivity controller cannot add damping (the loop would "
                      "fault as with \"fault\"). ";
    if (const auto* h = dynamic_cast<const hapio::HapioDevice*>(&dev); h != nullptr && h->info().version < hapio::kInfoVersion2)
        why += "This hapio board speaks info version 1, which carries no mass: ";
    if (is_usb(o.device))
        why += "give the mass you measured in a device file (--device-file FILE with {\"effective_mass_kg\": M}, "
               "docs/devices.md)";
    else
        why += "this simulated device has no mass model; use sim-cld";
    return why + ", or set \"passivity\": \"fault\"";
}

// Seed 002 constrains the roller's range "in software": the servo's travel limits shrink to
// `travel` (m, total) centred on the pad; the mechanism's hard stops stay where they are.
RollerTravel software_roller_travel(const Device& dev, const ServoConfig& config, double travel) {
    if (!config.has_roller) throw BadInput(std::string("--roller-travel: device ") + dev.name() + " has no roller");
    const double full = config.roller_travel.max - config.roller_travel.min;  // m
    if (!std::isfinite(travel) || !(travel > 0.0) || travel > full + 1e-12) {
        char buf[160];
        std::snprintf(buf, sizeof buf, "--roller-travel: must be a length in (0, %g] m (the device's travel), got %.17g",
                      full, travel);
        throw BadInput(buf);
    }
    const double mid = 0.5 * (config.roller_travel.max + config.roller_travel.min);  // m
    return RollerTravel{mid - 0.5 * travel, mid + 0.5 * travel};
}

// --task roller-bandwidth: the sim-cld roller alone under the servo's roller PID at --rate, fed
// 1.0 cm peak-to-peak sines (seed 000 §4.3) in virtual time; writes the sweep, prints the -3 dB
// frequency. The scene is read (and must be valid) but not used.
int run_roller_bandwidth(const SimulateOptions& o) {
    if (o.device != "sim-cld") throw BadInput("--task roller-bandwidth runs the sim-cld roller (--device sim-cld)");
    if (!o.hand.empty()) throw BadInput("--task roller-bandwidth takes no --hand");
    if (o.realtime) throw BadInput("--task roller-bandwidth runs in virtual time only");
    if (!o.record.empty()) throw BadInput("--task roller-bandwidth records nothing (no --record)");
    load_scene_file(o.scene_path);
    const sim::SimCldParams sp;
    sim::SineTest st;
    st.rate = o.rate;
    st.substep = sp.substep;
    st.min_substeps = sp.min_substeps;
    if (o.roller_travel_set) {
        if (!std::isfinite(o.roller_travel) || !(o.roller_travel > 2.0 * st.amplitude) ||
            o.roller_travel > sp.roller.travel + 1e-12) {
            char buf[160];
            std::snprintf(buf, sizeof buf, "--roller-travel: must be in (%g, %g] m for the 1 cm sine, got %.17g",
                          2.0 * st.amplitude, sp.roller.travel, o.roller_travel);
            throw BadInput(buf);
        }
        st.travel = o.roller_travel;
    }
    const sim::BandwidthResult bw = sim::roller_bandwidth(sp.roller, RollerGains{}, st);
    std::ofstream out(o.output);
    if (!out) throw BadInput("cannot write " + o.output);
    out << "freq,gain,phase_deg,element_gain,max_error\n";  // Hz, m/m, deg, m/m, m
    char line[256];
    for (const sim::SineResponse& r : bw.sweep) {
        std::snprintf(line, sizeof line, "%.6f,%.6f,%.3f,%.6f,%.9f\n", r.freq, r.gain, r.phase * 57.29577951308232,
                      r.element_gain, r.max_error);
        out << line;
    }
    out.close();
    if (!out) throw BadInput("cannot write " + o.output);
    if (bw.found) {
        std::fprintf(stderr, "simulate: roller 1.0 cm peak-to-peak sine bandwidth (-3 dB) %.2f Hz at %.0f Hz servo rate "
                     "(seed 000: about 8 Hz)\n", bw.bandwidth, o.rate);
    } else {
        std::fprintf(stderr, "simulate: roller gain stayed above -3 dB up to %.0f Hz\n", bw.sweep.back().freq);
    }
    std::fprintf(stderr, "simulate: sweep (%zu frequencies) written to %s\n", bw.sweep.size(), o.output.c_str());
    return 0;
}

}  // namespace

int run_simulate(const SimulateOptions& o) {
    if (!(o.rate >= limits::kMinServoRate && o.rate <= limits::kMaxRealtimeServoRate))
        throw BadInput("--rate: must be between 100 and 20000 Hz");  // haptics/parameter_limits.hpp
    if (o.output.empty()) throw BadInput("--output is required");
    if (o.task == "roller-bandwidth") return run_roller_bandwidth(o);
    if (is_wearable_task(o.task)) return run_wearable_task(o);
    Scene scene = load_scene_file(o.scene_path);
    apply_overrides(scene, o.overrides);

    double path_duration = 0.0;
    std::unique_ptr<Device> dev = make_device(o, scene, path_duration);
    const double duration = o.duration >= 0.0 ? o.duration : path_duration;
    if (!std::isfinite(duration) || duration > 3600.0) throw BadInput("--duration: must be at most 3600 s");
    const double period = 1.0 / o.rate;
    const auto ticks = static_cast<std::uint64_t>(std::llround(duration / period));

    ServoParams params;
    params.stiffness = scene.force.stiffness;
    params.max_force = scene.force.max_force;
    params.passivity = scene.force.passivity;
    params.safety.watchdog_timeout = watchdog_timeout_for(o.rate);
    // Opened before the tick is built: what the device declares (a hapio board's effective mass is
    // in its info frame) decides whether the scene's options can be honoured at all.
    if (!dev->open()) {
        std::fprintf(stderr, "simulate: device %s failed to open: %s\n", dev->name(), dev->fault().detail);
        return 1;
    }
    ServoConfig config = servo_config_for(*dev, o.rate);
    if (scene.force.passivity == PassivityMode::control && !(config.max_damping > 0.0)) {
        dev->close();
        throw BadInput(passivity_refusal(*dev, o));
    }
    if (o.roller_travel_set) config.roller_travel = software_roller_travel(*dev, config, o.roller_travel);
    ServoTick tick(config, params);
    tick.scenes().publish(std::make_unique<ServoScene>(scene));

    SpscRing<TickRecord> ring(1u << 16);
    RecordWriter writer(ring, o.output, o.record);
    ServoLoop loop(*dev, tick, period, &ring);
    loop.start_opened();
    // A real device cannot run in virtual time.
    const bool realtime = o.realtime || is_usb(o.device);
    RealtimeReport rt;
    if (realtime) {
        rt = run_realtime(loop, ticks);
    } else {
        loop.run_virtual(ticks);
    }
    const RecordSummary sum = writer.finish();
    const ServoSnapshot snap = tick.snapshot();

    std::fprintf(stderr, "simulate: %s, %s time, %.0f Hz, %llu ticks (%.3f s), %llu in contact, max |F| %.3f N\n",
                 dev->name(), realtime ? "real" : "virtual", o.rate, static_cast<unsigned long long>(sum.rows),
                 duration, static_cast<unsigned long long>(sum.contact_rows), sum.max_force);
    std::fprintf(stderr, "simulate: roller |target - measured| max %.4f mm while engaged in contact; state %s, %u fault(s)%s%s\n",
                 sum.max_roller_error * 1e3, to_string(snap.state), snap.fault_count,
                 snap.fault_count ? ", last: " : "", snap.fault_count ? to_string(tick.snapshot().fault) : "");
    if (o.roller_travel_set) {
        std::fprintf(stderr, "simulate: roller travel limited to %.1f mm (%+.1f..%+.1f mm)\n", o.roller_travel * 1e3,
                     config.roller_travel.min * 1e3, config.roller_travel.max * 1e3);
    }
    if (dev->state() == DeviceState::fault) {
        std::fprintf(stderr, "simulate: device %s ended in fault (%s): %s\n", dev->name(), to_string(dev->fault().code),
                     dev->fault().detail);
    }
    if (const auto* h = dynamic_cast<const hapio::HapioDevice*>(dev.get())) {
        const hapio::HapioStats st = h->stats();
        std::fprintf(stderr, "simulate: %s: %llu frames, %llu commands, %llu rejected, %llu lost, %llu timeouts, "
                     "%llu stalls, %llu unplugs, %llu replugs; round trip mean %.3f ms, max %.3f ms\n",
                     dev->name(), static_cast<unsigned long long>(st.frames), static_cast<unsigned long long>(st.commands),
                     static_cast<unsigned long long>(st.rejected()), static_cast<unsigned long long>(st.sequence_gaps),
                     static_cast<unsigned long long>(st.timeouts), static_cast<unsigned long long>(st.stalls),
                     static_cast<unsigned long long>(st.disconnects), static_cast<unsigned long long>(st.reconnects),
                     st.rtt_mean * 1e3, st.rtt_max * 1e3);
    }
    if (const auto* w = dynamic_cast<const sim::SimWearableDevice*>(dev.get()); w != nullptr && w->rig() != nullptr) {
        const wearable::WearableRig& rig = *w->rig();
        const wearable::Pose& xi = rig.plant().pose();
        const wearable::Pose& rest = rig.def().plant.platform.rest;
        std::fprintf(stderr, "simulate: sim-wearable at the end: platform %.3f mm into the pad, roll %.4f rad, pitch %.4f rad; "
                     "cable tensions %.3f %.3f %.3f N\n", (xi(2) - rest(2)) * 1e3, xi(3), xi(4), rig.plant().tension()(0),
                     rig.plant().tension()(1), rig.plant().tension()(2));
    }
    if (const auto* f = dynamic_cast<const falcon::FalconDevice*>(dev.get())) {
        const falcon::FalconStats st = f->stats();
        std::fprintf(stderr, "simulate: %s: %llu packets, %llu commands, %llu malformed, %llu timeouts, %llu unplugs, "
                     "%llu replugs, %llu firmware uploads\n",
                     dev->name(), static_cast<unsigned long long>(st.packets), static_cast<unsigned long long>(st.commands),
                     static_cast<unsigned long long>(st.malformed), static_cast<unsigned long long>(st.timeouts),
                     static_cast<unsigned long long>(st.disconnects), static_cast<unsigned long long>(st.reconnects),
                     static_cast<unsigned long long>(st.firmware_uploads));
    }
    if (const auto* hp = dynamic_cast<const haply::HaplyDevice*>(dev.get())) {
        const haply::HaplyStats st = hp->stats();
        std::fprintf(stderr, "simulate: %s (2DIY generation %d on %s): %llu exchanges, %llu replies, %llu rejected "
                     "(%llu short, %llu wrong device id, %llu not finite), %llu timeouts, %llu unplugs, %llu replugs\n",
                     dev->name(), hp->hardware().generation, hp->port().c_str(), static_cast<unsigned long long>(st.exchanges),
                     static_cast<unsigned long long>(st.replies), static_cast<unsigned long long>(st.rejected()),
                     static_cast<unsigned long long>(st.short_frames), static_cast<unsigned long long>(st.wrong_device),
                     static_cast<unsigned long long>(st.not_finite), static_cast<unsigned long long>(st.timeouts),
                     static_cast<unsigned long long>(st.disconnects), static_cast<unsigned long long>(st.reconnects));
    }
    if (realtime) {
        std::fprintf(stderr, "simulate: %s; %s\n", rt.scheduling.c_str(), rt.memory_lock.c_str());
        std::fprintf(stderr, "simulate: period p50 %.2f us, p99 %.2f us, max %.2f us, mean %.3f us, %llu overruns, %llu records dropped\n",
                     rt.p50 * 1e6, rt.p99 * 1e6, rt.max * 1e6, rt.mean * 1e6,
                     static_cast<unsigned long long>(rt.overruns),
                     static_cast<unsigned long long>(loop.dropped_records()));
    }
    std::fprintf(stderr, "simulate: written to %s%s%s\n", o.output.c_str(), o.record.empty() ? "" : " and ",
                 o.record.c_str());
    return 0;
}

}  // namespace contactlab::app
