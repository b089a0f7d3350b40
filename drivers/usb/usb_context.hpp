// usb_context.hpp — one libusb context with its own event thread (DESIGN.md "Devices").
//
// Every asynchronous transfer callback and hot-plug callback runs on that thread. Work that libusb
// forbids inside a callback (closing a handle after hot-plug LEFT, synchronous I/O after ARRIVED,
// clearing a stall) is posted here and runs on the same thread between event-handling rounds,
// so device handles are only ever touched by one thread.
#pragma once

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <functional>
#include <mutex>
#include <string>
#include <thread>

struct libusb_context;
struct libusb_device;

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

// One hot-plug registration (arrivals and departures of vendor:product) on a context, shared by
// the device classes. Removed by unwatch() or when the watch is destroyed.
class HotplugWatch {
public:
    // The devices' callbacks take the event as a plain int (libusb's enum in disguise).
    using Callback = int (*)(libusb_context*, libusb_device*, int event, void* user);
    HotplugWatch() = default;
    HotplugWatch(const HotplugWatch&) = delete;
    HotplugWatch& operator=(const HotplugWatch&) = delete;
    ~HotplugWatch() { unwatch(); }

    // Registers unless already registered or the context has no hot-plug; true when registered.
    bool watch(UsbContext& ctx, std::uint16_t vendor_id, std::uint16_t product_id, Callback callback, void* user);
    void unwatch();

private:
    UsbContext* ctx_ = nullptr;  // set while registered
    int handle_ = 0;
};

}  // namespace contactlab::drivers::usb
