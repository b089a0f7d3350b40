// haply_device.cpp — the 2DIY behind the Device interface (see haply_device.hpp).
#include "drivers/usb/haply_device.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <ctime>

namespace contactlab::drivers::haply {

namespace {

double monotonic() noexcept {
    timespec ts{};
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

void sleep_until(const timespec& t) noexcept {
    while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &t, nullptr) == EINTR) {
    }
}

timespec plus(timespec t, double s) noexcept {
    const auto ns = static_cast<long long>(s * 1e9);
    t.tv_sec += static_cast<time_t>(ns / 1000000000LL);
    t.tv_nsec += static_cast<long>(ns % 1000000000LL);
    if (t.tv_nsec >= 1000000000L) {
        t.tv_nsec -= 1000000000L;
        ++t.tv_sec;
    }
    return t;
}

// Missed exchanges in a row before the board counts as silent (a fault the next reply clears).
constexpr int kMissedForFault = 3;

}  // namespace

bool is_board_id(std::uint16_t vendor_id, std::uint16_t product_id) noexcept {
    for (const BoardId& b : kBoardIds)
        if (b.vendor_id == vendor_id && b.product_id == product_id) return true;
    return false;
}

HaplyDevice::HaplyDevice(const HaplyOptions& o) : opt_(o), hw_(haply::hardware(o.generation)), epoch_(monotonic()) {
    const Aabb box = workspace(hw_.geometry);
    centre_ = {0.5 * (box.lo.x + box.hi.x), 0.5 * (box.lo.y + box.hi.y)};
}

HaplyDevice::~HaplyDevice() { close(); }

double HaplyDevice::now() const noexcept { return monotonic() - epoch_; }

Vec2 HaplyDevice::to_world(Vec p) const noexcept { return opt_.origin - Vec2{p.x - centre_.x, p.y - centre_.y}; }

Vec HaplyDevice::to_device(Vec2 w) const noexcept {
    const Vec2 d = opt_.origin - w;
    return {centre_.x + d.x, centre_.y + d.y};
}

DeviceCapabilities HaplyDevice::capabilities() const noexcept {
    DeviceCapabilities c;
    c.planar_force = true;  // no finger angle: phi stays fixed (or comes from the keyboard)
    return c;
}

DeviceLimits HaplyDevice::limits() const noexcept {
    DeviceLimits l;
    l.max_force = opt_.max_force;
    l.axis_max_force = Vec2{opt_.max_force};
    const Aabb box = workspace(hw_.geometry);
    const Vec2 a = to_world(Vec{box.lo.x, box.lo.y}), b = to_world(Vec{box.hi.x, box.hi.y});
    l.workspace.lo = glm::min(a, b);
    l.workspace.hi = glm::max(a, b);
    l.native_rate = opt_.rate;
    l.mass = opt_.mass;
    return l;
}

DeviceFault HaplyDevice::fault() const noexcept {
    return status_.fault();
}

void HaplyDevice::set_fault(DeviceFaultCode code, const char* detail) noexcept {
    status_.set_fault(code, detail);
}

void HaplyDevice::clear_fault() noexcept {
    if (state() != DeviceState::fault) return;
    status_.clear(want_engaged_.load(std::memory_order_acquire) ? DeviceState::engaged : DeviceState::ready);
}

void HaplyDevice::set_engaged(bool on) noexcept {
    want_engaged_.store(on, std::memory_order_release);
    status_.engage(on);
}

bool HaplyDevice::read(DeviceReading& out) noexcept {
    out = DeviceReading{};
    out.t = now();
    if (!status_.readable()) return false;
    const Sample s = latest_.load();
    if (s.count == 0 || out.t - s.rx_time > opt_.stale_after) return false;
    out.finger = to_world(s.p);
    out.valid = true;
    return true;
}

void HaplyDevice::write(const DeviceCommand& cmd) noexcept { command_.store(cmd); }

HaplyStats HaplyDevice::stats() const noexcept {
    HaplyStats s;
    s.exchanges = exchanges_.load();
    s.replies = replies_.load();
    s.short_frames = short_.load();
    s.wrong_device = wrong_id_.load();
    s.not_finite = nan_.load();
    s.bad_pose = bad_pose_.load();
    s.timeouts = timeouts_.load();
    s.disconnects = disconnects_.load();
    s.reconnects = reconnects_.load();
    return s;
}

std::array<double, 2> HaplyDevice::torques_for(const DeviceCommand& c, const std::array<double, 2>& angles) const noexcept {
    if (state() != DeviceState::engaged || !have_angles_) return {0.0, 0.0};
    Vec2 f = c.force;  // N, world
    if (!std::isfinite(f.x) || !std::isfinite(f.y)) return {0.0, 0.0};
    const double mag = glm::length(f);
    if (mag > opt_.max_force) f *= opt_.max_force / mag;
    std::array<double, 2> tau{};
    // The plane is turned by 180 degrees: a world force is the opposite device force.
    if (joint_torques(hw_.geometry, angles, Vec{-f.x, -f.y}, tau) != KinStatus::ok) return {0.0, 0.0};
    for (double& t : tau) t = std::clamp(t, -opt_.max_torque, opt_.max_torque);
    return tau;
}

