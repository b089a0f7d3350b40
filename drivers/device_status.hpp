// device_status.hpp — a device's state and fault, shared lock-free between its I/O thread, the
// servo thread and the UI.
//
// Why one struct: the hapio board, the Falcon and the 2DIY each held the same three atomics and
// wrote the same fault(), set_fault() and engage logic (the fault's detail stored before its code,
// the code before the state, so a reader that sees DeviceState::fault sees its code and detail).
#pragma once

#include "drivers/device.hpp"

#include <atomic>

namespace contactlab::drivers {

struct DeviceStatus {
    std::atomic<DeviceState> state{DeviceState::disconnected};
    std::atomic<DeviceFaultCode> code{DeviceFaultCode::none};
    std::atomic<const char*> detail{""};  // a string literal: never freed

    DeviceState get() const noexcept { return state.load(std::memory_order_acquire); }
    DeviceFault fault() const noexcept {
        return {code.load(std::memory_order_acquire), detail.load(std::memory_order_acquire)};
    }
    // Faulted with `code` and `detail` (a string literal).
    void set_fault(DeviceFaultCode fault_code, const char* fault_detail) noexcept {
        detail.store(fault_detail, std::memory_order_release);
        code.store(fault_code, std::memory_order_release);
        state.store(DeviceState::fault, std::memory_order_release);
    }
    // No fault, in state `to`.
    void clear(DeviceState to) noexcept {
        code.store(DeviceFaultCode::none, std::memory_order_release);
        detail.store("", std::memory_order_release);
        state.store(to, std::memory_order_release);
    }
    // Whether the device's last sample may be read: not while disconnected or opening, nor
    // unplugged (faulted as disconnected: the last frame describes a device that is gone).
    bool readable() const noexcept {
        const DeviceState st = get();
        if (st == DeviceState::disconnected || st == DeviceState::opening) return false;
        return !(st == DeviceState::fault && code.load(std::memory_order_acquire) == DeviceFaultCode::disconnected);
    }
    // ready <-> engaged; a device in any other state (opening, fault, disconnected) stays there.
    void engage(bool on) noexcept {
        DeviceState expect = on ? DeviceState::ready : DeviceState::engaged;
        state.compare_exchange_strong(expect, on ? DeviceState::engaged : DeviceState::ready, std::memory_order_acq_rel);
    }
};

}  // namespace contactlab::drivers
