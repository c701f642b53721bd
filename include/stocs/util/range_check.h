#pragma once
// Parameter range checks that name the parameter, for the validate() of parameter structs.

#include <fmt/format.h>

#include "stocs/util/error.h"

namespace stocs {

/// Throws InputError "<context>: <name> = <value> is outside [lo, hi]" unless lo <= value <= hi
/// (NaN is outside every range).
inline void checkRange(const char* context, const char* name, double value, double lo, double hi) {
  if (!(value >= lo && value <= hi)) {
    throw InputError(fmt::format("{}: {} = {} is outside [{}, {}]", context, name, value, lo, hi));
  }
}

}  // namespace stocs
