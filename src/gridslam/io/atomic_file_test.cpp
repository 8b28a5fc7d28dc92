#include "gridslam/io/atomic_file.hpp"

#include <filesystem>

#include <gtest/gtest.h>

#include "gridslam/io/options_yaml.hpp"
#include "gridslam/testing/data_path.hpp"

namespace gridslam::io {
namespace {

TEST(AtomicFile, WriterWritesThePiecesInOrder) {
  const auto dir = testing::MakeTempDir("atomic_writer");
  const std::string path = (dir / "out.txt").string();
  ASSERT_TRUE(WriteFileAtomically(path, [](std::FILE* f) {
                return std::fputs("first ", f) >= 0 && std::fputs("second", f) >= 0;
              }).ok());
  EXPECT_EQ(ReadTextFile(path).value(), "first second");
}

TEST(AtomicFile, AFailedWriterLeavesTheOldFileAndNoTemporary) {
  const auto dir = testing::MakeTempDir("atomic_writer_fails");
  const std::string path = (dir / "out.txt").string();
  ASSERT_TRUE(WriteFileAtomically(path, std::string("old")).ok());
  const Status s = WriteFileAtomically(path, [](std::FILE* f) {
    std::fputs("half", f);
    return false;
  });
  ASSERT_FALSE(s.ok());
  EXPECT_NE(s.error().ToString().find(path), std::string::npos);
  EXPECT_EQ(ReadTextFile(path).value(), "old");
  int files = 0;
  for ([[maybe_unused]] const auto& entry : std::filesystem::directory_iterator(dir)) {
    ++files;
  }
  EXPECT_EQ(files, 1);
}

}  // namespace
}  // namespace gridslam::io
