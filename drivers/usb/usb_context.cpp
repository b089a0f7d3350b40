// usb_context.cpp — libusb context + event thread + deferred tasks (see usb_context.hpp).
#include "drivers/usb/usb_context.hpp"

#include <libusb.h>

namespace contactlab::drivers::usb {

UsbContext::UsbContext() {
    const int rc = libusb_init(&ctx_);
    if (rc != LIBUSB_SUCCESS) {
        ctx_ = nullptr;
        why_ = std::string("libusb_init failed (") + libusb_error_name(rc) +
               "): this system has no usable USB subsystem, so no USB device can be found";
        return;
    }
    hotplug_ = libusb_has_capability(LIBUSB_CAP_HAS_HOTPLUG) != 0;
    thread_ = std::thread([this] { loop(); });
}

UsbContext::~UsbContext() {
    if (ctx_ == nullptr) return;
    stop_.store(true);
    libusb_interrupt_event_handler(ctx_);
    thread_.join();
    libusb_exit(ctx_);
}

void UsbContext::loop() {
    auto drain = [this] {
        for (;;) {
            std::function<void()> task;
            {
                std::lock_guard<std::mutex> lock(mu_);
                if (tasks_.empty()) return;
                task = std::move(tasks_.front());
                tasks_.pop_front();
            }
            task();
        }
    };
    while (!stop_.load()) {
        // Short rounds: posted tasks wait at most this long (libusb_interrupt_event_handler
        // usually wakes the round at once).
        timeval tv{0, 2000};
        libusb_handle_events_timeout_completed(ctx_, &tv, nullptr);
        drain();
    }
    drain();  // nobody waiting in run() may hang at shutdown
}

void UsbContext::post(std::function<void()> task) {
    if (ctx_ == nullptr) return;
    {
        std::lock_guard<std::mutex> lock(mu_);
        tasks_.push_back(std::move(task));
    }
    libusb_interrupt_event_handler(ctx_);
}

void UsbContext::run(const std::function<void()>& task) {
    if (ctx_ == nullptr) return;
    if (on_event_thread()) {
        task();
        return;
    }
    bool done = false;
    std::mutex m;
    std::condition_variable cv;
    post([&] {
        task();
        std::lock_guard<std::mutex> lock(m);
        done = true;
        cv.notify_one();
    });
    std::unique_lock<std::mutex> lock(m);
    cv.wait(lock, [&] { return done; });
}

bool HotplugWatch::watch(UsbContext& ctx, std::uint16_t vendor_id, std::uint16_t product_id, Callback callback,
                         void* user) {
    if (ctx_) return true;
    if (!ctx.ok() || !ctx.has_hotplug()) return false;
    const int rc = libusb_hotplug_register_callback(
        ctx.raw(), LIBUSB_HOTPLUG_EVENT_DEVICE_ARRIVED | LIBUSB_HOTPLUG_EVENT_DEVICE_LEFT, LIBUSB_HOTPLUG_NO_FLAGS,
        vendor_id, product_id, LIBUSB_HOTPLUG_MATCH_ANY, reinterpret_cast<libusb_hotplug_callback_fn>(callback), user,
        &handle_);
    if (rc == LIBUSB_SUCCESS) ctx_ = &ctx;
    return ctx_ != nullptr;
}

void HotplugWatch::unwatch() {
    if (!ctx_) return;
    libusb_hotplug_deregister_callback(ctx_->raw(), handle_);
    ctx_ = nullptr;
}

}  // namespace contactlab::drivers::usb
