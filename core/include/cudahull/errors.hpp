// Error types, and the exit codes the command line maps them to (documented in README, "Exit codes").
#pragma once

#include <cstdio>
#include <exception>
#include <new>
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

// Runs a program's command, `work` (returning its exit code), and turns what it throws into the one line
// and the exit code above: InputError 3; DeviceError and a failed allocation 4; OutputError 1;
// std::invalid_argument (a value the command line let through) 2; any other exception 1, as an internal
// error.  `Usage`, an error type of the program's own (e.g. the viewer's ScriptError), is a usage error.
struct NoUsageError : std::exception {};  // run_reporting_errors()'s default: no error type of its own
template <class Usage = NoUsageError, class Work>
int run_reporting_errors(const char* program, Work&& work) {
  try {
    return work();
  } catch (const Usage& e) {
    return report_error(program, kExitUsage, e.what());
  } catch (const InputError& e) {
    return report_error(program, kExitBadInput, e.what());
  } catch (const DeviceError& e) {
    return report_error(program, kExitDevice, e.what());
  } catch (const OutputError& e) {
    return report_error(program, kExitOutput, e.what());
  } catch (const std::bad_alloc&) {
    return report_error(program, kExitDevice, "out of memory");
  } catch (const std::invalid_argument& e) {
    return report_error(program, kExitUsage, e.what());
  } catch (const std::exception& e) {
    return report_error(program, kExitOutput, std::string("internal error: ") + e.what());
  }
}

}  // namespace cudahull
