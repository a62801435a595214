// Output files appear whole or not at all: a writer that fails or throws half-way leaves the
// previous file (or none) and no temporary behind.
#include "hylo/io/atomic_file.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "hylo/io/trajectory_io.h"
#include "test_data.h"

namespace hylo::io {
namespace {

namespace fs = std::filesystem;

std::string Read(const std::string& path) {
  std::ifstream in(path);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

std::size_t FilesIn(const std::string& dir) {
  std::size_t n = 0;
  for ([[maybe_unused]] const auto& entry : fs::directory_iterator(dir)) ++n;
  return n;
}

TEST(AtomicFile, CommittedTextReplacesTheFile) {
  const std::string dir = testing::ScratchDir("atomic_commit");
  const std::string path = dir + "/out.txt";
  WriteFileAtomically(path, "old\n");
  AtomicFile file(path);
  file.stream() << "new\n";
  EXPECT_EQ(Read(path), "old\n") << "the target changes only at Commit";
  file.Commit();
  EXPECT_EQ(Read(path), "new\n");
  EXPECT_EQ(FilesIn(dir), 1u) << "no temporary left";
}

TEST(AtomicFile, AWriterThatThrowsLeavesThePreviousFileAndNoTemporary) {
  const std::string dir = testing::ScratchDir("atomic_abort");
  const std::string path = dir + "/out.txt";
  WriteFileAtomically(path, "complete\n");
  try {
    AtomicFile file(path);
    file.stream() << "half";
    throw std::runtime_error("the writer failed");
  } catch (const std::runtime_error&) {
  }
  EXPECT_EQ(Read(path), "complete\n");
  EXPECT_EQ(FilesIn(dir), 1u);
}

TEST(AtomicFile, AnUnwritablePlaceIsAClearErrorNamingTheFile) {
  const std::string path = testing::ScratchDir("atomic_missing") + "/no/such/dir/out.tum";
  try {
    WriteTum(path, {StampedPose{}});
    FAIL() << "expected an error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
  }
  EXPECT_FALSE(fs::exists(path));
}

}  // namespace
}  // namespace hylo::io
