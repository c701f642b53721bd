#pragma once
// The CPU time of the whole process, the figure to compare on a machine shared with other work.

namespace stocs {

/// CPU time consumed so far by every thread of this process (CLOCK_PROCESS_CPUTIME_ID), seconds.
double processCpuSeconds();
/// CPU time consumed so far by the calling thread (CLOCK_THREAD_CPUTIME_ID), seconds.
double threadCpuSeconds();

}  // namespace stocs
