#pragma once
// Test helper: run the `gran` program (GRAN_BINARY) with arguments and capture its output and exit
// status, the way a user's shell would.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace gran::testing {

inline const std::string kGran = GRAN_BINARY;

// The whole content of a file (empty if it cannot be read), to compare results byte for byte.
inline std::string read_text(const std::filesystem::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

inline std::string shell_quote(const std::string& s) {
    std::string q = "'";
    for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return q + "'";
}

struct Outcome {
    int exit_code = -1;     // valid when !signaled
    bool signaled = false;  // the program died by a signal (crash)
    int signal = 0;
    std::string output;  // stdout and stderr, interleaved
};

// Runs a program (args[0]) with its arguments through the shell, capturing stdout+stderr and the
// exit status.
inline Outcome run_command(const std::vector<std::string>& args) {
    // `exec`: the shell becomes the program, so pclose reports its own status (and its signal).
    std::string cmd = "exec";
    for (const auto& a : args) cmd += " " + shell_quote(a);
    cmd += " 2>&1";
    Outcome out;
    FILE* pipe = ::popen(cmd.c_str(), "r");
    if (!pipe) {
        ADD_FAILURE() << "popen failed for: " << cmd;
        return out;
    }
    char buf[4096];
    std::size_t n = 0;
    while ((n = std::fread(buf, 1, sizeof buf, pipe)) > 0) out.output.append(buf, n);
    const int status = ::pclose(pipe);
    if (WIFSIGNALED(status)) {
        out.signaled = true;
        out.signal = WTERMSIG(status);
    } else if (WIFEXITED(status)) {
        out.exit_code = WEXITSTATUS(status);
    }
    return out;
}

// Runs gran with `args`.
inline Outcome run_gran(const std::vector<std::string>& args) {
    std::vector<std::string> all{kGran};
    all.insert(all.end(), args.begin(), args.end());
    return run_command(all);
}

}  // namespace gran::testing
