#include "libgran/run/progress.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <cstdio>
#include <string>

namespace gran {

Progress::Progress(bool enabled, bool terminal, double log_interval, const char* unit)
    : enabled_(enabled),
      terminal_(terminal),
      log_interval_(log_interval),
      unit_(unit),
      start_(Clock::now()),
      last_log_(start_) {}

void Progress::update(const char* phase, double fraction, std::uint64_t work, bool force) {
    if (!enabled_) return;
    const auto now = Clock::now();
    const double since = std::chrono::duration<double>(now - last_draw_).count();
    if (!force && terminal_ && since < 0.2) return;
    if (!force && !terminal_ &&
        std::chrono::duration<double>(now - last_log_).count() < log_interval_)
        return;
    last_draw_ = now;
    const double elapsed = std::chrono::duration<double>(now - start_).count();
    const double rate = elapsed > 0 ? double(work) / elapsed : 0;
    const double eta = fraction > 1e-9 ? elapsed * (1 - fraction) / fraction : 0;
    const std::string line =
        fmt::format("{:<13} {:5.1f}%  elapsed {:.0f}s  ETA {:.0f}s  {:.3g} {}/s", phase,
                    100 * fraction, elapsed, eta, rate, unit_);
    if (terminal_) {
        std::fprintf(stderr, "\r%s   ", line.c_str());
        std::fflush(stderr);
        drawn_ = true;
    } else {
        spdlog::info("{}", line);
        last_log_ = now;
    }
}

void Progress::finish() {
    if (drawn_) std::fprintf(stderr, "\n");
}

double Progress::elapsed() const {
    return std::chrono::duration<double>(Clock::now() - start_).count();
}

}  // namespace gran
