// replay_device.hpp — plays a recording (record_writer.hpp, "contactlab recording v1") back as a
// device: each tick reads the next recorded finger configuration and roller position exactly
// (the file holds 17 significant digits). Commands are accepted and ignored. At the end of the
// recording the device holds the last sample and reports end_of_data.
#pragma once

#include "drivers/device.hpp"

#include <stdexcept>
#include <string>
#include <vector>

namespace contactlab::drivers {

struct RecordingError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

struct RecordedSample {
    double t = 0.0;         // s
    Vec2 finger{0.0};       // m
    double phi = 0.0;       // rad
    double roller_l = 0.0;  // m
};

// Reads the rows of a recording; throws RecordingError naming file:line on bad input.
std::vector<RecordedSample> read_recording_file(const std::string& path);

class ReplayDevice final : public Device {
public:
    explicit ReplayDevice(std::vector<RecordedSample> samples) : samples_(std::move(samples)) {}

    const char* name() const noexcept override { return "replay"; }
    DeviceCapabilities capabilities() const noexcept override;
    DeviceLimits limits() const noexcept override { return DeviceLimits{}; }
    bool open() override;
    void close() override { state_ = DeviceState::disconnected; }
    DeviceState state() const noexcept override { return state_; }
    DeviceFault fault() const noexcept override { return fault_; }
    void set_engaged(bool on) noexcept override;
    bool read(DeviceReading& out) noexcept override;
    void write(const DeviceCommand&) noexcept override {}
    void advance(double dt) noexcept override;

    std::size_t size() const { return samples_.size(); }
    double duration() const { return samples_.empty() ? 0.0 : samples_.back().t - samples_.front().t; }

private:
    std::vector<RecordedSample> samples_;
    std::size_t index_ = 0;
    DeviceState state_ = DeviceState::disconnected;
    DeviceFault fault_;
};

}  // namespace contactlab::drivers
