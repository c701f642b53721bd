#pragma once
// Errors the core reports for bad input. Callers (CLI, ROS node) turn them into messages or exit
// codes; the core never prints or exits itself.

#include <stdexcept>
#include <string>

namespace stocs {

/// Malformed or inconsistent input: a file, an image, a cloud or a parameter value. The message
/// names the offending item and the problem.
class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace stocs
