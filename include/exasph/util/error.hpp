#pragma once
#include <stdexcept>
#include <string>

namespace exasph {

// A user-facing error: bad input or a physical state the code cannot continue from.
// The command line prints what() as one line and exits with exit_code().
// `all_ranks` marks errors that every MPI rank detects identically (from global data): they end
// the run cleanly; any other error on one rank aborts all ranks, so that none waits forever.
class Error : public std::runtime_error {
  public:
    explicit Error(const std::string& msg, int exit_code = 1, bool all_ranks = false)
        : std::runtime_error(msg), exit_code_(exit_code), all_ranks_(all_ranks) {}
    int exit_code() const { return exit_code_; }
    bool all_ranks() const { return all_ranks_; }

  private:
    int exit_code_;
    bool all_ranks_;
};

// Bad input (option, file content): exit code 2 by project convention.
inline Error input_error(const std::string& msg, bool all_ranks = false) {
    return Error(msg, 2, all_ranks);
}

} // namespace exasph
