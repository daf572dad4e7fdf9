#pragma once
// Advisory whole-file locks (flock(2)): the kind HDF5 takes on every file it opens, and the one
// study merges take turns on (libgran/study/study_merge.hpp). One home for the open + flock
// details: close-on-exec (a child process must not inherit a lock), EINTR, file systems without
// locks.
#include <functional>
#include <string>

namespace gran {

// Whether another process holds a lock on the file at `path`. False when the file does not exist
// or cannot be opened, and on a file system without locks (nothing can be seen there).
bool file_locked_by_another(const std::string& path);

// An exclusive lock on the file at `path` (created if missing, and left there: removing a locked
// file races with the next process opening it), held while this object lives.
class ExclusiveFileLock {
  public:
    enum class Outcome {
        Held,           // at once
        HeldAfterWait,  // another process held it; this one waited for it
        Unavailable,    // could not open or lock the file (error() says why): not held
    };
    // Takes the lock, waiting for another holder; `on_wait` (may be empty) is called once before
    // the wait, so a caller can say what it waits for.
    explicit ExclusiveFileLock(const std::string& path, const std::function<void()>& on_wait = {});
    ~ExclusiveFileLock();
    ExclusiveFileLock(const ExclusiveFileLock&) = delete;
    ExclusiveFileLock& operator=(const ExclusiveFileLock&) = delete;

    Outcome outcome() const { return outcome_; }
    bool held() const { return outcome_ != Outcome::Unavailable; }
    const std::string& error() const { return error_; }  // strerror of the failure

  private:
    int fd_ = -1;
    Outcome outcome_ = Outcome::Unavailable;
    std::string error_;
};

}  // namespace gran
