// usb_status.cpp — libusb status -> DeviceFault (see usb_status.hpp).
#include "drivers/usb/usb_status.hpp"

#include <libusb.h>

namespace contactlab::drivers::usb {

DeviceFault fault_of_error(int e) noexcept {
    switch (e) {
        case LIBUSB_SUCCESS: return {};
        case LIBUSB_ERROR_ACCESS: return {DeviceFaultCode::permission_denied, kUdevHint};
        case LIBUSB_ERROR_NO_DEVICE: return {DeviceFaultCode::disconnected, "USB device disconnected"};
        case LIBUSB_ERROR_NOT_FOUND: return {DeviceFaultCode::not_found, "USB device or interface not found"};
        case LIBUSB_ERROR_BUSY:
            return {DeviceFaultCode::open_failed,
                    "USB interface busy: another program (or a kernel driver that could not be detached) holds it"};
        case LIBUSB_ERROR_TIMEOUT: return {DeviceFaultCode::timeout, "USB transfer timed out"};
        case LIBUSB_ERROR_PIPE: return {DeviceFaultCode::io_error, "USB endpoint stalled (request refused by the device)"};
        case LIBUSB_ERROR_OVERFLOW: return {DeviceFaultCode::io_error, "USB device sent more data than requested"};
        case LIBUSB_ERROR_IO: return {DeviceFaultCode::io_error, "USB I/O error"};
        case LIBUSB_ERROR_INVALID_PARAM: return {DeviceFaultCode::io_error, "USB call with an invalid parameter (driver bug)"};
        case LIBUSB_ERROR_INTERRUPTED: return {DeviceFaultCode::io_error, "USB call interrupted"};
        case LIBUSB_ERROR_NO_MEM: return {DeviceFaultCode::io_error, "out of memory in libusb"};
        case LIBUSB_ERROR_NOT_SUPPORTED: return {DeviceFaultCode::open_failed, "operation not supported by this USB backend"};
        default: return {DeviceFaultCode::io_error, "USB error (other)"};
    }
}

DeviceFault fault_of_transfer(int s) noexcept {
    switch (s) {
        case LIBUSB_TRANSFER_COMPLETED: return {};
        case LIBUSB_TRANSFER_TIMED_OUT: return {DeviceFaultCode::timeout, "USB transfer timed out (device stopped answering)"};
        case LIBUSB_TRANSFER_STALL: return {DeviceFaultCode::io_error, "USB endpoint stalled"};
        case LIBUSB_TRANSFER_NO_DEVICE: return {DeviceFaultCode::disconnected, "USB device disconnected"};
        case LIBUSB_TRANSFER_OVERFLOW: return {DeviceFaultCode::io_error, "USB device sent more data than requested"};
        case LIBUSB_TRANSFER_CANCELLED: return {DeviceFaultCode::io_error, "USB transfer cancelled"};
        case LIBUSB_TRANSFER_ERROR:
        default: return {DeviceFaultCode::io_error, "USB transfer failed"};
    }
}

const char* error_name(int e) noexcept { return libusb_error_name(e); }

}  // namespace contactlab::drivers::usb
