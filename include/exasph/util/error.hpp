#pragma once
#include <stdexcept>
#include <string>

namespace exasph {

// A user-facing error: bad input or a physical state the code cannot continue from.
// The command line prints what() as one line and exits with exit_code().
class Error : public std::runtime_error {
  public:
    explicit Error(const std::string& msg, int exit_code = 1)
        : std::runtime_error(msg), exit_code_(exit_code) {}
    int exit_code() const { return exit_code_; }

  private:
    int exit_code_;
};

// Bad input (option, file content): exit code 2 by project convention.
inline Error input_error(const std::string& msg) {
    return Error(msg, 2);
}

} // namespace exasph
