#pragma once
// What every fuzz target shares: a scratch file (or folder) holding the current input for the
// readers that only take paths, and the checks that turn a broken promise into a crash that
// libFuzzer (or the replay driver) reports.
//
// A target's contract, checked on every input: the reader either returns a result that keeps
// its documented invariants, or throws its documented exception type with a one-line message
// that names the file. Anything else (another exception type, an abort, a sanitizer report,
// a hang) is a finding.

#include <cstddef>
#include <cstdint>
#include <exception>
#include <string>
#include <vector>

namespace hylo::fuzz {

/// Prints "fuzz contract broken: <what>" and aborts (libFuzzer saves the input as a crash).
[[noreturn]] void Fail(const std::string& what);

/// Aborts with `what` unless `condition` holds.
inline void Require(bool condition, const std::string& what) {
  if (!condition) Fail(what);
}

/// A file path private to this process (in /dev/shm when it exists, else the temp folder)
/// whose content is replaced by each call; the file is removed when the process exits.
/// `name` is the file name (its extension picks the reader where that matters).
std::string WriteScratchFile(const std::string& name, const uint8_t* data, std::size_t size);
inline std::string WriteScratchFile(const std::string& name, const std::string& text) {
  return WriteScratchFile(name, reinterpret_cast<const uint8_t*>(text.data()), text.size());
}

/// An empty folder private to this process (emptied on each call, removed at exit).
std::string FreshScratchFolder(const std::string& name);

/// The reader's error must be one line and contain `must_name` (the file it read).
void RequireClearError(const std::exception& e, const std::string& must_name);
/// The same, with any one of `names` (when either of two files may be at fault).
void RequireClearError(const std::exception& e, const std::vector<std::string>& names);

/// The input split at every occurrence of `separator` (at least one part).
std::vector<std::string> Split(const std::string& text, const std::string& separator);

}  // namespace hylo::fuzz
