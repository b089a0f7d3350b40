// serial_port.hpp — a USB serial port (a CDC-ACM tty such as /dev/ttyACM0) in raw mode, and the
// sysfs walk that finds which ttys belong to which USB device.
//
// Boards that speak over USB serial (the Haply 2DIY's Arduino-class controller) reach the host
// through the kernel's cdc_acm driver, not libusb: the tty is the path a real board uses, and the
// tests drive this very code against ttys emulated by umockdev (a pty behind /dev/ttyACM0, the
// USB device's attributes in a faked /sys).
//
// read_exact/write_all are for the exchange thread only; they poll with a timeout and never
// allocate. A hung-up port (the board unplugged) is reported as such, distinct from a timeout.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace contactlab::drivers::serial {

enum class IoResult : std::uint8_t { ok, timeout, hangup, error };

class SerialPort {
public:
    SerialPort() = default;
    ~SerialPort() { close(); }
    SerialPort(const SerialPort&) = delete;
    SerialPort& operator=(const SerialPort&) = delete;

    // Opens `path` read-write in raw mode (8N1, no echo, no flow control, `baud`). On failure
    // returns false and `error` says why (errno's name and what to do about it).
    bool open(const std::string& path, int baud, std::string& error);
    void close() noexcept;
    bool is_open() const noexcept { return fd_ >= 0; }

    IoResult write_all(const std::uint8_t* data, std::size_t n, int timeout_ms) noexcept;
    // Reads exactly n bytes within timeout_ms; `got` is how many arrived (a short frame on timeout).
    IoResult read_exact(std::uint8_t* data, std::size_t n, int timeout_ms, std::size_t& got) noexcept;
    // Drops whatever the board sent that was not read (after a short or stray frame).
    void discard_input() noexcept;
    int last_errno() const noexcept { return errno_; }

private:
    int fd_ = -1;
    int errno_ = 0;
};

// A tty whose USB device is known by its sysfs attributes.
struct UsbTty {
    std::string node;         // /dev/ttyACM0
    std::string sysfs;        // /sys/devices/.../1-3 (the USB device)
    std::uint16_t vendor_id = 0, product_id = 0;
    std::string serial;       // the USB device's iSerial, "" when it has none
    std::string product;      // its iProduct string
    bool accessible = false;  // this user may open the node read-write
};
// Every tty under /sys/class/tty that sits on a USB device (its node need not be accessible).
std::vector<UsbTty> usb_ttys();
// The one for `node` (e.g. "/dev/ttyACM0"), if it is on a USB device.
bool usb_tty_of(const std::string& node, UsbTty& out);

}  // namespace contactlab::drivers::serial
