// replay_device.cpp — recording reader and playback device.
#include "drivers/replay_device.hpp"
#include "drivers/record_writer.hpp"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <fstream>

namespace contactlab::drivers {

std::vector<RecordedSample> read_recording_file(const std::string& path) {
    std::ifstream in(path);
    if (!in) throw RecordingError(path + ": cannot open");
    std::string line;
    if (!std::getline(in, line) || line != kRecordingHeader)
        throw RecordingError(path + ":1: not a contactlab recording (expected the header " +
                             std::string(kRecordingHeader) + ")");
    std::vector<RecordedSample> out;
    int line_no = 1;
    while (std::getline(in, line)) {
        ++line_no;
        if (line.empty()) continue;
        double v[5];
        const char* p = line.c_str();
        for (int c = 0; c < 5; ++c) {
            char* end = nullptr;
            errno = 0;
            v[c] = std::strtod(p, &end);
            if (end == p || (*end != ',' && *end != '\0') || errno == ERANGE)
                throw RecordingError(path + ":" + std::to_string(line_no) + " (column " + std::to_string(c + 1) +
                                     "): not a number");
            p = *end == ',' ? end + 1 : end;
        }
        out.push_back({v[0], {v[1], v[2]}, v[3], v[4]});
    }
    if (out.empty()) throw RecordingError(path + ": no samples");
    return out;
}

DeviceCapabilities ReplayDevice::capabilities() const noexcept {
    DeviceCapabilities c;
    c.finger_angle = true;
    c.roller = true;
    c.simulated = true;
    return c;
}

bool ReplayDevice::open() {
    index_ = 0;
    if (samples_.empty()) {
        state_ = DeviceState::fault;
        fault_ = {DeviceFaultCode::end_of_data, "empty recording"};
        return false;
    }
    state_ = DeviceState::ready;
    fault_ = {};
    return true;
}

void ReplayDevice::set_engaged(bool on) noexcept {
    if (state_ == DeviceState::ready && on) state_ = DeviceState::engaged;
    else if (state_ == DeviceState::engaged && !on) state_ = DeviceState::ready;
}

bool ReplayDevice::read(DeviceReading& out) noexcept {
    out = DeviceReading{};
    if (samples_.empty() || state_ == DeviceState::disconnected) return false;
    const RecordedSample& s = samples_[index_];
    out.t = s.t;
    out.finger = s.finger;
    out.phi = s.phi;
    out.roller_l = s.roller_l;
    out.valid = true;
    return true;
}

void ReplayDevice::advance(double) noexcept {
    if (index_ + 1 < samples_.size()) {
        ++index_;
    } else if (state_ != DeviceState::fault) {
        fault_ = {DeviceFaultCode::end_of_data, "end of recording"};
    }
}

}  // namespace contactlab::drivers
