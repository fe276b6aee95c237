// Errors that end a command with a one-line message. `UsageError` (bad flags or values) exits with 2,
// `Error` (bad input files, no device, Vulkan failures) exits with 1. Nothing else is thrown on purpose.
#pragma once

#include <stdexcept>
#include <string>

namespace vct {

struct Error : std::runtime_error {
    using std::runtime_error::runtime_error;
};

struct UsageError : Error {
    using Error::Error;
};

}  // namespace vct
