#include "apps/gran/signals.hpp"

#include <csignal>

namespace gran::app {

std::atomic<bool> g_interrupt{false};

namespace {

extern "C" void on_signal(int) {
    g_interrupt.store(true);
}

}  // namespace

void stop_on_signals() {
    struct sigaction sa {};
    sa.sa_handler = on_signal;
    sigemptyset(&sa.sa_mask);
    sa.sa_flags = 0;
    for (int sig : {SIGINT, SIGTERM, SIGHUP, SIGUSR1, SIGXCPU}) sigaction(sig, &sa, nullptr);
}

}  // namespace gran::app
