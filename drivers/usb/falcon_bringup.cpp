// falcon_bringup.cpp — bringing a Falcon up on the event thread: open and claim, check for
// running firmware, otherwise bootloader handshake and firmware upload from the user's file.
// Every wait is bounded, and every failure says what the user can try.
#include "drivers/usb/falcon_device.hpp"
#include "drivers/usb/usb_status.hpp"

#include <libusb.h>

#include <chrono>
#include <cstring>
#include <fstream>
#include <thread>
#include <vector>

namespace contactlab::drivers::falcon {

namespace {

constexpr std::uint8_t kFtdiOut = 0x40;  // vendor, device recipient, host -> device

bool permanent(DeviceFaultCode c) {
    return c == DeviceFaultCode::permission_denied || c == DeviceFaultCode::not_found ||
           c == DeviceFaultCode::disconnected || c == DeviceFaultCode::open_failed;
}

}  // namespace

bool FalconDevice::bring_up_with_retries() {
    DeviceFault f;
    for (int attempt = 0; attempt < std::max(1, opt_.open_attempts); ++attempt) {
        if (attempt > 0) std::this_thread::sleep_for(std::chrono::duration<double>(opt_.retry_delay));
        f = bring_up();
        if (f.code == DeviceFaultCode::none) return true;
        teardown(false);
        if (permanent(f.code)) break;
    }
    set_fault(f);
    return false;
}

DeviceFault FalconDevice::control(std::uint8_t request, std::uint16_t value) {
    const int rc = libusb_control_transfer(handle_, kFtdiOut, request, value, 0, nullptr, 0, opt_.timeout_ms);
    return rc < 0 ? usb::fault_of_error(rc) : DeviceFault{};
}

DeviceFault FalconDevice::write_bytes(const std::uint8_t* data, int n) {
    int done = 0;
    const int rc = libusb_bulk_transfer(handle_, kEndpointOut, const_cast<std::uint8_t*>(data), n, &done, opt_.timeout_ms);
    if (rc < 0) return usb::fault_of_error(rc);
    if (done != n) return {DeviceFaultCode::io_error, "short write to the Falcon"};
    return {};
}

int FalconDevice::read_payload(std::uint8_t* buf, int want, unsigned ms, DeviceFault& f) {
    // The FTDI answers every IN with two modem-status bytes, and with nothing else when no serial
    // data has arrived: keep reading until enough payload came or the time is up.
    const auto end = std::chrono::steady_clock::now() + std::chrono::milliseconds(ms);
    int got = 0;
    std::uint8_t raw[kFtdiPacket];
    while (got < want && std::chrono::steady_clock::now() < end) {
        int n = 0;
        const int rc = libusb_bulk_transfer(handle_, kEndpointIn, raw, sizeof raw, &n, opt_.timeout_ms);
        if (rc == LIBUSB_ERROR_TIMEOUT) continue;
        if (rc < 0) {
            f = usb::fault_of_error(rc);
            return got;
        }
        for (int i = 2; i < n && got < want; ++i) buf[got++] = raw[i];
        if (n <= 2) std::this_thread::sleep_for(std::chrono::microseconds(200));
    }
    return got;
}

bool FalconDevice::firmware_running(DeviceFault& f) {
    // Running firmware answers a command packet with a state packet. A bootloader that echoes
    // bytes would hand our own packet back, so a reply identical to the probe does not count.
    for (int attempt = 0; attempt < 3; ++attempt) {
        std::uint8_t pkt[kPacketSize];
        Command probe;
        probe.flags = attempt % 2 ? kLedRed : kLedBlue;
        pack(probe, pkt);
        if (f = write_bytes(pkt, kPacketSize); f.code != DeviceFaultCode::none) return false;
        std::uint8_t buf[kPacketSize * 2];
        const int n = read_payload(buf, kPacketSize, 30, f);
        if (f.code != DeviceFaultCode::none) return false;
        for (int i = 0; i + static_cast<int>(kPacketSize) <= n; ++i) {
            State s;
            if (unpack(buf + i, kPacketSize, s) && std::memcmp(buf + i, pkt, kPacketSize) != 0) return true;
        }
    }
    return false;
}

DeviceFault FalconDevice::upload_firmware() {
    if (opt_.firmware.empty())
        return {DeviceFaultCode::open_failed,
                "the Falcon has no firmware running: give the firmware file to upload (Novint's Falcon firmware, "
                "e.g. from their driver package; ContactLab does not ship it)"};
    std::ifstream in(opt_.firmware, std::ios::binary);
    if (!in) return {DeviceFaultCode::open_failed, "cannot read the Falcon firmware file (check the path)"};
    std::vector<std::uint8_t> fw((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (fw.empty() || fw.size() > 65536)
        return {DeviceFaultCode::open_failed, "the Falcon firmware file is empty or larger than 64 KiB: not a Falcon firmware"};

    for (const FtdiRequest& r : kBootloaderSetup)
        if (DeviceFault f = control(r.request, r.value); f.code != DeviceFaultCode::none) return f;
    bool answered = false;
    for (int attempt = 0; attempt < opt_.handshake_attempts && !answered; ++attempt) {
        if (DeviceFault f = write_bytes(kBootProbe.data(), kBootProbe.size()); f.code != DeviceFaultCode::none) return f;
        std::uint8_t buf[8]{};
        DeviceFault f;
        const int n = read_payload(buf, 5, 20, f);
        if (f.code != DeviceFaultCode::none) return f;
        // The reply may come with a leading 0x00 (seen on some hosts).
        const int skip = n > 0 && buf[0] == 0x00 ? 1 : 0;
        answered = n - skip >= 4 && std::memcmp(buf + skip, kBootReply.data(), kBootReply.size()) == 0;
    }
    if (!answered)
        return {DeviceFaultCode::timeout,
                "the Falcon's bootloader did not answer: check that its power supply is plugged in (USB power alone is "
                "not enough), unplug and replug it, and try a powered USB hub"};
    for (const FtdiRequest& r : kUploadSetup)
        if (DeviceFault f = control(r.request, r.value); f.code != DeviceFaultCode::none) return f;
    const std::uint8_t a = kUploadProbe;
    if (DeviceFault f = write_bytes(&a, 1); f.code != DeviceFaultCode::none) return f;
    std::uint8_t echo[kUploadChunk]{};
    DeviceFault f;
    if (read_payload(echo, 1, 100, f) != 1 || echo[0] != kUploadProbe)
        return f.code != DeviceFaultCode::none
                   ? f
                   : DeviceFault{DeviceFaultCode::timeout, "the Falcon's bootloader did not accept the upload: unplug and replug it, then try again"};
    // The bootloader echoes every byte: compare chunk by chunk.
    for (std::size_t off = 0; off < fw.size(); off += kUploadChunk) {
        const int n = static_cast<int>(std::min(kUploadChunk, fw.size() - off));
        if (f = write_bytes(fw.data() + off, n); f.code != DeviceFaultCode::none) return f;
        if (read_payload(echo, n, 200, f) != n || std::memcmp(echo, fw.data() + off, static_cast<std::size_t>(n)) != 0)
            return f.code != DeviceFaultCode::none
                       ? f
                       : DeviceFault{DeviceFaultCode::io_error, "Falcon firmware upload failed (the echo did not match): unplug and replug it and try again"};
    }
    uploads_.fetch_add(1);
    for (const FtdiRequest& r : kNormalSetup)
        if (f = control(r.request, r.value); f.code != DeviceFaultCode::none) return f;
    if (!firmware_running(f))
        return f.code != DeviceFaultCode::none
                   ? f
                   : DeviceFault{DeviceFaultCode::open_failed, "the firmware was uploaded but the Falcon does not answer: is the file the Falcon's firmware?"};
    return {};
}

DeviceFault FalconDevice::bring_up() {
    if (handle_ != nullptr) return {};
    status_.state.store(DeviceState::opening);
    libusb_device** list = nullptr;
    const ssize_t n = libusb_get_device_list(ctx_->raw(), &list);
    if (n < 0) return usb::fault_of_error(static_cast<int>(n));
    for (ssize_t i = 0; i < n && dev_ == nullptr; ++i) {
        libusb_device_descriptor d{};
        if (libusb_get_device_descriptor(list[i], &d) != LIBUSB_SUCCESS) continue;
        if (d.idVendor != kVendorId || d.idProduct != kProductId) continue;
        if (opt_.bus >= 0 && libusb_get_bus_number(list[i]) != opt_.bus) continue;
        if (opt_.address >= 0 && libusb_get_device_address(list[i]) != opt_.address) continue;
        dev_ = libusb_ref_device(list[i]);
    }
    libusb_free_device_list(list, 1);
    if (dev_ == nullptr) return {DeviceFaultCode::not_found, "no Novint Falcon (USB 0403:cb48) is plugged in"};
    if (const int rc = libusb_open(dev_, &handle_); rc != LIBUSB_SUCCESS) {
        handle_ = nullptr;
        return usb::fault_of_error(rc);
    }
    // ftdi_sio binds to FTDI chips as a serial port: detach it while we drive the Falcon.
    const int ad = libusb_set_auto_detach_kernel_driver(handle_, 1);
    if (ad != LIBUSB_SUCCESS && ad != LIBUSB_ERROR_NOT_SUPPORTED) return usb::fault_of_error(ad);
    if (const int rc = libusb_claim_interface(handle_, 0); rc != LIBUSB_SUCCESS) return usb::fault_of_error(rc);
    // The FTDI chip's serial names this Falcon in the results' meta. A Falcon that will not say
    // it still works: the serial stays "" and only provenance loses it.
    libusb_device_descriptor desc{};
    if (libusb_get_device_descriptor(dev_, &desc) == LIBUSB_SUCCESS && desc.iSerialNumber != 0) {
        std::array<char, 64> sn{};
        const int n = libusb_get_string_descriptor_ascii(handle_, desc.iSerialNumber,
                                                         reinterpret_cast<unsigned char*>(sn.data()), sn.size() - 1);
        if (n > 0) serial_.store(sn);
    }

    for (const FtdiRequest& r : kNormalSetup)
        if (DeviceFault f = control(r.request, r.value); f.code != DeviceFaultCode::none) return f;
    DeviceFault f;
    if (!firmware_running(f)) {
        if (f.code != DeviceFaultCode::none) return f;
        if (f = upload_firmware(); f.code != DeviceFaultCode::none) return f;
    }

    in_ = libusb_alloc_transfer(0);
    out_ = libusb_alloc_transfer(0);
    stopping_ = gone_ = false;
    parser_.reset();
    latest_.store(Sample{});
    libusb_fill_bulk_transfer(in_, handle_, kEndpointIn, in_buf_, sizeof in_buf_, &FalconDevice::in_callback, this,
                              opt_.timeout_ms);
    const int rc = libusb_submit_transfer(in_);
    in_active_ = rc == LIBUSB_SUCCESS;
    if (!in_active_) return usb::fault_of_error(rc);
    status_.clear(DeviceState::ready);
    send_command();
    return {};
}

}  // namespace contactlab::drivers::falcon
