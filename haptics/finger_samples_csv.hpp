// finger_samples_csv.hpp — reading finger paths: CSV with the header `t,x,y,phi`.
//
// One sample per line: time (s), finger centre x_f (m), finger angle phi (rad); times strictly
// increase. The same file feeds `contactlab trace` (one proxy tick per row) and the scripted hand
// of `contactlab simulate` (a path interpolated in time). Bad input is a CsvError naming the file,
// the line and the column.
#pragma once

#include "haptics/vec2.hpp"

#include <iosfwd>
#include <stdexcept>
#include <string>
#include <vector>

namespace contactlab {

struct CsvError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

struct FingerSample {
    double t = 0.0;    // s
    Vec2 x{0.0};       // m
    double phi = 0.0;  // rad
};

inline constexpr const char* kFingerSamplesHeader = "t,x,y,phi";

// Shortest text that reads back to the same double, for messages (std::to_string prints 1e-7
// as "0.000000").
std::string exact(double v);

// Reads samples from `in`; `origin` (the file name) prefixes error messages.
std::vector<FingerSample> read_finger_samples(std::istream& in, const std::string& origin);
std::vector<FingerSample> read_finger_samples_file(const std::string& path);

}  // namespace contactlab
