// device_file.hpp — what a user declares about a real device that the device cannot say itself:
// a small JSON file given with --device-file. Today: the effective mass at the finger, which the
// passivity controller needs ("passivity": "control") and which the Novint Falcon, the Haply 2DIY
// and version 1 hapio boards do not report.
//   {"effective_mass_kg": 0.12, "source": "measured: 0.5 N steps, encoder acceleration"}
// Strict: unknown keys, a missing or non-positive mass are errors naming the file and the field.
#pragma once

#include <stdexcept>
#include <string>

namespace contactlab::drivers {

struct DeviceFile {
    double effective_mass = 0.0;  // kg, lightest effective mass at the finger (> 0)
    std::string source;           // how it was obtained (free text, for the results' provenance)
};

struct DeviceFileError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

// Reads and checks `path`; throws DeviceFileError("PATH: what is wrong") otherwise.
DeviceFile read_device_file(const std::string& path);
DeviceFile parse_device_file(const std::string& text, const std::string& origin);

}  // namespace contactlab::drivers
