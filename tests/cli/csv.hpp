// csv.hpp — a small, strict reader for the trace output CSV in the command-line tests (kept
// independent of engine/app/trace_csv so that a bug there cannot hide itself).
#pragma once

#include <cerrno>
#include <cstdlib>
#include <stdexcept>
#include <string>
#include <vector>

namespace cli_test {

struct Csv {
    std::string header;                         // the first line, as written
    std::vector<std::vector<std::string>> raw;  // the fields of each following line
    std::vector<std::vector<double>> rows;      // the same fields as numbers
};

inline std::vector<std::string> split_commas(const std::string& line) {
    std::vector<std::string> fields;
    std::size_t start = 0;
    for (;;) {
        const std::size_t comma = line.find(',', start);
        fields.push_back(line.substr(start, comma == std::string::npos ? std::string::npos : comma - start));
        if (comma == std::string::npos) return fields;
        start = comma + 1;
    }
}

// Every line must end with '\n'; every field must be a whole number text for strtod.
inline Csv parse_csv(const std::string& text) {
    Csv csv;
    std::size_t pos = 0, line_no = 0;
    while (pos < text.size()) {
        const std::size_t nl = text.find('\n', pos);
        if (nl == std::string::npos) throw std::runtime_error("line " + std::to_string(line_no + 1) + " has no newline");
        const std::string line = text.substr(pos, nl - pos);
        pos = nl + 1;
        ++line_no;
        if (line_no == 1) {
            csv.header = line;
            continue;
        }
        std::vector<std::string> fields = split_commas(line);
        std::vector<double> values;
        for (const std::string& f : fields) {
            if (f.empty()) throw std::runtime_error("line " + std::to_string(line_no) + ": empty field");
            errno = 0;
            char* end = nullptr;
            const double v = std::strtod(f.c_str(), &end);
            if (end != f.c_str() + f.size() || errno == ERANGE)
                throw std::runtime_error("line " + std::to_string(line_no) + ": not a number: " + f);
            values.push_back(v);
        }
        csv.raw.push_back(std::move(fields));
        csv.rows.push_back(std::move(values));
    }
    return csv;
}

// Column indices of the trace output `t,x,y,phi,proxy_x,proxy_y,contact,depth,fx,fy,l_d` (the
// contract) and the columns appended since: `stiction_x,stiction_y`.
enum Col { T, X, Y, PHI, PROXY_X, PROXY_Y, CONTACT, DEPTH, FX, FY, L_D, STICTION_X, STICTION_Y, NCOLS };

}  // namespace cli_test
