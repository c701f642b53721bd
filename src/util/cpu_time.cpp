#include "stocs/util/cpu_time.h"

#include <ctime>

namespace stocs {

namespace {

double clockSeconds(clockid_t clock) {
  timespec t{};
  clock_gettime(clock, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

}  // namespace

double processCpuSeconds() {
  return clockSeconds(CLOCK_PROCESS_CPUTIME_ID);
}

double threadCpuSeconds() {
  return clockSeconds(CLOCK_THREAD_CPUTIME_ID);
}

}  // namespace stocs
