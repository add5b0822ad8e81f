#pragma once
// How idle OpenMP threads wait between the step's parallel loops. rcdem's default is passive
// (they sleep) unless the user's environment sets OMP_WAIT_POLICY: spinning threads make a step
// wait for a thread the system has descheduled when another process holds a core, which at 2
// threads on 2 cores with one busy cost 30% below 1 thread's rate, while passive waiting kept
// 2 threads at 1 thread's rate there and within noise of spinning on a quiet machine
// (bench/RESULTS.md, "Threads on a shared machine").
#include <cstdlib>

namespace rcdem {

// Call first thing in main() (and at the Python module's import), before any OpenMP call: the
// runtime reads the variable once, when it starts.
inline void prefer_passive_thread_waiting() { ::setenv("OMP_WAIT_POLICY", "passive", 0); }

}  // namespace rcdem
