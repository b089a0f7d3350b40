// device.cpp — names of device states and fault codes.
#include "drivers/device.hpp"

namespace contactlab::drivers {

const char* to_string(DeviceState s) noexcept {
    switch (s) {
        case DeviceState::disconnected: return "disconnected";
        case DeviceState::opening: return "opening";
        case DeviceState::ready: return "ready";
        case DeviceState::engaged: return "engaged";
        case DeviceState::fault: return "fault";
    }
    return "?";
}

const char* to_string(DeviceFaultCode c) noexcept {
    switch (c) {
        case DeviceFaultCode::none: return "none";
        case DeviceFaultCode::not_found: return "not found";
        case DeviceFaultCode::open_failed: return "open failed";
        case DeviceFaultCode::io_error: return "I/O error";
        case DeviceFaultCode::timeout: return "timeout";
        case DeviceFaultCode::watchdog: return "watchdog";
        case DeviceFaultCode::non_finite_command: return "non-finite command";
        case DeviceFaultCode::over_limit: return "over limit";
        case DeviceFaultCode::end_of_data: return "end of data";
        case DeviceFaultCode::disconnected: return "disconnected";
        case DeviceFaultCode::permission_denied: return "permission denied";
    }
    return "?";
}

}  // namespace contactlab::drivers