bool HaplyDevice::connect(std::string& error, bool reconnect) {
    std::string path = opt_.port;
    serial::UsbTty info;
    if (path.empty()) {
        for (const serial::UsbTty& t : serial::usb_ttys()) {
            if (is_board_id(t.vendor_id, t.product_id)) {
                path = t.node;
                info = t;
                break;
            }
        }
        if (path.empty()) {
            error = "no Haply board found: no USB serial port of an Arduino Due (2341:003e, 2341:003d) or Zero (2341:804d) "
                    "is present; plug the 2DIY in, or name its port with --haply-port /dev/ttyACMn";
            return false;
        }
    } else {
        serial::usb_tty_of(path, info);  // for its serial number; a tty not on USB is allowed
    }
    if (!tty_.open(path, 115200, error)) return false;
    // The names are kept from the first open: other threads read them (serial(), port()).
    if (!reconnect) {
        port_ = path;
        serial_ = info.serial;
    }
    return true;
}

bool HaplyDevice::handshake(std::string& error) {
    std::uint8_t reset[kResetSize];
    std::uint8_t params[kParametersSize];
    std::uint8_t ex[kExchangeSize];
    std::uint8_t reply[kReplySize];
    pack_reset(reset);
    pack_parameters(hw_, opt_.device_id, params);
    pack_exchange(hw_, opt_.device_id, {0.0, 0.0}, ex);
    const double end = monotonic() + opt_.handshake_timeout;
    ReplyError last = ReplyError::short_frame;
    bool answered = false;
    std::uint8_t other_id = 0;
    do {
        if (tty_.write_all(reset, sizeof reset, 100) != serial::IoResult::ok ||
            tty_.write_all(params, sizeof params, 100) != serial::IoResult::ok ||
            tty_.write_all(ex, sizeof ex, 100) != serial::IoResult::ok) {
            error = "writing to " + port_ + " failed: the board went away";
            return false;
        }
        std::size_t got = 0;
        const serial::IoResult r = tty_.read_exact(reply, sizeof reply, 50, got);
        if (r == serial::IoResult::hangup || r == serial::IoResult::error) {
            error = port_ + " hung up during the hAPI handshake: the board went away";
            return false;
        }
        if (r == serial::IoResult::ok) {
            answered = true;
            std::array<double, 2> a{};
            last = unpack_reply(hw_, opt_.device_id, reply, got, a);
            if (last == ReplyError::wrong_device) other_id = reply[0];
            if (last == ReplyError::none) {
                Vec p;
                if (forward_kinematics(hw_.geometry, a, p) == KinStatus::ok) {
                    angles_ = a;
                    have_angles_ = true;
                    latest_.store(Sample{p, now(), 1});
                    return true;
                }
            }
        } else if (got > 0) {
            answered = true;
            last = ReplyError::short_frame;
        }
        tty_.discard_input();
    } while (monotonic() < end);
    if (!answered)
        error = "the board on " + port_ + " does not answer hAPI's exchange (no reply in " +
                std::to_string(opt_.handshake_timeout) + " s): is it a Haply board with its hAPI firmware?";
    else if (last == ReplyError::wrong_device)
        error = "the board on " + port_ + " answers as hAPI device " + std::to_string(other_id) + ", not " +
                std::to_string(opt_.device_id) + ": another program's set-up or firmware; unplug and replug it";
    else
        error = std::string("the board on ") + port_ + " answers hAPI's exchange with invalid replies (" + to_string(last) +
                "): check --haply-hardware (2 or 3) and the board's firmware";
    return false;
}

bool HaplyDevice::open() {
    close();
    if (!(opt_.generation == 2 || opt_.generation == 3)) {
        open_error_ = "--haply-hardware must be 2 or 3";
        set_fault(DeviceFaultCode::open_failed, open_error_.c_str());
        return false;
    }
    status_.state.store(DeviceState::opening, std::memory_order_release);
    std::string error;
    if (!connect(error, false) || !handshake(error)) {
        tty_.close();
        open_error_ = error;
        const bool denied = error.rfind("permission denied", 0) == 0;
        const bool missing = error.rfind("no Haply board", 0) == 0 || error.find("does not exist") != std::string::npos;
        set_fault(denied ? DeviceFaultCode::permission_denied : missing ? DeviceFaultCode::not_found : DeviceFaultCode::open_failed,
                  open_error_.c_str());
        return false;
    }
    status_.clear(want_engaged_.load() ? DeviceState::engaged : DeviceState::ready);
    stop_.store(false);
    thread_ = std::thread([this] { run(); });
    return true;
}

void HaplyDevice::close() {
    if (thread_.joinable()) {
        stop_.store(true);
        thread_.join();
    }
    if (tty_.is_open()) {
        // Leave the motors off: one last exchange with zero torque (its reply is not waited for).
        std::uint8_t ex[kExchangeSize];
        pack_exchange(hw_, opt_.device_id, {0.0, 0.0}, ex);
        tty_.write_all(ex, sizeof ex, 50);
        tty_.close();
    }
    status_.clear(DeviceState::disconnected);
}

