// Error types, and the exit codes the command line maps them to (documented in README, "Exit codes").
#pragma once

#include <cstdio>
#include <stdexcept>
#include <string>

namespace cudahull {

enum ExitCode : int {
  kExitOk = 0,
  kExitUsage = 2,        // bad command line
  kExitBadInput = 3,     // unreadable or invalid input file
  kExitDevice = 4,       // out of memory, no device, kernel fault
  kExitOutput = 1,       // an output file could not be written
  kExitVerifyFailed = 5  // --verify found the hull wrong
};

// Unreadable or malformed input.  The message names the file and the line or element index.
class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Out of memory or an accelerator failure.
class DeviceError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Out of device memory (a DeviceError): a caller with a path that needs less may take it instead.
class OutOfDeviceMemory : public DeviceError {
 public:
  using DeviceError::DeviceError;
};

// An output file could not be written.
class OutputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// The one line a command-line program prints before exiting with `code`: "PROGRAM: error: MESSAGE".
inline int report_error(const char* program, int code, const std::string& message) {
  std::fprintf(stderr, "%s: error: %s\n", program, message.c_str());
  return code;
}

}  // namespace cudahull
