#pragma once
// OpenMP threads spin-wait between parallel regions by default (libgomp: a few hundred thousand
// spins), and with two cores and several thread teams (the node's tracking and its background
// detection, the objects followed in parallel) the spinning takes the CPU the others need. The
// programs wait passively instead unless the user chose a policy: libgomp reads OMP_WAIT_POLICY
// once, when it is loaded, before main runs, so the program executes itself again with it set.

namespace stocs {

/// Call first in main. When OMP_WAIT_POLICY is not set, sets it to "passive" and re-executes the
/// program (/proc/self/exe, the same arguments and process id); returns when it is set already or
/// the re-execution failed (then the program runs with libgomp's default policy).
void preferPassiveOpenMpWaiting(char** argv);

}  // namespace stocs
