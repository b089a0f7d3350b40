// device.cpp — names of device states.
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

}  // namespace contactlab::drivers
