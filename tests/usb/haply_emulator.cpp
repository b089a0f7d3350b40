// haply_emulator.cpp — hAPI's firmware on the far end of umockdev's pty (see haply_emulator.hpp).
#include "haply_emulator.hpp"

#include "deny_node_access.hpp"

#include "drivers/usb/haply_protocol.hpp"

#include <umockdev.h>

#include <dirent.h>
#include <fcntl.h>
#include <poll.h>
#include <sys/stat.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <atomic>
#include <cmath>
#include <limits>
#include <mutex>
#include <stdexcept>
#include <thread>

namespace contactlab::test {

using namespace drivers::haply;

namespace {

constexpr const char* kUsbPath = "/devices/pci0000:00/0000:00:14.0/usb1/1-3";

}  // namespace

struct HaplyEmulator::Impl {
    Config cfg;
    HaplyHardware hw;
    UMockdevTestbed* testbed = nullptr;
    mutable std::mutex mu;
    bool plugged = false;
    int master = -1;
    // ttyACM<index>: a board replugged while its old tty is still held open comes back as the
    // next one, as cdc_acm numbers them (and umockdev cannot reuse a node name in one testbed).
    int index = -1;
    std::string tty() const { return "ttyACM" + std::to_string(index); }
    std::string tty_path() const { return std::string(kUsbPath) + "/1-3:1.0/tty/" + tty(); }
    std::thread board;
    std::atomic<bool> stop{false};

    std::array<float, 2> angles_deg{90.0f, 90.0f};
    HaplyMisbehaviour mis = HaplyMisbehaviour::none;
    std::uint64_t resets = 0, exchanges = 0, replies = 0;
    std::vector<std::uint8_t> params;
    std::array<float, 2> torques{};
    std::uint8_t id = 0;

    void add_device() {
        const std::string rec = std::string("P: ") + kUsbPath +
                                "\nE: SUBSYSTEM=usb\nE: DEVTYPE=usb_device\n"
                                "A: idVendor=2341\nA: idProduct=003e\nA: serial=" + cfg.serial +
                                "\nA: manufacturer=Arduino LLC\nA: product=Arduino Due\n\n"
                                "P: " + kUsbPath + "/1-3:1.0\nE: SUBSYSTEM=usb\nE: DEVTYPE=usb_interface\nE: DRIVER=cdc_acm\n\n"
                                "P: " + tty_path() + "\nN: " + tty() + "\nE: SUBSYSTEM=tty\nE: DEVNAME=/dev/" + tty() +
                                "\nA: dev=166:" + std::to_string(index) + "\n";
        GError* err = nullptr;
        if (!umockdev_testbed_add_from_string(testbed, rec.c_str(), &err)) {
            const std::string msg = err ? err->message : "?";
            if (err) g_error_free(err);
            throw std::runtime_error("umockdev_testbed_add_from_string: " + msg);
        }
        master = umockdev_testbed_get_dev_fd(testbed, ("/dev/" + tty()).c_str());
        if (master < 0) throw std::runtime_error("umockdev gave no pty for /dev/" + tty());
        // The firmware reads the host's bytes as they come: no line discipline on this end.
        ::fcntl(master, F_SETFL, ::fcntl(master, F_GETFL) | O_NONBLOCK);
    }

    // Reads up to n bytes within ms; false when the board is told to stop.
    bool read_bytes(std::uint8_t* buf, std::size_t n, std::size_t& got) {
        got = 0;
        while (got < n) {
            if (stop.load()) return false;
            pollfd p{master, POLLIN, 0};
            if (::poll(&p, 1, 5) <= 0) continue;
            const ssize_t r = ::read(master, buf + got, n - got);
            if (r > 0) got += static_cast<std::size_t>(r);
        }
        return true;
    }

    void write_bytes(const std::uint8_t* b, std::size_t n) {
        std::size_t done = 0;
        while (done < n && !stop.load()) {
            const ssize_t w = ::write(master, b + done, n - done);
            if (w > 0) done += static_cast<std::size_t>(w);
            else ::usleep(100);
        }
    }

    // Unplugged from the board's own thread (mid-exchange): close the pty's end at once so the
    // host's pending read hangs up; the sysfs record goes in unplug().
    void hang_up() {
        std::lock_guard<std::mutex> lock(mu);
        if (master >= 0) ::close(master);
        master = -1;
    }

