#include "stocs/util/openmp_wait.h"

#include <unistd.h>

#include <cstdlib>

namespace stocs {

void preferPassiveOpenMpWaiting(char** argv) {
  if (std::getenv("OMP_WAIT_POLICY") != nullptr) return;
  if (setenv("OMP_WAIT_POLICY", "passive", 1) != 0) return;
  execv("/proc/self/exe", argv);
  unsetenv("OMP_WAIT_POLICY");  // exec failed: say nothing that is not in effect
}

}  // namespace stocs
