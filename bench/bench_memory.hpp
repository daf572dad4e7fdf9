#pragma once
// Resident memory of this process (Linux /proc), for the benchmarks' bytes per particle: the peak
// resident set of one case is read after resetting the kernel's high-water mark before the case
// (writing 5 to /proc/self/clear_refs, Linux >= 4.0), minus the resident set at its start.
#include <cstdint>
#include <fstream>
#include <string>

namespace gran::bench {

// A "Vm...:  N kB" line of /proc/self/status in bytes; 0 when unreadable (not Linux).
inline std::uint64_t proc_status_bytes(const std::string& key) {
    std::ifstream in("/proc/self/status");
    std::string line;
    while (std::getline(in, line)) {
        if (line.rfind(key + ":", 0) == 0) return 1024 * std::stoull(line.substr(key.size() + 1));
    }
    return 0;
}

inline std::uint64_t resident_bytes() {
    return proc_status_bytes("VmRSS");
}
inline std::uint64_t peak_resident_bytes() {
    return proc_status_bytes("VmHWM");
}

// Sets the peak to the current resident set; false if the kernel refused (then the peak is that
// of the whole process so far).
inline bool reset_peak_resident() {
    std::ofstream out("/proc/self/clear_refs");
    out << "5";
    out.flush();
    return bool(out);
}

}  // namespace gran::bench