void HaplyDevice::exchange_once() noexcept {
    const std::array<double, 2> tau = torques_for(command_.load(), angles_);
    std::uint8_t ex[kExchangeSize];
    std::uint8_t reply[kReplySize];
    pack_exchange(hw_, opt_.device_id, tau, ex);
    serial::IoResult r = tty_.write_all(ex, sizeof ex, opt_.reply_timeout_ms);
    std::size_t got = 0;
    if (r == serial::IoResult::ok) {
        sent_.store(tau);
        exchanges_.fetch_add(1, std::memory_order_relaxed);
        r = tty_.read_exact(reply, sizeof reply, opt_.reply_timeout_ms, got);
    }
    if (r == serial::IoResult::hangup || r == serial::IoResult::error) {
        // Unplugged mid-exchange: nothing more reaches the motors; the servo keeps running with
        // no reading (zero force) and run() reopens the port when the board is back.
        tty_.close();
        have_angles_ = false;
        disconnects_.fetch_add(1, std::memory_order_relaxed);
        set_fault(DeviceFaultCode::disconnected, "Haply board disconnected (its serial port hung up)");
        return;
    }
    ReplyError e = ReplyError::short_frame;
    std::array<double, 2> a{};
    if (r == serial::IoResult::ok) e = unpack_reply(hw_, opt_.device_id, reply, got, a);
    if (r == serial::IoResult::timeout && got == 0) {
        timeouts_.fetch_add(1, std::memory_order_relaxed);
    } else if (e == ReplyError::short_frame) {
        short_.fetch_add(1, std::memory_order_relaxed);
    } else if (e == ReplyError::wrong_device) {
        wrong_id_.fetch_add(1, std::memory_order_relaxed);
    } else if (e == ReplyError::not_finite) {
        nan_.fetch_add(1, std::memory_order_relaxed);
    }
    Vec p;
    if (e == ReplyError::none && forward_kinematics(hw_.geometry, a, p) != KinStatus::ok) {
        bad_pose_.fetch_add(1, std::memory_order_relaxed);
        e = ReplyError::not_finite;
    }
    if (e != ReplyError::none) {
        // A frame that is not whole leaves the stream misaligned: drop what is buffered so the
        // next reply starts at its first byte.
        tty_.discard_input();
        if (++missed_ >= kMissedForFault) {
            const char* why = r == serial::IoResult::timeout && got == 0
                                  ? "Haply board stopped answering (no reply to the last exchanges)"
                              : e == ReplyError::wrong_device ? "Haply board answers as another hAPI device id"
                              : e == ReplyError::not_finite   ? "Haply board sends angles that are not finite or name no pose"
                                                              : "Haply board sends short frames";
            set_fault(r == serial::IoResult::timeout && got == 0 ? DeviceFaultCode::timeout : DeviceFaultCode::io_error, why);
        }
        return;
    }
    missed_ = 0;
    angles_ = a;
    have_angles_ = true;
    const Sample prev = latest_.load();
    latest_.store(Sample{p, now(), prev.count + 1});
    replies_.fetch_add(1, std::memory_order_relaxed);
    if (status_.code.load(std::memory_order_acquire) != DeviceFaultCode::disconnected) clear_fault();
}

void HaplyDevice::run() noexcept {
    const double period = 1.0 / opt_.rate;  // s
    timespec next{};
    clock_gettime(CLOCK_MONOTONIC, &next);
    double reopen_at = 0.0;
    while (!stop_.load(std::memory_order_acquire)) {
        if (!tty_.is_open()) {
            // Unplugged: try the port again every reopen_every s until the board is back.
            if (monotonic() >= reopen_at) {
                reopen_at = monotonic() + opt_.reopen_every;
                std::string error;
                try {
                    if (connect(error, true) && handshake(error)) {
                        reconnects_.fetch_add(1, std::memory_order_relaxed);
                        missed_ = 0;
                        status_.code.store(DeviceFaultCode::none, std::memory_order_release);
                        clear_fault();
                    } else {
                        tty_.close();
                    }
                } catch (...) {  // allocation failure while unplugged: try again later
                    tty_.close();
                }
            }
            next = plus(next, 0.01);
            sleep_until(next);
            clock_gettime(CLOCK_MONOTONIC, &next);
            continue;
        }
        exchange_once();
        next = plus(next, period);
        timespec now_ts{};
        clock_gettime(CLOCK_MONOTONIC, &now_ts);
        // Behind by more than a period (a slow reply): restart the schedule rather than burst.
        if (now_ts.tv_sec > next.tv_sec + 1 ||
            (static_cast<double>(now_ts.tv_sec - next.tv_sec) + 1e-9 * static_cast<double>(now_ts.tv_nsec - next.tv_nsec)) > period)
            next = now_ts;
        sleep_until(next);
    }
}

}  // namespace contactlab::drivers::haply
