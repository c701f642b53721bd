#include "stocs/util/openmp_wait.h"

#include <sys/auxv.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cstdlib>

namespace stocs {
namespace {

/// Whether /proc/self/exe is the program the kernel was asked to execute. It is not under
/// valgrind (the tool's own executable), when the dynamic loader runs the program
/// (`ld.so PROGRAM`) or after the program's file was replaced: executing /proc/self/exe with the
/// program's arguments would then run something else.
bool selfIsTheExecutedProgram() {
  const char* executed = reinterpret_cast<const char*>(getauxval(AT_EXECFN));
  struct stat self = {}, program = {};
  return executed != nullptr && stat("/proc/self/exe", &self) == 0 &&
         stat(executed, &program) == 0 && self.st_dev == program.st_dev &&
         self.st_ino == program.st_ino;
}

}  // namespace

void preferPassiveOpenMpWaiting(char** argv) {
  if (std::getenv("OMP_WAIT_POLICY") != nullptr || !selfIsTheExecutedProgram()) return;
  if (setenv("OMP_WAIT_POLICY", "passive", 1) != 0) return;
  execv("/proc/self/exe", argv);
  unsetenv("OMP_WAIT_POLICY");  // exec failed: say nothing that is not in effect
}

}  // namespace stocs
