#include <fmt/format.h>
#include <fmt/ranges.h>

#include <functional>
#include <map>
#include <utility>

#include "baseline_methods.h"
#include "stocs/methods/pose_method.h"
#include "stocs/methods/stocs_methods.h"
#include "stocs/util/error.h"

namespace stocs {
namespace {

/// The methods of this library; registerMethod() adds those of libraries it does not link.
std::map<std::string, MethodFactory>& registry() {
  static std::map<std::string, MethodFactory> methods = {
      {"fpcs", makeFpcsMethod},
      {"kfpcs", makeKfpcsMethod},
      {"ppf", makePpfMethod},
      {"stocs", [](const MethodOptions&) { return std::make_unique<StocsMethod>(); }},
      {"stocs-hard",
       [](const MethodOptions& o) {
         return std::make_unique<HardSegmentStocsMethod>(o.hard_threshold);
       }},
  };
  return methods;
}

}  // namespace

void registerMethod(const std::string& name, MethodFactory factory) {
  registry()[name] = std::move(factory);
}

std::vector<std::string> methodNames() {
  std::vector<std::string> names;
  for (const auto& [name, factory] : registry()) names.push_back(name);
  return names;
}

std::unique_ptr<PoseMethod> makeMethod(const std::string& name, const MethodOptions& options) {
  const auto it = registry().find(name);
  if (it == registry().end()) {
    throw InputError(fmt::format("unknown method '{}'; known methods: {}", name,
                                 fmt::join(methodNames(), ", ")));
  }
  if (!(options.hard_threshold > 0.0f && options.hard_threshold < 1.0f)) {
    throw InputError(
        fmt::format("hard segmentation threshold {} is outside (0, 1)", options.hard_threshold));
  }
  return it->second(options);
}

}  // namespace stocs
