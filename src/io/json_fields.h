#pragma once
// Typed fields of the entries of the project's JSON inputs, each error naming the entry.

#include <string>

#include <nlohmann/json.hpp>

namespace stocs {

/// The value of `key` in an entry (`where` names it): an integer of at least `min`. Throws
/// InputError when it is missing or is not such an integer.
int integerAtLeast(const nlohmann::json& entry, const char* key, int min, const std::string& where);

}  // namespace stocs
