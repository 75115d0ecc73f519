#pragma once
// A fresh, empty scratch folder for the running test, named after it so that tests running in
// parallel (ctest -j) never share one.

#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <string_view>

namespace warpath::testing {

inline std::filesystem::path freshTestDir(std::string_view prefix) {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() /
      (std::string(prefix) + ::testing::UnitTest::GetInstance()->current_test_info()->name());
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

}  // namespace warpath::testing
