#include "stocs/util/param_set.h"

#include <fmt/format.h>

#include <algorithm>

#include "stocs/util/error.h"

namespace stocs {

bool ParamRange::contains(double v, bool in_float) const {
  const auto as = [in_float](double x) { return in_float ? double(static_cast<float>(x)) : x; };
  if (also && v == as(*also)) return true;
  const bool above = lo_open ? v > as(lo) : v >= as(lo);
  const bool below = hi_open ? v < as(hi) : v <= as(hi);
  return above && below;  // false for NaN
}

std::string ParamRange::str() const {
  const std::string interval =
      fmt::format("{}{}, {}{}", lo_open ? "(" : "[", lo, hi, hi_open ? ")" : "]");
  return also ? fmt::format("{} or {}", *also, interval) : interval;
}

std::string ParamInfo::cliFlag() const {
  if (!flag.empty()) return flag;
  std::string name = "--" + key;
  std::replace(name.begin(), name.end(), '.', '-');
  std::replace(name.begin(), name.end(), '_', '-');
  return name;
}

namespace {

/// The value as a number for the range check, or nothing for flags and strings.
std::optional<double> numeric(const ParamRef& value) {
  return std::visit(
      [](const auto& v) -> std::optional<double> {
        using T = std::decay_t<decltype(v)>;
        if constexpr (std::is_same_v<T, bool*> || std::is_same_v<T, std::string*> ||
                      std::is_same_v<T, std::vector<std::string>*> ||
                      std::is_same_v<T, std::vector<int>*> || std::is_same_v<T, ChoiceRef>) {
          return std::nullopt;
        } else {
          return static_cast<double>(*v);
        }
      },
      value);
}

}  // namespace

std::string paramText(const ParamRef& value) {
  return std::visit(
      [](const auto& v) -> std::string {
        using T = std::decay_t<decltype(v)>;
        if constexpr (std::is_same_v<T, ChoiceRef>) {
          return v.get();
        } else if constexpr (std::is_same_v<T, std::vector<std::string>*> ||
                             std::is_same_v<T, std::vector<int>*>) {
          return fmt::format("[{}]", fmt::join(*v, ", "));
        } else {
          return fmt::format("{}", *v);
        }
      },
      value);
}

std::optional<std::string> ParamInfo::problem(const ParamRef& value) const {
  const std::string shown = unit.empty() ? paramText(value) : paramText(value) + " " + unit;
  const std::optional<double> number = numeric(value);
  if (range && number && !range->contains(*number, std::holds_alternative<float*>(value))) {
    return fmt::format("{} is outside {}", shown, range->str());
  }
  if (!choices.empty() &&
      std::find(choices.begin(), choices.end(), paramText(value)) == choices.end()) {
    return fmt::format("'{}' is not one of {}", paramText(value), fmt::join(choices, ", "));
  }
  return std::nullopt;
}

void throwParamProblem(const std::string& name, const std::optional<std::string>& problem) {
  if (problem) throw InputError(fmt::format("{} {}", name, *problem));
}

}  // namespace stocs
