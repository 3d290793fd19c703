// The one exception type that carries a user-facing error out to main().
#pragma once

#include <stdexcept>
#include <string>

namespace rt {

// A scene, texture or output error. what() is the complete message, already prefixed with
// "file:line:col: " where the error has a place in a scene file. main() prints it and
// exits with status 1.
class Error : public std::runtime_error {
  public:
    using std::runtime_error::runtime_error;
};

}  // namespace rt
