// The programs wait passively between OpenMP parallel regions unless the user chose a policy
// (stocs/util/openmp_wait.h). libgomp prints its settings with OMP_DISPLAY_ENV=verbose when it
// loads (once per execution); the spin count of the last execution is the one in effect: 0 when
// passive, 300000 by default (which libgomp displays as 'PASSIVE' too), more when active.
#include <elf.h>
#include <gtest/gtest.h>
#include <link.h>

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

/// The dynamic loader this test program was started by (its PT_INTERP), which runs the tool too.
std::string dynamicLoader() {
  std::string loader;
  dl_iterate_phdr(
      [](dl_phdr_info* info, size_t, void* out) {
        for (int k = 0; k < info->dlpi_phnum; ++k) {
          if (info->dlpi_phdr[k].p_type == PT_INTERP) {
            *static_cast<std::string*>(out) =
                reinterpret_cast<const char*>(info->dlpi_addr + info->dlpi_phdr[k].p_vaddr);
          }
        }
        return 1;  // the first object is the program itself
      },
      &loader);
  return loader;
}

TEST(CliOpenMpWait, WaitsPassivelyUnlessTheUserChoseAPolicy) {
  EXPECT_EQ(spinCountInEffect(""), "0");
  EXPECT_NE(spinCountInEffect("OMP_WAIT_POLICY=active"), "0");
  EXPECT_EQ(spinCountInEffect("OMP_WAIT_POLICY=passive"), "0");
}

// Run by the dynamic loader, /proc/self/exe is the loader: executing it again with the tool's
// arguments would have the loader look for a program named after the subcommand.
TEST(CliOpenMpWait, RunsWhenTheDynamicLoaderStartsIt) {
  const std::string loader = dynamicLoader();
  ASSERT_FALSE(loader.empty());
  std::string out;
  EXPECT_EQ(
      test::runCommand("env -u OMP_WAIT_POLICY " + loader + " " + kTool + " estimate --help", out),
      0)
      << out;
  EXPECT_NE(out.find("Estimate object poses"), std::string::npos) << out;
}

}  // namespace
}  // namespace stocs
