// path_name.hpp — names that become parts of file names: a protocol's condition names (the
// traces' PARTICIPANT-CONDITION-TRIAL.csv) and a live participant's id (the editor's default
// results file PROTOCOL-ID.csv). Checked where they are read (the protocol file, the command
// line), so that a name never reaches a path: not empty, no '/' or '\', no "..", no control
// character.
//
// Room engine/experiments/base/ (results_table.hpp says what the room holds).
#pragma once

#include <string>

namespace contactlab::experiments {

// "" when `name` may be part of a file name; otherwise why not, e.g. "must not hold '/'".
std::string path_name_problem(const std::string& name);

// `name` for a message: control characters written \xNN, the rest as given.
std::string escaped_name(const std::string& name);

}  // namespace contactlab::experiments
