#pragma once
// OpenMP threads spin-wait between parallel regions by default (libgomp: a few hundred thousand
// spins), and with two cores and several thread teams (the node's tracking and its background
// detection, the objects followed in parallel) the spinning takes the CPU the others need. The
// programs wait passively instead unless the user chose a policy: libgomp reads OMP_WAIT_POLICY
// (and GOMP_SPINCOUNT) once, in its constructor, before main runs, and OpenMP has no call that
// sets the policy later, so the program executes itself again with it set. Launch files set the
// variable with <env> instead (launch/stocs.launch): there the re-execution does not happen, and a
// nodelet manager, which does not call this, gets it too.

namespace stocs {

/// Call first in main. When OMP_WAIT_POLICY is not set, sets it to "passive" and re-executes the
/// program (/proc/self/exe, the same arguments and process id); returns when it is set already,
/// when /proc/self/exe is not the program that was executed (under valgrind, run by the dynamic
/// loader, its file replaced) or the re-execution failed: then the program runs with libgomp's
/// default policy. A debugger follows the re-execution (gdb: "executing new program").
void preferPassiveOpenMpWaiting(char** argv);

}  // namespace stocs
