// The programs wait passively between OpenMP parallel regions unless the user chose a policy
// (stocs/util/openmp_wait.h). libgomp prints its settings with OMP_DISPLAY_ENV=verbose when it
// loads (once per execution); the spin count of the last execution is the one in effect: 0 when
// passive, 300000 by default (which libgomp displays as 'PASSIVE' too), more when active.
#include <gtest/gtest.h>

#include "test_support.h"

namespace stocs {
namespace {

const std::string kTool = STOCS_TOOL_PATH;

/// The spin count libgomp last displayed when the tool ran in `environment`.
std::string spinCountInEffect(const std::string& environment) {
  std::string out;
  EXPECT_EQ(test::runCommand("env -u OMP_WAIT_POLICY OMP_DISPLAY_ENV=verbose " + environment + " " +
                                 kTool + " estimate --help",
                             out),
            0)
      << out;
  const std::string key = "GOMP_SPINCOUNT = '";
  const size_t at = out.rfind(key);
  if (at == std::string::npos) return "not displayed: " + out;
  return out.substr(at + key.size(), out.find('\'', at + key.size()) - at - key.size());
}

TEST(CliOpenMpWait, WaitsPassivelyUnlessTheUserChoseAPolicy) {
  EXPECT_EQ(spinCountInEffect(""), "0");
  EXPECT_NE(spinCountInEffect("OMP_WAIT_POLICY=active"), "0");
  EXPECT_EQ(spinCountInEffect("OMP_WAIT_POLICY=passive"), "0");
}

}  // namespace
}  // namespace stocs
