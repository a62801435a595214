#include "fuzz_support.h"

#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>

namespace hylo::fuzz {
namespace fs = std::filesystem;
namespace {

// One folder per process; /dev/shm keeps the per-execution writes off the disk.
const fs::path& ProcessFolder() {
  static const fs::path folder = [] {
    std::error_code ec;
    const fs::path base =
        fs::is_directory("/dev/shm", ec) ? fs::path("/dev/shm") : fs::temp_directory_path();
    fs::path dir = base / ("hylo_fuzz_" + std::to_string(::getpid()));
    fs::remove_all(dir, ec);
    fs::create_directories(dir);
    std::atexit([] {
      std::error_code ignored;
      fs::remove_all(ProcessFolder(), ignored);
    });
    return dir;
  }();
  return folder;
}

}  // namespace

void Fail(const std::string& what) {
  std::fprintf(stderr, "fuzz contract broken: %s\n", what.c_str());
  std::fflush(stderr);
  std::abort();
}

std::string WriteScratchFile(const std::string& name, const uint8_t* data, std::size_t size) {
  const std::string path = (ProcessFolder() / name).string();
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  out.close();
  Require(static_cast<bool>(out), "cannot write the scratch file " + path);
  return path;
}

std::string FreshScratchFolder(const std::string& name) {
  const fs::path dir = ProcessFolder() / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir.string();
}

void RequireClearError(const std::exception& e, const std::string& must_name) {
  RequireClearError(e, std::vector<std::string>{must_name});
}

void RequireClearError(const std::exception& e, const std::vector<std::string>& names) {
  const std::string message = e.what();
  Require(message.find('\n') == std::string::npos, "error spans lines: " + message);
  for (const std::string& name : names) {
    if (message.find(name) != std::string::npos) return;
  }
  Fail("error does not name '" + names.front() + "': " + message);
}

std::vector<std::string> Split(const std::string& text, const std::string& separator) {
  std::vector<std::string> parts;
  std::size_t begin = 0;
  while (true) {
    const std::size_t at = text.find(separator, begin);
    parts.push_back(text.substr(begin, at - begin));
    if (at == std::string::npos) return parts;
    begin = at + separator.size();
  }
}

}  // namespace hylo::fuzz
