// usb_context.hpp — one libusb context with its own event thread (DESIGN.md "Devices").
//
// Every asynchronous transfer callback and hot-plug callback runs on that thread. Work that libusb
// forbids inside a callback (closing a handle after hot-plug LEFT, synchronous I/O after ARRIVED,
// clearing a stall) is posted here and runs on the same thread between event-handling rounds,
// so device handles are only ever touched by one thread.
#pragma once

#include <atomic>
#include <condition_variable>
#include <deque>
#include <functional>
#include <mutex>
#include <string>
#include <thread>

struct libusb_context;

namespace contactlab::drivers::usb {

class UsbContext {
public:
    // Initialises libusb and starts the event thread. Never throws: when libusb_init fails (no
    // USB subsystem, or a libusb built without one) ok() is false and why() says so.
    UsbContext();
    ~UsbContext();
    UsbContext(const UsbContext&) = delete;
    UsbContext& operator=(const UsbContext&) = delete;

    bool ok() const noexcept { return ctx_ != nullptr; }
    const std::string& why() const noexcept { return why_; }
    libusb_context* raw() const noexcept { return ctx_; }
    bool has_hotplug() const noexcept { return hotplug_; }

    // Runs `task` on the event thread, outside any libusb callback.
    void post(std::function<void()> task);
    // Same, and waits for it (from any thread but the event thread, where it runs it inline).
    void run(const std::function<void()>& task);
    bool on_event_thread() const noexcept { return std::this_thread::get_id() == thread_.get_id(); }

private:
    void loop();

    libusb_context* ctx_ = nullptr;
    std::string why_;
    bool hotplug_ = false;
    std::atomic<bool> stop_{false};
    std::mutex mu_;  // guards tasks_ (never taken by the servo thread)
    std::deque<std::function<void()>> tasks_;
    std::thread thread_;
};

}  // namespace contactlab::drivers::usb
