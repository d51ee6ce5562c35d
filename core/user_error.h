// A failure the user can act on: bad input, an unwritable output, an unusable device.
// Its message is one line naming the thing and the reason; the CLI prints it and exits 1.
#pragma once

#include <stdexcept>
#include <string>

namespace ddt {

class UserError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

// The device (or host) ran out of memory in a backend's prepare, optimize or render. The
// backend stays usable: the next prepare starts afresh. A UserError, so that where nobody
// retries with smaller tiles (app/tiled_upscale.h) it still reaches the user as one line.
class DeviceOutOfMemory : public UserError {
public:
    using UserError::UserError;
};

// A UserError met while decoding an input's rows as its tiles need them, after the job began:
// its message names the input already, so callers that prefix the name pass it on as it is.
class InputError : public UserError {
public:
    using UserError::UserError;
};

}  // namespace ddt
