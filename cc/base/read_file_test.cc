#include "cc/base/read_file.h"

#include <sys/stat.h>
#include <unistd.h>

#include <cstdio>
#include <fstream>
#include <string>
#include <thread>

#include "gtest/gtest.h"

namespace kdtree {
namespace {

std::string TempDir() {
  const char* d = std::getenv("TEST_TMPDIR");
  return d != nullptr ? d : "/tmp";
}

TEST(ReadTextInput, ReadsARegularFile) {
  const std::string path = TempDir() + "/read_file_test.txt";
  std::ofstream(path) << "KDTree { maxDepth 24 }\n";
  absl::StatusOr<std::string> text = ReadTextInput(path, "environment file");
  ASSERT_TRUE(text.ok()) << text.status();
  EXPECT_EQ(*text, "KDTree { maxDepth 24 }\n");
}

TEST(ReadTextInput, ReadsAPipeOnce) {
  const std::string path = TempDir() + "/read_file_test.fifo";
  std::remove(path.c_str());
  ASSERT_EQ(mkfifo(path.c_str(), 0600), 0);
  std::thread writer([&] { std::ofstream(path) << "resolution 8 8\n"; });
  absl::StatusOr<std::string> text = ReadTextInput(path, "view file");
  writer.join();
  ASSERT_TRUE(text.ok()) << text.status();
  EXPECT_EQ(*text, "resolution 8 8\n");
}

TEST(ReadTextInput, RefusesADirectoryByName) {
  absl::StatusOr<std::string> text = ReadTextInput(TempDir(), "environment file");
  ASSERT_FALSE(text.ok());
  EXPECT_EQ(text.status().message(), TempDir() + ": the environment file is a directory");
}

TEST(ReadTextInput, RefusesADevice) {
  absl::StatusOr<std::string> text = ReadTextInput("/dev/zero", "view file");
  ASSERT_FALSE(text.ok());
  EXPECT_EQ(text.status().message(), "/dev/zero: the view file is a device");
}

TEST(ReadTextInput, MissingIsNotFound) {
  absl::StatusOr<std::string> text = ReadTextInput(TempDir() + "/no/such/file", "view file");
  EXPECT_TRUE(absl::IsNotFound(text.status())) << text.status();
}

TEST(ReadTextInput, RefusesMoreThanTheBudget) {
  const std::string path = TempDir() + "/read_file_test_big.txt";
  std::ofstream(path) << std::string(1000, 'x');
  absl::StatusOr<std::string> text = ReadTextInput(path, "view file", 999);
  ASSERT_FALSE(text.ok());
  EXPECT_NE(text.status().message().find("longer than 999 bytes"), std::string::npos);
  EXPECT_TRUE(ReadTextInput(path, "view file", 1000).ok());
}

}  // namespace
}  // namespace kdtree
