#include "apps/gran/study_mpi.hpp"

#include <fmt/format.h>
#include <mpi.h>
#include <spdlog/spdlog.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdlib>
#include <deque>
#include <iostream>
#include <map>
#include <thread>

#include "libgran/study/study_exec.hpp"

namespace gran {

namespace {

constexpr int kTagReport = 1;  // worker -> rank 0: {finished run or -1 (ready), exit code}
constexpr int kTagAssign = 2;  // rank 0 -> worker: the next run, or -1 (no more)

int env_size() {
    for (const char* v : {"OMPI_COMM_WORLD_SIZE", "PMIX_SIZE", "PMI_SIZE"}) {
        if (const char* x = std::getenv(v); x && *x) return std::atoi(x);
    }
    return 0;
}

// Rank 0: the queue, its own runs, and the other ranks' requests.
class Coordinator {
  public:
    Coordinator(const Study& st, const StudyOptions& opt, StudyPlan& plan, int ranks, int local)
        : st_(st), opt_(opt), plan_(plan), workers_(ranks - 1), local_(local) {
        longest_first(st, plan.todo);
        queue_.assign(plan.todo.begin(), plan.todo.end());
    }

    void run() {
        while (workers_ > 0 || !running_.empty() || (!queue_.empty() && !stopping_)) {
            stop_on_interrupt();
            bool busy = start_local();
            busy = serve_one() || busy;
            busy = reap_local() || busy;
            // Nothing happened: the runs take seconds, a millisecond of latency costs nothing.
            if (!busy) std::this_thread::sleep_for(std::chrono::milliseconds(1));
        }
        plan_.report.interrupted = stopping_;
    }

  private:
    void stop_on_interrupt() {
        if (stopping_ || !opt_.interrupt || !opt_.interrupt->load()) return;
        stopping_ = true;
        spdlog::warn("study interrupted: no new runs; running runs keep what they measured");
        for (const auto& [pid, i] : running_) kill(pid, SIGTERM);
    }

    bool start_local() {
        bool started = false;
        while (!stopping_ && int(running_.size()) < local_ && !queue_.empty()) {
            const std::size_t i = queue_.front();
            queue_.pop_front();
            try {
                running_[start_study_run(st_, opt_, plan_.files, i)] = i;
                started = true;
            } catch (const std::exception& e) {
                ++plan_.report.failed;
                spdlog::error("{}: {}", st_.runs[i].name, e.what());
            }
        }
        return started;
    }

    // One request of another rank: record what it finished, give it the next run or stop it.
    bool serve_one() {
        int flag = 0;
        MPI_Status status;
        MPI_Iprobe(MPI_ANY_SOURCE, kTagReport, MPI_COMM_WORLD, &flag, &status);
        if (!flag) return false;
        int msg[2];
        MPI_Recv(msg, 2, MPI_INT, status.MPI_SOURCE, kTagReport, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
        if (msg[0] >= 0) finished(std::size_t(msg[0]), msg[1], status.MPI_SOURCE);
        int next = -1;
        if (!stopping_ && !queue_.empty()) {
            next = int(queue_.front());
            queue_.pop_front();
        } else {
            --workers_;
        }
        MPI_Send(&next, 1, MPI_INT, status.MPI_SOURCE, kTagAssign, MPI_COMM_WORLD);
        return true;
    }

    bool reap_local() {
        int status = 0;
        const pid_t pid = waitpid(-1, &status, WNOHANG);
        if (pid <= 0) return false;
        auto it = running_.find(pid);
        if (it == running_.end()) return true;
        const std::size_t i = it->second;
        running_.erase(it);
        finished(i, exit_code_of(status), 0);
        return true;
    }

    void finished(std::size_t i, int code, int rank) {
        ++done_;
        record_run_exit(st_, i, code, stopping_, plan_);
        if (code == 0 && opt_.progress)
            spdlog::info("[{}/{}] {} done on rank {}", done_, plan_.todo.size(), st_.runs[i].name,
                         rank);
    }

    const Study& st_;
    const StudyOptions& opt_;
    StudyPlan& plan_;
    int workers_;  // ranks not yet told that there is no more work
    const int local_;
    std::deque<std::size_t> queue_;
    std::map<pid_t, std::size_t> running_;
    std::size_t done_ = 0;
    bool stopping_ = false;
};

// A rank other than 0: ask, run, report, until told there is no more.
void work(const Study& st, const StudyOptions& opt, const RunFiles& files) {
    int msg[2] = {-1, 0};
    while (true) {
        MPI_Send(msg, 2, MPI_INT, 0, kTagReport, MPI_COMM_WORLD);
        int next = -1;
        MPI_Recv(&next, 1, MPI_INT, 0, kTagAssign, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
        if (next < 0) return;
        int code = 1;
        try {
            const pid_t pid = start_study_run(st, opt, files, std::size_t(next));
            bool signalled = false;
            int status = 0;
            while (true) {
                const pid_t w = waitpid(pid, &status, WNOHANG);
                if (w == pid) break;
                if (w < 0 && errno != EINTR) break;
                if (!signalled && opt.interrupt && opt.interrupt->load()) {
                    kill(pid, SIGTERM);  // the run writes what it measured and exits 3
                    signalled = true;
                }
                std::this_thread::sleep_for(std::chrono::milliseconds(1));
            }
            code = exit_code_of(status);
        } catch (const std::exception& e) {
            spdlog::error("{}: {}", st.runs[std::size_t(next)].name, e.what());
        }
        msg[0] = next;
        msg[1] = code;
    }
}

}  // namespace

bool launched_by_mpirun() {
    return env_size() > 1;
}

int run_study_mpi(const Study& st, const StudyOptions& opt) {
    MPI_Init(nullptr, nullptr);
    int rank = 0, ranks = 1;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    MPI_Comm_size(MPI_COMM_WORLD, &ranks);
    // Under MPI each rank is one slot: one run at a time per rank unless -j says more.
    const int local = opt.jobs > 0 ? opt.jobs : 1;
    int code = 0;
    if (rank == 0) {
        StudyPlan plan = plan_study(st, opt);
        spdlog::info(
            "study {}: {} runs, {} already complete, {} to run on {} MPI ranks ({} at a "
            "time each); results in {}",
            st.file, st.runs.size(), plan.report.reused, plan.todo.size(), ranks, local,
            plan.outdir);
        Coordinator(st, opt, plan, ranks, local).run();
        finish_study(st, plan);
        const StudyReport& rep = plan.report;
        std::cout << fmt::format(
            "{} ran, {} reused, {} failed{}; {} MPI ranks\nresult: {}\ntable: {}\n", rep.ran,
            rep.reused, rep.failed, rep.interrupted ? " (interrupted)" : "", ranks, rep.merged,
            rep.table);
        code = rep.interrupted ? 3 : rep.failed > 0 ? 1 : 0;
    } else {
        // The folders exist once rank 0 hands out the first run.
        work(st, opt, run_files(st, study_output_dir(st, opt)));
    }
    MPI_Bcast(&code, 1, MPI_INT, 0, MPI_COMM_WORLD);
    MPI_Finalize();
    return code;
}

}  // namespace gran
