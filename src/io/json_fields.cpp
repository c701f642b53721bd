#include "json_fields.h"

#include <fmt/format.h>

#include <limits>

#include "stocs/util/error.h"

namespace stocs {

int integerAtLeast(const nlohmann::json& entry, const char* key, int min,
                   const std::string& where) {
  if (!entry.contains(key)) throw InputError(fmt::format("{}: missing key '{}'", where, key));
  const nlohmann::json& v = entry.at(key);
  // Every JSON integer converts to double closely enough for a range check.
  if (!v.is_number_integer() || v.get<double>() < min ||
      v.get<double>() > std::numeric_limits<int>::max()) {
    throw InputError(fmt::format("{}: '{}' is {}; it must be an integer of at least {}", where, key,
                                 v.dump(), min));
  }
  return v.get<int>();
}

}  // namespace stocs
