// haptics_host.cpp — device switching, servo rate and recording for the editor (see the header).
#include "engine/editor/haptics_host.hpp"

#include "drivers/replay_device.hpp"
#include "drivers/usb/falcon_device.hpp"
#include "drivers/usb/hapio_device.hpp"
#include "drivers/usb/haply_device.hpp"
#include "engine/editor/keyed_angle_device.hpp"
#include "drivers/servo_loop.hpp"
#include "drivers/usb/usb_devices.hpp"
#include "engine/editor/cursor_cld_device.hpp"
#include "engine/editor/cursor_wearable_device.hpp"
#include "engine/editor/platform_finger_device.hpp"
#include "engine/editor/mouse_device.hpp"
#include "engine/editor/servo_view.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace contactlab::editor {
namespace {

constexpr std::size_t kRecordRing = 1u << 16;  // ticks between the UI's forward and the writer

bool is_usb(const std::string& spec) { return spec.rfind("usb:", 0) == 0; }

}  // namespace

HapticsHost::~HapticsHost() {
    if (writer_) stop_recording();
    stop();
}

double HapticsHost::watchdog_timeout() const {
    return is_usb(spec_) ? std::max(0.005, 3.0 / rate_) : kMouseWatchdog;
}

std::unique_ptr<drivers::Device> HapticsHost::make_device(const std::string& spec, const MousePose& pose,
                                                          std::string& error) {
    if (spec == "mouse") return std::make_unique<MouseDevice>();
    if (spec == "sim-cld") return std::make_unique<CursorCldDevice>(CursorCldParams{}, pose);
    if (spec == "sim-wearable") return std::make_unique<CursorWearableDevice>(pose);
    if (spec.rfind("replay:", 0) == 0) {
        const std::string file = spec.substr(7);
        if (file.empty()) {
            error = "device replay: name the recording (replay:FILE)";
            return nullptr;
        }
        try {
            return std::make_unique<drivers::ReplayDevice>(drivers::read_recording_file(file));
        } catch (const std::exception& e) {  // RecordingError names file:line
            error = std::string("device replay: ") + e.what();
            return nullptr;
        }
    }
    // A model 2 board (the wearable platform) tracks no finger: the cursor, or seed 003's live
    // sweep, supplies it (platform_finger_device.hpp).
    if (spec == "usb:hapio") return std::make_unique<PlatformFingerDevice>(std::make_unique<drivers::hapio::HapioDevice>(), pose);
    // The Falcon and the 2DIY measure no finger angle: phi is the editor's (its keys and wheel).
    if (spec == "usb:falcon") return std::make_unique<KeyedAngleDevice>(std::make_unique<drivers::falcon::FalconDevice>(), pose);
    if (spec == "usb:haply") return std::make_unique<KeyedAngleDevice>(std::make_unique<drivers::haply::HaplyDevice>(), pose);
    error = "unknown device \"" + spec + "\" (mouse, sim-cld, sim-wearable, replay:FILE, usb:hapio, usb:falcon, usb:haply)";
    return nullptr;
}

