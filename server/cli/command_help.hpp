#pragma once
// `lienewton COMMAND --help`: the fields a command takes, each as its flag with its type, default and bounds or
// values, read from the request contract (core/fields.hpp), so the help cannot disagree with what the codec takes.
#include <string>
#include <vector>

#include "core/fields.hpp"

namespace lienewton::cli {

// The help of `lienewton <command>` (e.g. "solve", "render frames") whose fields are `fields`, in their order.
std::string command_help(const std::string& command, const std::vector<const fields::Field*>& fields);

}  // namespace lienewton::cli
