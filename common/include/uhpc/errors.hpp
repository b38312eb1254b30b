#pragma once
// The two failure kinds every program distinguishes (docs/architecture.md section 2):
// bad input -> exit code 2, numerical failure -> exit code 1.
#include <stdexcept>
#include <string>

namespace uhpc {

// Bad input: a file, key or value the user can fix. The message is complete and user-facing.
class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// A computation that went wrong (NaN, inverted volume, no convergence). Exit code 1.
class NumericalError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// The one format of every input error: "<file>: key '<key>': <reason>" (or "<file>: <reason>"
// when no key is involved).
inline std::string input_message(const std::string& file, const std::string& key, const std::string& reason) {
  if (key.empty()) return file + ": " + reason;
  return file + ": key '" + key + "': " + reason;
}

[[noreturn]] inline void throw_input_error(const std::string& file, const std::string& key, const std::string& reason) {
  throw InputError(input_message(file, key, reason));
}

}  // namespace uhpc
