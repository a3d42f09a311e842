#pragma once
// A scratch folder per test (named by the test and gtest's seed), removed with everything in it at the end.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

namespace graspmix::test_support {

struct TempDir {
  std::filesystem::path dir;
  TempDir() {
    const auto* test = ::testing::UnitTest::GetInstance();
    dir = std::filesystem::temp_directory_path() /
          ("graspmix_io_" + std::to_string(test->random_seed()) + "_" + test->current_test_info()->name());
    std::filesystem::create_directories(dir);
  }
  ~TempDir() { std::filesystem::remove_all(dir); }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  std::string operator/(const std::string& name) const { return (dir / name).string(); }
};

}  // namespace graspmix::test_support
