#include "stocs_ros/stocs_node/runtime_settings.h"

#include <fmt/format.h>

#include <algorithm>
#include <limits>
#include <type_traits>

#include "stocs/util/error.h"

namespace stocs_ros {
namespace {

template <class Parameter, class Value>
Parameter named(const std::string& name, Value value) {
  Parameter p;
  p.name = name;
  p.value = value;
  return p;
}

dynamic_reconfigure::GroupState groupState(const std::string& name, int id) {
  dynamic_reconfigure::GroupState g;
  g.name = name;
  g.state = true;
  g.id = id;
  g.parent = 0;
  return g;
}

using Entry = stocs::ParamSet<NodeConfig>::Entry;

const Entry& schemaEntry(const std::string& key) {
  for (const Entry& e : NodeConfig::schema().entries()) {
    if (e.info.key == key) return e;
  }
  throw std::logic_error("runtime key " + key + " is not in the node's schema");
}

/// "estimation.confidence.min_confidence" -> section "estimation", name "min_confidence".
std::string sectionOf(const std::string& key) {
  return key.substr(0, key.find('.'));
}
std::string nameOf(const std::string& key) {
  return key.substr(key.rfind('.') + 1);
}

/// dynamic_reconfigure's type of a schema field: bool, int, double or str.
std::string typeOf(const stocs::ParamRef& field) {
  return std::visit(
      [](auto f) -> std::string {
        using T = std::remove_pointer_t<decltype(f)>;
        if constexpr (std::is_same_v<T, bool>) {
          return "bool";
        } else if constexpr (std::is_integral_v<T>) {
          return "int";
        } else if constexpr (std::is_floating_point_v<T>) {
          return "double";
        } else {
          return "str";
        }
      },
      field);
}

/// Appends the field's value to `config` under `name`; `bound` (a range end) replaces a number's.
void addValue(dynamic_reconfigure::Config& config, const std::string& name,
              const stocs::ParamRef& field, std::optional<double> bound = std::nullopt) {
  std::visit(
      [&](auto f) {
        using T = std::remove_pointer_t<decltype(f)>;
        if constexpr (std::is_same_v<T, bool>) {
          config.bools.push_back(named<dynamic_reconfigure::BoolParameter>(name, *f));
        } else if constexpr (std::is_integral_v<T>) {
          const double v = bound.value_or(static_cast<double>(*f));
          const double limit = std::numeric_limits<int>::max();
          config.ints.push_back(named<dynamic_reconfigure::IntParameter>(
              name, static_cast<int>(std::clamp(v, -limit, limit))));
        } else if constexpr (std::is_floating_point_v<T>) {
          // A float's shortest decimal (0.6, not 0.6000000238), as the configuration file has it.
          const double value = std::stod(fmt::format("{}", *f));
          config.doubles.push_back(
              named<dynamic_reconfigure::DoubleParameter>(name, bound.value_or(value)));
        } else {
          config.strs.push_back(
              named<dynamic_reconfigure::StrParameter>(name, stocs::paramText(f)));
        }
      },
      field);
}

/// The group id of each section, in runtimeKeys() order (the default group is 0).
std::vector<std::string> sections() {
  std::vector<std::string> out;
  for (const std::string& key : runtimeKeys()) {
    if (std::find(out.begin(), out.end(), sectionOf(key)) == out.end())
      out.push_back(sectionOf(key));
  }
  return out;
}

void addGroupStates(dynamic_reconfigure::Config& config) {
  config.groups.push_back(groupState("Default", 0));
  const std::vector<std::string> names = sections();
  for (size_t i = 0; i < names.size(); ++i) {
    config.groups.push_back(groupState(names[i], static_cast<int>(i + 1)));
  }
}

/// The runtime keys' values in `config`, or their range ends (`lower`: the minimum, else the
/// maximum).
dynamic_reconfigure::Config values(const NodeConfig& config, std::optional<bool> lower) {
  NodeConfig& fields = const_cast<NodeConfig&>(config);  // only read
  dynamic_reconfigure::Config out;
  for (const std::string& key : runtimeKeys()) {
    const Entry& e = schemaEntry(key);
    std::optional<double> bound;
    if (lower && e.info.range) {
      const stocs::ParamRange& r = *e.info.range;
      bound =
          *lower ? std::min(r.lo, r.also.value_or(r.lo)) : std::max(r.hi, r.also.value_or(r.hi));
    }
    addValue(out, nameOf(key), e.field(fields), bound);
  }
  addGroupStates(out);
  return out;
}

/// Sets `field` from the value named `name` in `changes`, if there is one; throws
/// stocs::InputError when its type does not fit.
void takeValue(const dynamic_reconfigure::Config& changes, const std::string& name,
               const stocs::ParamRef& field) {
  const auto find = [&name](const auto& list) {
    return std::find_if(list.begin(), list.end(),
                        [&name](const auto& p) { return p.name == name; });
  };
  std::visit(
      [&](auto f) {
        using T = std::remove_pointer_t<decltype(f)>;
        if constexpr (std::is_same_v<T, bool>) {
          if (auto it = find(changes.bools); it != changes.bools.end()) *f = it->value;
        } else if constexpr (std::is_integral_v<T>) {
          if (auto it = find(changes.ints); it != changes.ints.end()) {
            if (it->value < 0 && std::is_unsigned_v<T>) {
              throw stocs::InputError(fmt::format("{}: {} is negative", name, it->value));
            }
            *f = static_cast<T>(it->value);
          }
        } else if constexpr (std::is_floating_point_v<T>) {
          if (auto it = find(changes.doubles); it != changes.doubles.end()) {
            *f = static_cast<T>(it->value);
          }
        }
      },
      field);
}

/// Every name `changes` sets, to refuse those that are not runtime keys.
std::vector<std::string> namesIn(const dynamic_reconfigure::Config& changes) {
  std::vector<std::string> names;
  for (const auto& p : changes.bools) names.push_back(p.name);
  for (const auto& p : changes.ints) names.push_back(p.name);
  for (const auto& p : changes.doubles) names.push_back(p.name);
  for (const auto& p : changes.strs) names.push_back(p.name);
  return names;
}

}  // namespace

const std::vector<std::string>& runtimeKeys() {
  static const std::vector<std::string> keys = {"estimation.confidence.min_confidence",
                                                "estimation.stocs.time_budget",
                                                "tracking.enabled",
                                                "tracking.redetect_every",
                                                "tracking.max_gap",
                                                "tracking.velocity_damping",
                                                "tracking.roi_margin",
                                                "tracking.match_distance",
                                                "tracking.hold_hidden"};
  return keys;
}

dynamic_reconfigure::ConfigDescription describeRuntimeKeys() {
  dynamic_reconfigure::ConfigDescription d;
  dynamic_reconfigure::Group top;
  top.name = "Default";
  d.groups.push_back(top);
  const std::vector<std::string> names = sections();
  for (size_t i = 0; i < names.size(); ++i) {
    dynamic_reconfigure::Group g;
    g.name = names[i];
    g.id = static_cast<int>(i + 1);
    g.parent = 0;
    NodeConfig defaults;
    for (const std::string& key : runtimeKeys()) {
      if (sectionOf(key) != names[i]) continue;
      const Entry& e = schemaEntry(key);
      dynamic_reconfigure::ParamDescription p;
      p.name = nameOf(key);
      p.type = typeOf(e.field(defaults));
      p.description = fmt::format("{}{} ({})", e.info.meaning,
                                  e.info.unit.empty() ? "" : ", " + e.info.unit, key);
      g.parameters.push_back(p);
    }
    d.groups.push_back(g);
  }
  d.min = values(NodeConfig(), true);
  d.max = values(NodeConfig(), false);
  d.dflt = values(NodeConfig(), std::nullopt);
  return d;
}

dynamic_reconfigure::Config runtimeValues(const NodeConfig& config) {
  return values(config, std::nullopt);
}

NodeConfig withRuntimeValues(const NodeConfig& config, const dynamic_reconfigure::Config& changes) {
  for (const std::string& name : namesIn(changes)) {
    const bool known = std::any_of(runtimeKeys().begin(), runtimeKeys().end(),
                                   [&name](const std::string& key) { return nameOf(key) == name; });
    if (!known) throw stocs::InputError(fmt::format("{}: not a runtime setting", name));
  }
  NodeConfig changed = config;
  for (const std::string& key : runtimeKeys()) {
    takeValue(changes, nameOf(key), schemaEntry(key).field(changed));
  }
  NodeConfig::schema().validate(changed);
  return changed;
}

RuntimeSettings::RuntimeSettings(ros::NodeHandle& pnh, SetupStore& setups)
    : setups_(setups),
      descriptions_(
          pnh.advertise<dynamic_reconfigure::ConfigDescription>("parameter_descriptions", 1, true)),
      updates_(pnh.advertise<dynamic_reconfigure::Config>("parameter_updates", 1, true)) {
  descriptions_.publish(describeRuntimeKeys());
  publishValues();
  service_ = pnh.advertiseService("set_parameters", &RuntimeSettings::onSet, this);
}

void RuntimeSettings::publishValues() {
  updates_.publish(runtimeValues(setups_.current()->config));
}

bool RuntimeSettings::onSet(dynamic_reconfigure::Reconfigure::Request& request,
                            dynamic_reconfigure::Reconfigure::Response& response) {
  try {
    setups_.change(
        [&request](const NodeConfig& config) { return withRuntimeValues(config, request.config); });
    ROS_INFO("stocs: runtime settings changed; they apply from the next frame");
  } catch (const stocs::InputError& e) {
    ROS_WARN("stocs: dynamic_reconfigure: %s; the settings stay as they were", e.what());
  }
  response.config = runtimeValues(setups_.current()->config);
  updates_.publish(response.config);
  return true;
}

}  // namespace stocs_ros
