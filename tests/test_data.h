#pragma once
// Where tests find real data, and a visible skip when it is absent.

#include <gtest/gtest.h>

#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <string>

namespace hylo::testing {

/// $HYLO_DATA_DIR if set, else ../shared/data beside the checkout.
inline std::string DataDir() {
  const char* env = std::getenv("HYLO_DATA_DIR");
  return (env != nullptr && *env != '\0') ? std::string(env) : std::string(HYLO_DEFAULT_DATA_DIR);
}

/// Full path of `relative` inside the data directory.
inline std::string DataPath(const std::string& relative) { return DataDir() + "/" + relative; }

/// A scratch directory for one test, emptied on creation. The process id keeps parallel
/// ctest runs (each test is its own process) and concurrent checkouts apart.
inline std::string ScratchDir(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() /
                   ("hylo_test_" + name + "_" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir.string();
}

}  // namespace hylo::testing

/// Skips the current test, visibly, when a data file or folder is absent.
#define HYLO_REQUIRE_DATA(relative)                                                   \
  do {                                                                                \
    const std::string hylo_data_path_ = ::hylo::testing::DataPath(relative);          \
    if (!std::filesystem::exists(hylo_data_path_))                                    \
      GTEST_SKIP() << "real data absent: " << hylo_data_path_ << " (set HYLO_DATA_DIR)"; \
  } while (0)
