#pragma once
// Test helper: `gran` as a child process the test can wait for and signal (kill loops, signals
// mid-run), its stdout and stderr in a log file.
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <string>
#include <thread>
#include <vector>

#include "tests/support/run_gran.hpp"

namespace gran::testing {

class GranProcess {
  public:
    // Starts `gran args...`, output to `log` (appended).
    GranProcess(const std::vector<std::string>& args, const std::string& log) {
        std::vector<std::string> all{kGran};
        all.insert(all.end(), args.begin(), args.end());
        pid_ = ::fork();
        if (pid_ == 0) {
            std::FILE* f = std::freopen(log.c_str(), "a", stdout);
            if (f) ::dup2(::fileno(stdout), STDERR_FILENO);
            std::vector<char*> argv;
            for (auto& s : all) argv.push_back(s.data());
            argv.push_back(nullptr);
            ::execv(all[0].c_str(), argv.data());
            ::_exit(127);
        }
    }
    GranProcess(const GranProcess&) = delete;
    GranProcess& operator=(const GranProcess&) = delete;
    ~GranProcess() {
        if (running()) {
            ::kill(pid_, SIGKILL);
            wait_up_to(60);
        }
    }

    bool started() const { return pid_ > 0; }
    bool running() const { return pid_ > 0 && !ended_; }
    // Waits up to `seconds` for the end; true if it ended (then exit_code() or signal()).
    bool wait_up_to(double seconds) {
        const auto deadline =
            std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
        while (!ended_) {
            int status = 0;
            const pid_t r = ::waitpid(pid_, &status, WNOHANG);
            if (r == pid_) {
                ended_ = true;
                if (WIFEXITED(status)) exit_code_ = WEXITSTATUS(status);
                if (WIFSIGNALED(status)) signal_ = WTERMSIG(status);
                break;
            }
            if (std::chrono::steady_clock::now() >= deadline) break;
            std::this_thread::sleep_for(std::chrono::milliseconds(5));
        }
        return ended_;
    }
    void send(int sig) const { ::kill(pid_, sig); }
    int exit_code() const { return exit_code_; }  // -1 unless it exited
    int signal() const { return signal_; }        // 0 unless a signal ended it

  private:
    pid_t pid_ = -1;
    bool ended_ = false;
    int exit_code_ = -1;
    int signal_ = 0;
};

}  // namespace gran::testing
