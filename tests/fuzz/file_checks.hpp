// file_checks.hpp — the properties the experiment-file fuzz targets check (built where the
// experiments libraries are: not in the haptics-only configuration). For any bytes, a protocol
// file and a results CSV either read or are refused with ExperimentError naming the file
// ("ORIGIN: ..."); nothing else may escape, and nothing may crash or read out of bounds.
#pragma once

#include "engine/experiments/base/results_table.hpp"
#include "engine/experiments/protocol/protocol.hpp"

#include <exception>
#include <string>
#include <string_view>

namespace contactlab::fuzz {

template <class Parse>
std::string check_refusal_style(Parse parse, const char* what) {
    const std::string origin = "fuzz-input";
    try {
        parse(origin);
    } catch (const experiments::ExperimentError& e) {
        const std::string msg = e.what();
        if (msg.rfind(origin, 0) != 0) return std::string(what) + ": ExperimentError does not name the file: " + msg;
    } catch (const std::exception& e) {
        return std::string(what) + " threw something other than ExperimentError: " + e.what();
    } catch (...) {
        return std::string(what) + " threw a non-std::exception";
    }
    return {};
}

inline std::string check_protocol_input(std::string_view bytes) {
    const std::string text(bytes);
    return check_refusal_style([&](const std::string& origin) { experiments::parse_protocol(text, origin); },
                               "parse_protocol");
}

inline std::string check_results_input(std::string_view bytes) {
    const std::string text(bytes);
    return check_refusal_style(
        [&](const std::string& origin) {
            const experiments::ResultsTable t = experiments::parse_results_csv(text, origin);
            // Every cell the reader hands out is addressable by its row's line.
            for (std::size_t r = 0; r < t.rows.size(); ++r) (void)t.where(r);
        },
        "parse_results_csv");
}

}  // namespace contactlab::fuzz
