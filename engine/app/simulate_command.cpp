// simulate_command.cpp — wiring for `contactlab simulate` (see simulate_command.hpp).
#include "engine/app/simulate_command.hpp"
#include "engine/app/subcommands.hpp"

#include "drivers/hand_path.hpp"
#include "drivers/record_writer.hpp"
#include "drivers/replay_device.hpp"
#include "drivers/servo_loop.hpp"
#include "drivers/sim/sim_cld_device.hpp"
#include "drivers/tasks.hpp"
#include "drivers/usb/falcon_device.hpp"
#include "drivers/usb/hapio_device.hpp"
#include "haptics/scene_io.hpp"

#include <cmath>
#include <cstdio>
#include <memory>

namespace contactlab::app {

using namespace contactlab::drivers;

namespace {

bool is_usb(const std::string& device) { return device.rfind("usb:", 0) == 0; }

std::unique_ptr<Device> make_device(const SimulateOptions& o, const Scene& scene, double& path_duration) {
    if (is_usb(o.device)) {
        // A real device: the user's hand moves it, so there is no path, and time is real.
        if (!o.hand.empty() || !o.task.empty()) throw BadInput("--device " + o.device + " takes no --hand or --task");
        if (o.duration < 0.0) throw BadInput("--device " + o.device + " needs --duration (s)");
        if (o.device == "usb:hapio") return std::make_unique<hapio::HapioDevice>();
        if (o.device == "usb:falcon") {
            falcon::FalconOptions fo;
            fo.firmware = o.firmware;
            return std::make_unique<falcon::FalconDevice>(fo);
        }
        throw BadInput("--device: unknown USB device \"" + o.device + "\" (usb:hapio, usb:falcon; see contactlab devices)");
    }
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
    if (o.device != "sim-cld") throw BadInput("--device: unknown device \"" + o.device + "\" (sim-cld, replay:FILE, usb:hapio, usb:falcon)");
    if (o.hand.empty() == o.task.empty()) throw BadInput("sim-cld needs exactly one of --hand HAND.csv or --task contour-block");
    HandPath path;
    if (!o.task.empty()) {
        if (o.task != "contour-block") throw BadInput("--task: unknown task \"" + o.task + "\" (contour-block)");
        if (!(o.task_speed > 0.0 && o.task_speed <= 1.0)) throw BadInput("--task-speed: must be in (0, 1] m/s");
        BlockTaskParams bp;
        bp.finger_radius = scene.finger.radius;
        bp.speed = o.task_speed;
        path = contour_block_task(bp);
    } else {
        try {
            path = read_hand_path_file(o.hand);
        } catch (const HandPathError& e) {
            throw BadInput(e.what());
        }
    }
    path_duration = path.end() - path.start();
    sim::SimCldParams sp;
    return std::make_unique<sim::SimCldDevice>(sp, std::move(path));
}

}  // namespace

int run_simulate(const SimulateOptions& o) {
    if (!(o.rate >= 100.0 && o.rate <= 20000.0)) throw BadInput("--rate: must be between 100 and 20000 Hz");
    if (o.output.empty()) throw BadInput("--output is required");
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
    ServoTick tick(servo_config_for(*dev, o.rate), params);
    tick.scenes().publish(std::make_unique<ServoScene>(scene));

    SpscRing<TickRecord> ring(1u << 16);
    RecordWriter writer(ring, o.output, o.record);
    ServoLoop loop(*dev, tick, period, &ring);
    if (!loop.start()) {
        writer.finish();
        std::fprintf(stderr, "simulate: device %s failed to open: %s\n", dev->name(), dev->fault().detail);
        return 1;
    }
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
    if (const auto* f = dynamic_cast<const falcon::FalconDevice*>(dev.get())) {
        const falcon::FalconStats st = f->stats();
        std::fprintf(stderr, "simulate: %s: %llu packets, %llu commands, %llu malformed, %llu timeouts, %llu unplugs, "
                     "%llu replugs, %llu firmware uploads\n",
                     dev->name(), static_cast<unsigned long long>(st.packets), static_cast<unsigned long long>(st.commands),
                     static_cast<unsigned long long>(st.malformed), static_cast<unsigned long long>(st.timeouts),
                     static_cast<unsigned long long>(st.disconnects), static_cast<unsigned long long>(st.reconnects),
                     static_cast<unsigned long long>(st.firmware_uploads));
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
