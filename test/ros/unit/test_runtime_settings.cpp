#include <gtest/gtest.h>

#include "stocs/util/error.h"
#include "stocs_ros/stocs_node/runtime_settings.h"

namespace stocs_ros {
namespace {

dynamic_reconfigure::Config oneDouble(const std::string& name, double value) {
  dynamic_reconfigure::Config c;
  dynamic_reconfigure::DoubleParameter p;
  p.name = name;
  p.value = value;
  c.doubles.push_back(p);
  return c;
}

TEST(RuntimeSettings, DescriptionComesFromTheSchema) {
  const dynamic_reconfigure::ConfigDescription d = describeRuntimeKeys();
  ASSERT_EQ(d.groups.size(), 3u);  // Default, estimation, tracking
  EXPECT_EQ(d.groups[1].name, "estimation");
  EXPECT_EQ(d.groups[2].name, "tracking");
  size_t described = 0;
  for (const auto& g : d.groups) described += g.parameters.size();
  EXPECT_EQ(described, runtimeKeys().size());
  const auto& min_confidence = d.groups[1].parameters.at(0);
  EXPECT_EQ(min_confidence.name, "min_confidence");
  EXPECT_EQ(min_confidence.type, "double");
  EXPECT_NE(min_confidence.description.find("estimation.confidence.min_confidence"),
            std::string::npos);
  // Ranges and defaults: min_confidence in [0, 1], default 0.25; max_gap in (0, 3600].
  const auto value = [](const dynamic_reconfigure::Config& c, const std::string& name) {
    for (const auto& p : c.doubles) {
      if (p.name == name) return p.value;
    }
    return -1.0;
  };
  EXPECT_EQ(value(d.min, "min_confidence"), 0);
  EXPECT_EQ(value(d.max, "min_confidence"), 1);
  EXPECT_FLOAT_EQ(value(d.dflt, "min_confidence"), 0.25f);
  EXPECT_EQ(value(d.max, "max_gap"), 3600);
}

TEST(RuntimeSettings, ChangesApplyAndOutOfRangeValuesAreRefusedWithTheSchemasMessage) {
  const NodeConfig config;
  const NodeConfig changed = withRuntimeValues(config, oneDouble("min_confidence", 0.8));
  EXPECT_FLOAT_EQ(changed.estimation.confidence.min_confidence, 0.8f);
  EXPECT_EQ(changed.tracking.max_gap, config.tracking.max_gap);

  const auto refused = [&config](const dynamic_reconfigure::Config& c, const std::string& text) {
    try {
      withRuntimeValues(config, c);
      ADD_FAILURE() << "accepted; expected: " << text;
    } catch (const stocs::InputError& e) {
      EXPECT_NE(std::string(e.what()).find(text), std::string::npos) << e.what();
    }
  };
  refused(oneDouble("min_confidence", 1.5),
          "estimation.confidence.min_confidence 1.5 is outside [0, 1]");
  refused(oneDouble("max_gap", 0), "tracking.max_gap 0 s is outside (0, 3600]");
  refused(oneDouble("bases", 3), "bases: not a runtime setting");
}

}  // namespace
}  // namespace stocs_ros
