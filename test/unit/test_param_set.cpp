// The parameter schemas: every estimation parameter's range is enforced at both ends and named by
// its key, keys and CLI options are unique, and nested schemas keep their keys and options.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <set>

#include "stocs/estimation/pipeline.h"
#include "stocs/util/error.h"
#include "stocs/util/param_docs.h"
#include "stocs/util/param_set.h"

namespace stocs {
namespace {

/// Sets a number field to `value` (rounded for integers).
void setNumber(const ParamRef& ref, double value) {
  std::visit(
      [value](auto field) {
        using T = decltype(field);
        if constexpr (std::is_same_v<T, int*>) {
          *field = static_cast<int>(value);
        } else if constexpr (std::is_same_v<T, float*> || std::is_same_v<T, double*>) {
          *field = static_cast<std::remove_pointer_t<T>>(value);
        } else {
          FAIL() << "not an int or floating-point field";
        }
      },
      ref);
}

bool isInteger(const ParamRef& ref) {
  return std::holds_alternative<int*>(ref);
}

/// The message validate() throws for `p`, or "" when it passes.
std::string validationError(const PipelineParams& p) {
  try {
    p.validate();
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(ParamSet, EveryRangeIsEnforcedAtBothEndsAndNamesItsKey) {
  int checked = 0;
  for (const auto& entry : PipelineParams::schema().entries()) {
    const ParamInfo& info = entry.info;
    if (!info.range) continue;
    const ParamRange& r = *info.range;
    PipelineParams p;
    const ParamRef field = entry.field(p);
    const double step = isInteger(field) ? 1 : std::max(1e-6, std::abs(r.hi - r.lo) * 1e-3);
    const double inside_lo = r.lo_open ? r.lo + step : r.lo;
    const double inside_hi = r.hi_open ? r.hi - step : r.hi;
    const double outside_lo = r.lo_open ? r.lo : r.lo - step;
    const double outside_hi = r.hi_open ? r.hi : r.hi + step;
    for (double v : {inside_lo, inside_hi}) {
      setNumber(field, v);
      EXPECT_EQ(validationError(p), "") << info.key << " = " << v;
    }
    for (double v : {outside_lo, outside_hi}) {
      if (r.also && v == *r.also) continue;
      setNumber(field, v);
      const std::string error = validationError(p);
      EXPECT_EQ(error.rfind(info.key + " ", 0), 0u) << info.key << " = " << v << ": " << error;
      EXPECT_NE(error.find("is outside " + r.str()), std::string::npos) << error;
    }
    if (r.also) {
      setNumber(field, *r.also);
      EXPECT_EQ(validationError(p), "") << info.key << " = " << *r.also;
    }
    if (!isInteger(field)) {
      setNumber(field, std::numeric_limits<double>::quiet_NaN());
      EXPECT_NE(validationError(p), "") << info.key << " = NaN";
    }
    ++checked;
  }
  EXPECT_GT(checked, 40);
}

TEST(ParamSet, KeysAndOptionsAreUniqueAndNestedKeysKeepTheirOptions) {
  std::set<std::string> keys, flags;
  for (const auto& entry : PipelineParams::schema().entries()) {
    EXPECT_TRUE(keys.insert(entry.info.key).second) << entry.info.key;
    EXPECT_TRUE(flags.insert(entry.info.cliFlag()).second) << entry.info.cliFlag();
    EXPECT_FALSE(entry.info.meaning.empty()) << entry.info.key;
    EXPECT_FALSE(entry.info.group.empty()) << entry.info.key;
  }
  EXPECT_TRUE(keys.count("stocs.icp.iterations"));
  EXPECT_TRUE(flags.count("--icp-iterations"));
  EXPECT_TRUE(flags.count("--segment-normals-samples-per-axis"));  // derived from the key
  EXPECT_EQ(keys.size(), PipelineParams::schema().entries().size());
}

TEST(ParamSet, RangesPrintAsIntervals) {
  EXPECT_EQ(ParamRange::closed(1, 100).str(), "[1, 100]");
  EXPECT_EQ(ParamRange::aboveUpTo(0, 0.1).str(), "(0, 0.1]");
  EXPECT_EQ(ParamRange::fromBelow(0, 1).str(), "[0, 1)");
  EXPECT_EQ(ParamRange::closed(1, 100).orAlso(0).str(), "0 or [1, 100]");
  EXPECT_FALSE(ParamRange::closed(0, 1).contains(std::nan("")));
  EXPECT_TRUE(ParamRange::closed(1, 100).orAlso(0).contains(0));
  EXPECT_FALSE(ParamRange::closed(1, 100).orAlso(0).contains(0.5));
}

TEST(ParamSet, YamlNestsKeysAndCommentsEachValue) {
  struct Inner {
    int steps = 3;
  };
  struct Outer {
    bool on = true;
    Inner inner;
    float size = 0.5f;
  };
  ParamSet<Inner> inner;
  inner.add(&Inner::steps, "steps", "", ParamRange::closed(1, 9), "steps taken");
  ParamSet<Outer> outer;
  outer.add(&Outer::on, "on", "switch").nest(&Outer::inner, "inner", inner);
  outer.add(&Outer::size, "size", "m", ParamRange::aboveUpTo(0, 1), "edge");
  EXPECT_EQ(paramsYaml(outer.describe(Outer())),
            "on: true                       # switch\n"
            "\n"
            "inner:\n"
            "  steps: 3                     # steps taken ([1, 9])\n"
            "\n"
            "size: 0.5                      # edge (m, (0, 1])\n");
}

}  // namespace
}  // namespace stocs
