#pragma once
// The signals that ask `gran` to stop (runs and studies alike), and the flag they set.
#include <atomic>

namespace gran::app {

// Set by SIGINT, SIGTERM, SIGHUP, SIGUSR1 and SIGXCPU once stop_on_signals() ran.
extern std::atomic<bool> g_interrupt;

// Every signal that asks a run to end: Ctrl-C, kill, a closed terminal (SIGHUP), a batch
// system's warning (SIGUSR1) and the CPU-time limit (SIGXCPU). Each stops the run like SIGTERM:
// what was measured is written and the exit status is 3. No SA_RESTART: a signal interrupts a
// study's wait for its runs, so they are stopped at once.
void stop_on_signals();

}  // namespace gran::app
