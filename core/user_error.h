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

}  // namespace ddt