std::string HapticsHost::start(const std::string& spec, double rate, const Scene& scene, const ServoParams& params,
                               const MousePose& pose, bool stopped) {
    if (!(rate >= kMinRate && rate <= kMaxRate)) {
        char buf[96];
        std::snprintf(buf, sizeof buf, "servo rate %g Hz: must be between %g and %g Hz", rate, kMinRate, kMaxRate);
        return buf;  // nothing was stopped: a bad request changes nothing
    }
    // The same device at another rate keeps its object: a simulated arm does not jump back under
    // the cursor because its servo was retimed (a real one could not either).
    const bool same = device_ && spec == spec_;
    std::string error;
    std::unique_ptr<drivers::Device> next = same ? nullptr : make_device(spec, pose, error);
    if (!same && !next) return error;  // likewise: the running device carries on
    // "passivity": "control" needs the device's effective mass: a real device is opened first to
    // read what it declares (a hapio board says it in its info frame) and refused here, before
    // any servo starts on it, when it declares none: never run as "fault" without saying so.
    if (next && is_usb(spec) && params.passivity == PassivityMode::control && next->open() &&
        !(drivers::servo_config_for(*next, rate).max_damping > 0.0)) {
        next->close();
        const bool running = servo_ != nullptr;
        if (!running) start("mouse", rate, scene, params, pose, stopped);  // as when a device does not open
        return "device " + spec + " declares no effective mass, so the scene's \"passivity\": \"control\" cannot run on it "
               "(give the mass in a device file with `contactlab simulate --device-file`, docs/devices.md, or use "
               "\"passivity\": \"fault\"); " + (running ? "the running device carries on" : "the mouse drives the finger");
    }

    // The proxy's history goes over to the new servo (issue 15): a finger resting in a wall keeps
    // feeling it across a rate change or a device switch; the new servo's first tick walks from
    // there to wherever the (new) device puts the finger, so a hand that jumped meets the surface
    // from the side it was on.
    bool have_history = false;
    Vec2 last_proxy{0.0};
    double last_phi = 0.0;
    if (servo_) {
        const ServoSnapshot snap = servo_->snapshot();
        have_history = snap.ticks > 0 && is_finite(snap.proxy) && std::isfinite(snap.phi);
        last_proxy = snap.proxy;
        last_phi = snap.phi;
    }

    // The safety path: the old servo's last tick commands zero force; then its device closes.
    if (writer_) stop_recording();
    if (same) {
        servo_->stop();
        servo_.reset();
        next = std::move(device_);
    }
    stop();

    ++generation_;
    const auto launch = [&](std::unique_ptr<drivers::Device> dev, const std::string& sp) {
        ServoParams p = params;
        spec_ = sp;
        rate_ = rate;
        p.safety.watchdog_timeout = watchdog_timeout();
        device_ = std::move(dev);
        pose_input_ = dynamic_cast<PoseInput*>(device_.get());
        if (pose_input_) pose_input_->set_pose(pose);
        servo_ = std::make_unique<LiveServo>(*device_, rate, p);
        if (have_history) servo_->seed_proxy(last_proxy, last_phi);
        servo_->publish_scene(scene);
        if (stopped) servo_->engage_stop();
        return servo_->start(core_);
    };
    if (launch(std::move(next), spec)) return {};
    const drivers::DeviceFault f = device_->fault();
    error = "device " + spec + " did not open (" + drivers::to_string(f.code) + ": " + f.detail + "); the mouse drives the finger";
    servo_.reset();
    launch(std::make_unique<MouseDevice>(), "mouse");
    return error;
}

void HapticsHost::stop() {
    if (servo_) servo_->stop();
    servo_.reset();
    pose_input_ = nullptr;
    device_.reset();
}

const std::vector<DeviceOption>& HapticsHost::options(bool rescan) {
    if (scanned_ && !rescan) return options_;
    scanned_ = true;
    options_.clear();
    options_.push_back({"mouse", "mouse (the cursor is the finger)", true, {}});
    options_.push_back({"sim-cld", "sim-cld (simulated CLD, the hand follows the cursor)", true, {}});
    options_.push_back({"sim-wearable", "sim-wearable (seed 003's platform, the cursor is the finger)", true, {}});
    options_.push_back({"replay:", "replay of a recording", true, {}});
    drivers::usb::UsbContext ctx;
    const drivers::usb::UsbScan scan = drivers::usb::scan_usb_devices(ctx);
    for (const drivers::usb::KnownModel& m : drivers::usb::known_models()) {
        if (std::any_of(options_.begin(), options_.end(), [&](const DeviceOption& o) { return o.spec == m.device; }))
            continue;  // one entry per driver (several boards may share one)
        DeviceOption o{m.device, std::string(m.device) + " (" + m.model + ")", false, {}};
        for (const drivers::usb::UsbDeviceEntry& e : scan.devices) {
            if (e.device != m.device) continue;
            o.available = e.problem.empty();
            o.why = o.available ? std::string() : e.state + ": " + e.problem;
            if (o.available) break;
        }
        if (!o.available && o.why.empty())
            o.why = "not on the USB bus" + (scan.why_none.empty() ? std::string() : " (" + scan.why_none + ")");
        options_.push_back(std::move(o));
    }
    return options_;
}

std::string HapticsHost::start_recording(const std::string& path) {
    if (writer_) return "already recording to " + record_path_;
    if (path.empty()) return "record: name the file to write";
    rec_ring_ = std::make_unique<SpscRing<drivers::TickRecord>>(kRecordRing);
    try {
        writer_ = std::make_unique<drivers::RecordWriter>(*rec_ring_, std::string(), path);
    } catch (const std::exception& e) {
        rec_ring_.reset();
        return std::string("record: ") + e.what();
    }
    record_path_ = path;
    forwarded_ = rec_dropped_ = 0;
    return {};
}

drivers::RecordSummary HapticsHost::stop_recording() {
    if (!writer_) return {};
    const drivers::RecordSummary sum = writer_->finish();
    writer_.reset();
    rec_ring_.reset();
    return sum;
}

void HapticsHost::forward(const drivers::TickRecord& r) {
    if (!writer_) return;
    // The writer keeps up with 20 kHz easily; should it not, the row is counted, never waited on.
    if (rec_ring_->try_push(r)) ++forwarded_;
    else ++rec_dropped_;
}

}  // namespace contactlab::editor
