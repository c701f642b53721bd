#include "stocs/util/param_file.h"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cstdint>
#include <type_traits>

#include "stocs/util/error.h"

namespace stocs {
namespace {

template <class T>
const char* expectedType() {
  if constexpr (std::is_same_v<T, bool>) {
    return "true or false";
  } else if constexpr (std::is_integral_v<T>) {
    return "an integer";
  } else if constexpr (std::is_floating_point_v<T>) {
    return "a number";
  } else {
    return "a string";
  }
}

template <class T>
void assignTo(const std::filesystem::path& file, const YAML::Node& n, const std::string& key,
              const ParamInfo&, T* target) {
  *target = readYamlScalar<T>(file, n, key);
}

template <class T>
void assignTo(const std::filesystem::path& file, const YAML::Node& n, const std::string& key,
              const ParamInfo&, std::vector<T>* target) {
  if (!n.IsSequence()) failAtYamlNode(file, n, key, "expected a list");
  target->clear();
  for (size_t k = 0; k < n.size(); ++k) {
    target->push_back(readYamlScalar<T>(file, n[k], fmt::format("{}[{}]", key, k)));
  }
}

void assignTo(const std::filesystem::path& file, const YAML::Node& n, const std::string& key,
              const ParamInfo& info, const ChoiceRef& target) {
  const auto value = readYamlScalar<std::string>(file, n, key);
  if (std::find(info.choices.begin(), info.choices.end(), value) == info.choices.end()) {
    failAtYamlNode(file, n, key,
                   fmt::format("'{}' is not one of {}", value, fmt::join(info.choices, ", ")));
  }
  target.set(value);
}

YAML::Node loadMap(const std::filesystem::path& file) {
  const YAML::Node root = loadYamlFile(file, "cannot read the file");
  if (!root.IsMap()) throw InputError(fmt::format("{}: expected a map of keys", file.string()));
  return root;
}

}  // namespace

YAML::Node loadYamlFile(const std::filesystem::path& file, const char* unreadable) {
  try {
    return YAML::LoadFile(file.string());
  } catch (const YAML::BadFile&) {
    throw InputError(fmt::format("{}: {}", file.string(), unreadable));
  } catch (const YAML::Exception& e) {
    throw InputError(fmt::format("{}: invalid YAML: {}", file.string(), e.what()));
  }
}

void failAtYamlNode(const std::filesystem::path& file, const YAML::Node& n, const std::string& key,
                    const std::string& problem) {
  throw InputError(fmt::format("{}:{}: {}: {}", file.string(), n.Mark().line + 1, key, problem));
}

template <class T>
T readYamlScalar(const std::filesystem::path& file, const YAML::Node& n, const std::string& key) {
  if (!n.IsScalar()) failAtYamlNode(file, n, key, fmt::format("expected {}", expectedType<T>()));
  try {
    return n.as<T>();
  } catch (const YAML::Exception&) {
    failAtYamlNode(file, n, key,
                   fmt::format("expected {}, got '{}'", expectedType<T>(), n.Scalar()));
  }
}

template bool readYamlScalar<bool>(const std::filesystem::path&, const YAML::Node&,
                                   const std::string&);
template int readYamlScalar<int>(const std::filesystem::path&, const YAML::Node&,
                                 const std::string&);
template float readYamlScalar<float>(const std::filesystem::path&, const YAML::Node&,
                                     const std::string&);
template double readYamlScalar<double>(const std::filesystem::path&, const YAML::Node&,
                                       const std::string&);
template uint64_t readYamlScalar<uint64_t>(const std::filesystem::path&, const YAML::Node&,
                                           const std::string&);
template std::string readYamlScalar<std::string>(const std::filesystem::path&, const YAML::Node&,
                                                 const std::string&);

void assignParamNode(const std::filesystem::path& file, const YAML::Node& n, const std::string& key,
                     const ParamInfo& info, const ParamRef& field) {
  std::visit([&](auto target) { assignTo(file, n, key, info, target); }, field);
  if (auto problem = info.problem(field)) failAtYamlNode(file, n, key, *problem);
}

void readParamFields(const std::filesystem::path& file, const std::vector<ParamField>& fields) {
  for (const auto& entry : loadMap(file)) {
    if (!entry.first.IsScalar()) {
      failAtYamlNode(file, entry.first, "?", "expected a key, not a list or map");
    }
    const std::string key = entry.first.Scalar();
    const auto field = std::find_if(fields.begin(), fields.end(),
                                    [&key](const ParamField& f) { return f.info.key == key; });
    if (field == fields.end()) failAtYamlNode(file, entry.first, key, "unknown key");
    assignParamNode(file, entry.second, key, field->info, field->field);
  }
}

}  // namespace stocs
