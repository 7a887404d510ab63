// Bad user input: the one exception every room throws for it.
//
// Description
//     A file, a key or a value the user gave that cannot be used. The message
//     is one line that names the file or option, the key and the reason; the
//     CLI prints it as `armour: error: ...` and exits with status 2. Its own
//     header so that a room throwing it need not include geometry (mesh.h).
#pragma once

#include <stdexcept>

namespace armour {

struct InputError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

} // namespace armour
