// device_file.cpp — the user's declarations about a device (see device_file.hpp).
#include "drivers/usb/device_file.hpp"

#include <nlohmann/json.hpp>

#include <cmath>
#include <fstream>
#include <sstream>

namespace contactlab::drivers {

namespace {
// kg: a hand-held haptic device's moving parts; more is a unit mistake (grams for kilograms).
constexpr double kMaxMass = 10.0;
}  // namespace

DeviceFile parse_device_file(const std::string& text, const std::string& origin) {
    nlohmann::json j;
    try {
        j = nlohmann::json::parse(text);
    } catch (const nlohmann::json::parse_error& e) {
        throw DeviceFileError(origin + ": not JSON (byte " + std::to_string(e.byte) + ")");
    }
    if (!j.is_object()) throw DeviceFileError(origin + ": must be a JSON object such as {\"effective_mass_kg\": 0.12}");
    for (auto it = j.begin(); it != j.end(); ++it)
        if (it.key() != "effective_mass_kg" && it.key() != "source")
            throw DeviceFileError(origin + ": unknown key \"" + it.key() + "\" (effective_mass_kg, source)");
    DeviceFile f;
    const auto m = j.find("effective_mass_kg");
    if (m == j.end()) throw DeviceFileError(origin + ": effective_mass_kg is missing (the device's effective mass, kg)");
    if (!m->is_number()) throw DeviceFileError(origin + ": effective_mass_kg must be a number (kg)");
    f.effective_mass = m->get<double>();
    if (!std::isfinite(f.effective_mass) || !(f.effective_mass > 0.0) || f.effective_mass > kMaxMass)
        throw DeviceFileError(origin + ": effective_mass_kg must lie in (0, 10] kg, got " + m->dump());
    if (const auto s = j.find("source"); s != j.end()) {
        if (!s->is_string()) throw DeviceFileError(origin + ": source must be a string");
        f.source = s->get<std::string>();
    }
    return f;
}

DeviceFile read_device_file(const std::string& path) {
    std::ifstream in(path);
    if (!in) throw DeviceFileError(path + ": cannot read the device file");
    std::ostringstream s;
    s << in.rdbuf();
    return parse_device_file(s.str(), path);
}

}  // namespace contactlab::drivers
