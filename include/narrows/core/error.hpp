// The one error type of narrows: a user-facing message plus the exit code it maps to.
#pragma once

#include <stdexcept>
#include <string>

namespace narrows {

// Exit codes of the command line (docs/architecture.md, "The user-facing contract").
enum class ExitCode : int { ok = 0, other = 1, bad_input = 2, invariant = 3 };

class Error : public std::runtime_error {
public:
  Error(ExitCode code, const std::string &message) : std::runtime_error(message), code_(code) {}
  ExitCode code() const { return code_; }

private:
  ExitCode code_;
};

// Bad scene, command line or checkpoint: exit code 2.
inline Error input_error(const std::string &message) { return Error(ExitCode::bad_input, message); }

// A runtime invariant broke (NaN, lost particle, momentum drift): exit code 3.
inline Error invariant_error(const std::string &message) {
  return Error(ExitCode::invariant, message);
}

} // namespace narrows
