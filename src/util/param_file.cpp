#include "stocs/util/param_file.h"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <type_traits>

#include "stocs/util/error.h"

namespace stocs {
namespace {

/// Sets fields from one file's map, each error naming the file, the line and the key.
class FieldReader {
 public:
  explicit FieldReader(const std::filesystem::path& file) : file_(file) {}

  [[noreturn]] void fail(const YAML::Node& n, const std::string& key,
                         const std::string& problem) const {
    throw InputError(fmt::format("{}:{}: {}: {}", file_.string(), n.Mark().line + 1, key, problem));
  }

  void assign(const YAML::Node& n, const ParamField& f) const {
    std::visit([&](auto target) { assignTo(n, f.info, target); }, f.field);
    if (auto problem = f.info.problem(f.field)) fail(n, f.info.key, *problem);
  }

 private:
  template <class T>
  T scalar(const YAML::Node& n, const std::string& key, const char* type) const {
    if (!n.IsScalar()) fail(n, key, fmt::format("expected {}", type));
    try {
      return n.as<T>();
    } catch (const YAML::Exception&) {
      fail(n, key, fmt::format("expected {}, got '{}'", type, n.Scalar()));
    }
  }

  template <class T>
  void assignTo(const YAML::Node& n, const ParamInfo& info, T* target) const {
    if constexpr (std::is_same_v<T, bool>) {
      *target = scalar<bool>(n, info.key, "true or false");
    } else if constexpr (std::is_floating_point_v<T>) {
      *target = static_cast<T>(scalar<double>(n, info.key, "a number"));
    } else if constexpr (std::is_integral_v<T>) {
      *target = scalar<T>(n, info.key, "an integer");
    } else {
      *target = scalar<std::string>(n, info.key, "a string");
    }
  }

  void assignTo(const YAML::Node& n, const ParamInfo& info,
                std::vector<std::string>* target) const {
    if (!n.IsSequence()) fail(n, info.key, "expected a list");
    target->clear();
    for (size_t k = 0; k < n.size(); ++k) {
      target->push_back(scalar<std::string>(n[k], fmt::format("{}[{}]", info.key, k), "a string"));
    }
  }

  void assignTo(const YAML::Node& n, const ParamInfo& info, const ChoiceRef& target) const {
    const auto value = scalar<std::string>(n, info.key, "a string");
    if (std::find(info.choices.begin(), info.choices.end(), value) == info.choices.end()) {
      fail(n, info.key, fmt::format("'{}' is not one of {}", value, fmt::join(info.choices, ", ")));
    }
    target.set(value);
  }

  std::filesystem::path file_;
};

YAML::Node loadMap(const std::filesystem::path& file) {
  YAML::Node root;
  try {
    root = YAML::LoadFile(file.string());
  } catch (const YAML::BadFile&) {
    throw InputError(fmt::format("{}: cannot read the file", file.string()));
  } catch (const YAML::Exception& e) {
    throw InputError(fmt::format("{}: invalid YAML: {}", file.string(), e.what()));
  }
  if (!root.IsMap()) throw InputError(fmt::format("{}: expected a map of keys", file.string()));
  return root;
}

}  // namespace

void readParamFields(const std::filesystem::path& file, const std::vector<ParamField>& fields) {
  const FieldReader reader(file);
  for (const auto& entry : loadMap(file)) {
    if (!entry.first.IsScalar()) reader.fail(entry.first, "?", "expected a key, not a list or map");
    const std::string key = entry.first.Scalar();
    const auto field = std::find_if(fields.begin(), fields.end(),
                                    [&key](const ParamField& f) { return f.info.key == key; });
    if (field == fields.end()) reader.fail(entry.first, key, "unknown key");
    reader.assign(entry.second, *field);
  }
}

}  // namespace stocs
