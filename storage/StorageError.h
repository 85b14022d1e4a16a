#pragma once

#include <stdexcept>
#include <string>

namespace driftlab {

// Any failure of the session store: the message names the database and what failed.
class StorageError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

} // namespace driftlab
