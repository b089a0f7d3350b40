// hapio_counters.hpp — HapioDevice's counters: written by the event thread, read by anyone.
#pragma once

#include "drivers/usb/hapio_device.hpp"

#include <atomic>

namespace contactlab::drivers::hapio {

struct HapioDevice::Counters {
    std::atomic<std::uint64_t> frames{0}, commands{0};
    std::atomic<std::uint64_t> short_frames{0}, bad_magic{0}, bad_version{0}, bad_crc{0}, bad_counts{0};
    std::atomic<std::uint64_t> sequence_gaps{0}, timeouts{0}, stalls{0}, transfer_errors{0};
    std::atomic<std::uint64_t> disconnects{0}, reconnects{0};
    std::atomic<std::uint64_t> rtt_count{0};
    std::atomic<double> rtt_min{0.0}, rtt_max{0.0}, rtt_sum{0.0};
    std::atomic<std::uint16_t> board_rejected{0};
    std::atomic<std::uint64_t> faults{0};
};

}  // namespace contactlab::drivers::hapio
