// serial_port.cpp — raw USB serial ports and their USB devices (see serial_port.hpp).
#include "drivers/usb/serial_port.hpp"

#include <dirent.h>
#include <fcntl.h>
#include <poll.h>
#include <termios.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <ctime>
#include <fstream>

namespace contactlab::drivers::serial {

namespace {

speed_t speed_of(int baud) noexcept {
    switch (baud) {
        case 9600: return B9600;
        case 57600: return B57600;
        case 230400: return B230400;
        case 460800: return B460800;
        case 921600: return B921600;
        default: return B115200;  // CDC-ACM ignores the rate; 115200 is what hAPI's examples set
    }
}

double monotonic_ms() noexcept {
    timespec ts{};
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return 1e3 * static_cast<double>(ts.tv_sec) + 1e-6 * static_cast<double>(ts.tv_nsec);
}

// Polls for `events` until the deadline (ms on monotonic_ms's clock).
IoResult wait_for(int fd, short events, double deadline, int& err) noexcept {
    for (;;) {
        const double left = deadline - monotonic_ms();
        if (left <= 0.0) return IoResult::timeout;
        pollfd p{fd, events, 0};
        const int r = ::poll(&p, 1, static_cast<int>(left) + 1);
        if (r < 0) {
            if (errno == EINTR) continue;
            err = errno;
            return IoResult::error;
        }
        if (r == 0) continue;
        // A hung-up tty (its USB device gone) reports POLLHUP, often with POLLIN and POLLERR.
        if ((p.revents & (POLLHUP | POLLERR | POLLNVAL)) != 0 && (p.revents & events) == 0) return IoResult::hangup;
        if ((p.revents & POLLHUP) != 0) return IoResult::hangup;
        if ((p.revents & events) != 0) return IoResult::ok;
    }
}

std::string read_attribute(const std::string& dir, const char* name) {
    std::ifstream in(dir + "/" + name);
    std::string s;
    std::getline(in, s);
    while (!s.empty() && (s.back() == '\n' || s.back() == '\r' || s.back() == ' ')) s.pop_back();
    return s;
}

// "/sys/class/tty/" + a link such as "../../devices/x/y/tty/ttyACM0", with "." and ".." resolved
// by name (the link's own form: sysfs links point straight at the device's directory).
std::string join_link(const std::string& base_dir, const std::string& link) {
    std::vector<std::string> parts;
    auto push = [&parts](const std::string& path) {
        std::size_t i = 0;
        while (i <= path.size()) {
            const std::size_t j = path.find('/', i);
            const std::string part = path.substr(i, j == std::string::npos ? std::string::npos : j - i);
            if (part == "..") {
                if (!parts.empty()) parts.pop_back();
            } else if (!part.empty() && part != ".") {
                parts.push_back(part);
            }
            if (j == std::string::npos) break;
            i = j + 1;
        }
    };
    if (link.empty() || link[0] != '/') push(base_dir);
    push(link);
    std::string out;
    for (const std::string& p : parts) out += "/" + p;
    return out;
}

// The USB device above a tty's sysfs directory: the nearest ancestor with an idVendor.
bool usb_device_above(std::string dir, std::string& device) {
    while (dir.size() > std::strlen("/sys/devices")) {
        const std::size_t slash = dir.rfind('/');
        if (slash == std::string::npos) return false;
        dir.resize(slash);
        if (!read_attribute(dir, "idVendor").empty()) {
            device = dir;
            return true;
        }
    }
    return false;
}

bool hex16(const std::string& s, std::uint16_t& v) {
    if (s.empty() || s.size() > 4) return false;
    unsigned long x = 0;
    for (char c : s) {
        const int d = c >= '0' && c <= '9' ? c - '0' : c >= 'a' && c <= 'f' ? c - 'a' + 10 : c >= 'A' && c <= 'F' ? c - 'A' + 10 : -1;
        if (d < 0) return false;
        x = x * 16 + static_cast<unsigned long>(d);
    }
    v = static_cast<std::uint16_t>(x);
    return true;
}

bool describe(const std::string& name, UsbTty& out) {
    char link[512];
    const std::string cls = "/sys/class/tty/" + name;
    const ssize_t n = ::readlink(cls.c_str(), link, sizeof link - 1);
    if (n <= 0) return false;
    link[n] = '\0';
    std::string device;
    if (!usb_device_above(join_link("/sys/class/tty", link), device)) return false;
    UsbTty t;
    t.node = "/dev/" + name;
    t.sysfs = device;
    if (!hex16(read_attribute(device, "idVendor"), t.vendor_id) || !hex16(read_attribute(device, "idProduct"), t.product_id))
        return false;
    t.serial = read_attribute(device, "serial");
    t.product = read_attribute(device, "product");
    t.accessible = ::access(t.node.c_str(), R_OK | W_OK) == 0;
    out = t;
    return true;
}

}  // namespace

bool SerialPort::open(const std::string& path, int baud, std::string& error) {
    close();
    const int fd = ::open(path.c_str(), O_RDWR | O_NOCTTY | O_NONBLOCK | O_CLOEXEC);
    if (fd < 0) {
        errno_ = errno;
        if (errno_ == EACCES || errno_ == EPERM)
            error = "permission denied opening " + path +
                    ": install the udev rule (assets/udev/70-contactlab.rules; see docs/devices.md) or add yourself to "
                    "the dialout group, then unplug and replug the board";
        else if (errno_ == ENOENT || errno_ == ENODEV || errno_ == ENXIO)
            error = path + " does not exist: the board is not plugged in (or is another tty; see contactlab devices)";
        else if (errno_ == EBUSY)
            error = path + " is busy: another program holds it";
        else
            error = "cannot open " + path + ": " + std::strerror(errno_);
        return false;
    }
    termios tio{};
    if (::tcgetattr(fd, &tio) != 0) {
        errno_ = errno;
        error = path + " is not a serial port (tcgetattr: " + std::strerror(errno_) + ")";
        ::close(fd);
        return false;
    }
    ::cfmakeraw(&tio);
    tio.c_cflag |= CLOCAL | CREAD;
    tio.c_cflag &= ~static_cast<tcflag_t>(CRTSCTS);
    tio.c_cc[VMIN] = 0;
    tio.c_cc[VTIME] = 0;
    ::cfsetispeed(&tio, speed_of(baud));
    ::cfsetospeed(&tio, speed_of(baud));
    if (::tcsetattr(fd, TCSANOW, &tio) != 0) {
        errno_ = errno;
        error = "cannot set raw mode on " + path + ": " + std::strerror(errno_);
        ::close(fd);
        return false;
    }
    ::tcflush(fd, TCIOFLUSH);
    fd_ = fd;
    return true;
}

void SerialPort::close() noexcept {
    if (fd_ >= 0) ::close(fd_);
    fd_ = -1;
}

IoResult SerialPort::write_all(const std::uint8_t* data, std::size_t n, int timeout_ms) noexcept {
    if (fd_ < 0) return IoResult::error;
    const double deadline = monotonic_ms() + timeout_ms;
    std::size_t done = 0;
    while (done < n) {
        const ssize_t w = ::write(fd_, data + done, n - done);
        if (w > 0) {
            done += static_cast<std::size_t>(w);
            continue;
        }
        if (w < 0 && errno == EINTR) continue;
        if (w < 0 && errno != EAGAIN) {
            errno_ = errno;
            return errno_ == EIO || errno_ == ENODEV || errno_ == ENXIO ? IoResult::hangup : IoResult::error;
        }
        const IoResult r = wait_for(fd_, POLLOUT, deadline, errno_);
        if (r != IoResult::ok) return r;
    }
    return IoResult::ok;
}

IoResult SerialPort::read_exact(std::uint8_t* data, std::size_t n, int timeout_ms, std::size_t& got) noexcept {
    got = 0;
    if (fd_ < 0) return IoResult::error;
    const double deadline = monotonic_ms() + timeout_ms;
    while (got < n) {
        const ssize_t r = ::read(fd_, data + got, n - got);
        if (r > 0) {
            got += static_cast<std::size_t>(r);
            continue;
        }
        if (r == 0) {
            // A raw tty with VMIN = 0 reads 0 both when idle and after hang-up: poll tells which.
            const IoResult w = wait_for(fd_, POLLIN, deadline, errno_);
            if (w != IoResult::ok) return w;
            continue;
        }
        if (errno == EINTR) continue;
        if (errno != EAGAIN) {
            errno_ = errno;
            return errno_ == EIO || errno_ == ENODEV || errno_ == ENXIO ? IoResult::hangup : IoResult::error;
        }
        const IoResult w = wait_for(fd_, POLLIN, deadline, errno_);
        if (w != IoResult::ok) return w;
    }
    return IoResult::ok;
}

void SerialPort::discard_input() noexcept {
    if (fd_ >= 0) ::tcflush(fd_, TCIFLUSH);
}

std::vector<UsbTty> usb_ttys() {
    std::vector<UsbTty> out;
    DIR* d = ::opendir("/sys/class/tty");
    if (d == nullptr) return out;
    while (const dirent* e = ::readdir(d)) {
        const std::string name = e->d_name;
        if (name == "." || name == "..") continue;
        UsbTty t;
        if (describe(name, t)) out.push_back(t);
    }
    ::closedir(d);
    return out;
}

bool usb_tty_of(const std::string& node, UsbTty& out) {
    const std::size_t slash = node.rfind('/');
    return describe(slash == std::string::npos ? node : node.substr(slash + 1), out);
}

}  // namespace contactlab::drivers::serial
