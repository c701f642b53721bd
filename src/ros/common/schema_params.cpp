#include "stocs_ros/common/schema_params.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <type_traits>

#include "stocs/util/error.h"

namespace stocs_ros {
namespace {

/// The value of `key` as T, or an InputError naming the parameter and the type it needs.
template <class T>
T typedParam(const ros::NodeHandle& pnh, const std::string& key, const char* type) {
  T value{};
  if (!pnh.getParam(key, value)) {
    throw stocs::InputError(fmt::format("parameter {} must be {}", pnh.resolveName(key), type));
  }
  return value;
}

void readChoice(const ros::NodeHandle& pnh, const stocs::ParamInfo& info,
                const stocs::ChoiceRef& choice) {
  const auto value = typedParam<std::string>(pnh, info.key, "a string");
  if (std::find(info.choices.begin(), info.choices.end(), value) == info.choices.end()) {
    throw stocs::InputError(fmt::format("parameter {} is '{}', not one of {}",
                                        pnh.resolveName(info.key), value,
                                        fmt::join(info.choices, ", ")));
  }
  choice.set(value);
}

}  // namespace

void requireSet(const ros::NodeHandle& pnh, const std::string& key, const std::string& value) {
  if (value.empty()) {
    throw stocs::InputError(fmt::format("parameter {} is not set", pnh.resolveName(key)));
  }
}

void readParam(const ros::NodeHandle& pnh, const stocs::ParamInfo& info,
               const stocs::ParamRef& field) {
  const std::string& key = info.key;
  if (!pnh.hasParam(key)) return;
  std::visit(
      [&](auto target) {
        using R = decltype(target);
        if constexpr (std::is_same_v<R, stocs::ChoiceRef>) {
          readChoice(pnh, info, target);
        } else {
          using T = std::remove_pointer_t<R>;
          if constexpr (std::is_same_v<T, bool>) {
            *target = typedParam<bool>(pnh, key, "true or false");
          } else if constexpr (std::is_floating_point_v<T>) {
            *target = static_cast<T>(typedParam<double>(pnh, key, "a number"));
          } else if constexpr (std::is_integral_v<T>) {
            *target = static_cast<T>(typedParam<int>(pnh, key, "an integer"));
          } else if constexpr (std::is_same_v<T, std::string>) {
            *target = typedParam<std::string>(pnh, key, "a string");
          } else if constexpr (std::is_same_v<T, std::vector<int>>) {
            *target = typedParam<T>(pnh, key, "a list of integers, such as [0, 3]");
          } else {
            *target = typedParam<T>(pnh, key, "a list of strings");
          }
        }
      },
      field);
}

}  // namespace stocs_ros
