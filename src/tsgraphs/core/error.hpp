#pragma once
/// Errors that front ends turn into exit codes: bad input -> 2, anything else -> 1.
#include <stdexcept>
#include <string>

namespace tsgraphs {

/// Raised for malformed user input (scene, config, data files). The message is one line
/// naming the file, the place in it and what is wrong, e.g. "office.yaml:12: walls[3].to: ...".
class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Builds "file:line: what" (line is 1-based; 0 leaves it out).
inline InputError input_error(const std::string& file, int line, const std::string& what) {
  std::string msg = file;
  if (line > 0) msg += ":" + std::to_string(line);
  return InputError(msg + ": " + what);
}

}  // namespace tsgraphs