    void firmware() {
        for (;;) {
            std::uint8_t type = 0;
            std::size_t got = 0;
            if (!read_bytes(&type, 1, got)) return;
            std::uint8_t buf[kParametersSize];
            buf[0] = type;
            const std::size_t size = type == kReset ? kResetSize : type == kParameters ? kParametersSize
                                   : type == kExchange ? kExchangeSize : 1;
            if (size > 1 && !read_bytes(buf + 1, size - 1, got)) return;
            if (type == kReset) {
                std::lock_guard<std::mutex> lock(mu);
                ++resets;
            } else if (type == kParameters) {
                std::lock_guard<std::mutex> lock(mu);
                params.assign(buf, buf + kParametersSize);
                id = buf[1];
            } else if (type == kExchange) {
                std::uint8_t ex_id = 0;
                std::array<float, 2> tau{};
                unpack_exchange(hw, buf, kExchangeSize, ex_id, tau);
                HaplyMisbehaviour m;
                std::array<float, 2> a{};
                std::uint8_t reply_id = 0;
                {
                    std::lock_guard<std::mutex> lock(mu);
                    ++exchanges;
                    torques = tau;
                    m = mis;
                    a = angles_deg;
                    reply_id = ex_id;
                }
                if (m == HaplyMisbehaviour::silent) continue;
                if (m == HaplyMisbehaviour::unplug_mid_exchange) {
                    hang_up();
                    return;
                }
                if (m == HaplyMisbehaviour::wrong_device) reply_id = static_cast<std::uint8_t>(ex_id + 1);
                if (m == HaplyMisbehaviour::nan_angles) a[0] = std::numeric_limits<float>::quiet_NaN();
                std::uint8_t reply[kReplySize];
                pack_reply(hw, reply_id, a, reply);
                write_bytes(reply, m == HaplyMisbehaviour::short_frames ? 5 : kReplySize);
                std::lock_guard<std::mutex> lock(mu);
                ++replies;
            }
        }
    }
};

HaplyEmulator::HaplyEmulator(const Config& c) : impl_(std::make_unique<Impl>()) {
    impl_->cfg = c;
    impl_->hw = hardware(c.generation);
    impl_->testbed = umockdev_testbed_new();
    // The handle in the middle of the workspace until a test says otherwise.
    const contactlab::Aabb box = workspace(impl_->hw.geometry);
    set_position(Vec{0.5 * (box.lo.x + box.hi.x), 0.5 * (box.lo.y + box.hi.y)});
    if (c.plugged) plug();
}

HaplyEmulator::~HaplyEmulator() {
    unplug();
    g_clear_object(&impl_->testbed);
}

void HaplyEmulator::plug() {
    {
        std::lock_guard<std::mutex> lock(impl_->mu);
        if (impl_->plugged) return;
        impl_->plugged = true;
        ++impl_->index;
        impl_->id = 0;
        impl_->params.clear();
    }
    impl_->add_device();
    impl_->stop.store(false);
    impl_->board = std::thread([this] { impl_->firmware(); });
}

void HaplyEmulator::unplug() {
    {
        std::lock_guard<std::mutex> lock(impl_->mu);
        if (!impl_->plugged) return;
        impl_->plugged = false;
    }
    impl_->stop.store(true);
    if (impl_->board.joinable()) impl_->board.join();
    impl_->hang_up();
    umockdev_testbed_remove_device(impl_->testbed, ("/sys" + impl_->tty_path()).c_str());
    umockdev_testbed_remove_device(impl_->testbed, (std::string("/sys") + kUsbPath + "/1-3:1.0").c_str());
    umockdev_testbed_remove_device(impl_->testbed, (std::string("/sys") + kUsbPath).c_str());
    // umockdev removes the node but keeps its map from the old pty (/dev/.ptymap/_dev_pts_N) to
    // the device number; the kernel reuses the freed pty's number at the replug, and umockdev
    // aborts on the stale link. Only this board's tty is mapped: clear them all, as an unplug
    // would.
    gchar* root = umockdev_testbed_get_root_dir(impl_->testbed);
    const std::string map = std::string(root) + "/dev/.ptymap";
    g_free(root);
    if (DIR* d = ::opendir(map.c_str())) {
        while (const dirent* e = ::readdir(d))
            if (e->d_name[0] != '.') ::unlink((map + "/" + e->d_name).c_str());
        ::closedir(d);
    }
}

void HaplyEmulator::deny_permission() { usb_test::deny_node_access(impl_->testbed, node()); }

void HaplyEmulator::set_position(Vec p) {
    std::array<double, 2> t{};
    if (inverse_kinematics(impl_->hw.geometry, p, t) != KinStatus::ok) throw std::runtime_error("emulator: unreachable");
    set_angles_deg(static_cast<float>(t[0] / kDegree), static_cast<float>(t[1] / kDegree));
}

void HaplyEmulator::set_angles_deg(float a1, float a2) {
    std::lock_guard<std::mutex> lock(impl_->mu);
    impl_->angles_deg = {a1, a2};
}

void HaplyEmulator::misbehave(HaplyMisbehaviour m) {
    std::lock_guard<std::mutex> lock(impl_->mu);
    impl_->mis = m;
}

std::uint64_t HaplyEmulator::resets() const {
    std::lock_guard<std::mutex> lock(impl_->mu);
    return impl_->resets;
}
std::uint64_t HaplyEmulator::exchanges() const {
    std::lock_guard<std::mutex> lock(impl_->mu);
    return impl_->exchanges;
}
std::uint64_t HaplyEmulator::replies() const {
    std::lock_guard<std::mutex> lock(impl_->mu);
    return impl_->replies;
}
std::vector<std::uint8_t> HaplyEmulator::parameters() const {
    std::lock_guard<std::mutex> lock(impl_->mu);
    return impl_->params;
}
std::array<float, 2> HaplyEmulator::last_torques() const {
    std::lock_guard<std::mutex> lock(impl_->mu);
    return impl_->torques;
}
std::uint8_t HaplyEmulator::device_id() const {
    std::lock_guard<std::mutex> lock(impl_->mu);
    return impl_->id;
}
std::string HaplyEmulator::node() const {
    std::lock_guard<std::mutex> lock(impl_->mu);
    return "/dev/" + impl_->tty();
}
bool HaplyEmulator::plugged() const {
    std::lock_guard<std::mutex> lock(impl_->mu);
    return impl_->plugged;
}

}  // namespace contactlab::test
