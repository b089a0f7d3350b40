// finger_samples_csv.cpp — the `t,x,y,phi` reader (finger_samples_csv.hpp).
#include "haptics/finger_samples_csv.hpp"

#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <istream>

namespace contactlab {
namespace {

constexpr const char* kColumns[4] = {"t", "x", "y", "phi"};

std::string where(const std::string& origin, std::size_t line) {
    return origin + ":" + std::to_string(line);
}

// Parses one field (already split at commas, surrounding spaces allowed) as a finite double.
double parse_field(std::string_view field, const std::string& origin, std::size_t line, int column) {
    while (!field.empty() && (field.front() == ' ' || field.front() == '\t')) field.remove_prefix(1);
    while (!field.empty() && (field.back() == ' ' || field.back() == '\t')) field.remove_suffix(1);
    const std::string col = " (column " + std::to_string(column + 1) + ", " + kColumns[column] + ")";
    if (field.empty()) throw CsvError(where(origin, line) + col + ": empty field");
    double v = 0.0;
    const char* first = field.data();
    if (*first == '+') ++first;  // from_chars does not take a leading '+'
    const auto [ptr, ec] = std::from_chars(first, field.data() + field.size(), v);
    if (ec == std::errc::result_out_of_range)
        throw CsvError(where(origin, line) + col + ": number out of range: \"" + std::string(field) + "\"");
    if (ec != std::errc() || ptr != field.data() + field.size())
        throw CsvError(where(origin, line) + col + ": not a number: \"" + std::string(field) + "\"");
    if (!std::isfinite(v))
        throw CsvError(where(origin, line) + col + ": not a finite number: \"" + std::string(field) + "\"");
    return v;
}

}  // namespace

std::string exact(double v) {
    char buf[32];
    const auto [ptr, ec] = std::to_chars(buf, buf + sizeof buf, v);
    return ec == std::errc() ? std::string(buf, ptr) : std::string("?");
}

std::vector<FingerSample> read_finger_samples(std::istream& in, const std::string& origin) {
    std::vector<FingerSample> samples;
    std::string text;
    std::size_t line = 0;
    bool have_header = false;
    while (std::getline(in, text)) {
        ++line;
        if (!text.empty() && text.back() == '\r') text.pop_back();  // files saved on Windows
        if (text.find('\0') != std::string::npos)
            throw CsvError(where(origin, line) + ": binary data (NUL byte) in a text file");
        if (!have_header) {
            if (line == 1 && text.size() >= 3 && text.compare(0, 3, "\xEF\xBB\xBF") == 0) text.erase(0, 3);
            std::string compact;
            for (char c : text)
                if (c != ' ' && c != '\t') compact += c;
            if (compact != kFingerSamplesHeader)
                throw CsvError(where(origin, line) + ": expected the header \"" + kFingerSamplesHeader +
                               "\", found \"" + text.substr(0, 80) + "\"");
            have_header = true;
            continue;
        }
        if (text.find_first_not_of(" \t") == std::string::npos) continue;  // blank line
        std::string_view rest(text);
        double values[4];
        for (int c = 0; c < 4; ++c) {
            const std::size_t comma = rest.find(',');
            if (c < 3 && comma == std::string_view::npos)
                throw CsvError(where(origin, line) + ": expected 4 fields (t,x,y,phi), found " +
                               std::to_string(c + 1));
            if (c == 3 && comma != std::string_view::npos)
                throw CsvError(where(origin, line) + ": expected 4 fields (t,x,y,phi), found more");
            values[c] = parse_field(rest.substr(0, comma), origin, line, c);
            if (comma != std::string_view::npos) rest.remove_prefix(comma + 1);
        }
        const FingerSample s{values[0], {values[1], values[2]}, values[3]};
        if (!samples.empty() && !(s.t > samples.back().t))
            throw CsvError(where(origin, line) + " (column 1, t): time " + exact(s.t) +
                           " s does not increase (previous " + exact(samples.back().t) + " s)");
        samples.push_back(s);
    }
    if (in.bad()) throw CsvError(origin + ": read error");
    if (!have_header) throw CsvError(origin + ":1: empty file (expected the header \"" + std::string(kFingerSamplesHeader) + "\")");
    return samples;
}

std::vector<FingerSample> read_finger_samples_file(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw CsvError(path + ": cannot open (" + std::strerror(errno) + ")");
    return read_finger_samples(in, path);
}

}  // namespace contactlab
