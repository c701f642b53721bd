#pragma once
// Private ROS parameters read through a core ParamSet schema: each key of the schema that is set
// overrides the struct's default, with the type the field has; the schema checks the ranges.

#include <ros/node_handle.h>

#include "stocs/util/param_set.h"

namespace stocs_ros {

/// Sets `field` from the parameter `key` of `pnh` when it is set. Throws stocs::InputError naming
/// the parameter when its type does not fit the field or a choice is unknown.
void readParam(const ros::NodeHandle& pnh, const stocs::ParamInfo& info,
               const stocs::ParamRef& field);

/// Throws stocs::InputError "parameter <resolved key> is not set" when `value` is empty.
void requireSet(const ros::NodeHandle& pnh, const std::string& key, const std::string& value);

/// Every set parameter of `schema` into `params`, then the schema's range checks. Throws
/// stocs::InputError naming the first bad parameter.
template <class S>
void readSchemaParams(const ros::NodeHandle& pnh, const stocs::ParamSet<S>& schema, S& params) {
  for (const auto& entry : schema.entries()) readParam(pnh, entry.info, entry.field(params));
  schema.validate(params,
                  [&pnh](const stocs::ParamInfo& info) { return pnh.resolveName(info.key); });
}

}  // namespace stocs_ros
