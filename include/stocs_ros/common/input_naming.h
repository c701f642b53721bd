#pragma once
// Errors of a conversion named after the input at fault ("cloud: ...", "boxes: ..."): the node
// counts rejected frames by that name (NodeStatistics).

#include <fmt/format.h>

#include <string>

#include "stocs/util/error.h"

namespace stocs_ros {

/// Runs `convert`, prefixing the message of any InputError with `what`.
template <class Convert>
auto naming(const std::string& what, Convert&& convert) {
  try {
    return convert();
  } catch (const stocs::InputError& e) {
    throw stocs::InputError(fmt::format("{}: {}", what, e.what()));
  }
}

}  // namespace stocs_ros
