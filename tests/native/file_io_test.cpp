// native/file_io: the errno -> Status code table, whole-file reads of what is not a
// regular file (a directory, a FIFO: refused at once, never waited on), and atomic writes of a
// file given in parts.
#include "native/file_io.h"

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace prt {
namespace {

TEST(FileIo, ErrnoCodes) {
  EXPECT_EQ(statusCodeForErrno(ENOENT), StatusCode::kNotFound);
  EXPECT_EQ(statusCodeForErrno(ENOTDIR), StatusCode::kNotFound);
  EXPECT_EQ(statusCodeForErrno(ENOSPC), StatusCode::kResourceExhausted);
  EXPECT_EQ(statusCodeForErrno(EDQUOT), StatusCode::kResourceExhausted);
  EXPECT_EQ(statusCodeForErrno(ENOMEM), StatusCode::kResourceExhausted);
  EXPECT_EQ(statusCodeForErrno(EMFILE), StatusCode::kResourceExhausted);
  EXPECT_EQ(statusCodeForErrno(EACCES), StatusCode::kIoError);
  EXPECT_EQ(statusCodeForErrno(EIO), StatusCode::kIoError);
  EXPECT_EQ(statusCodeForErrno(EROFS), StatusCode::kIoError);
}

TEST(FileIo, ReadRefusesWhatIsNotARegularFile) {
  char pattern[] = "/tmp/prt-file-io-test-XXXXXX";
  ASSERT_NE(::mkdtemp(pattern), nullptr);
  const std::string dir = pattern;
  std::vector<std::uint8_t> bytes;

  Status s = readFileBytes(dir + "/absent", 1024, &bytes);
  EXPECT_EQ(s.code(), StatusCode::kNotFound);
  EXPECT_EQ(s.message(), "'" + dir + "/absent': no such file");

  s = readFileBytes(dir, 1024, &bytes);
  EXPECT_EQ(s.code(), StatusCode::kInvalidArgument);
  EXPECT_NE(s.message().find("not a regular file"), std::string::npos) << s.message();

  // Without O_NONBLOCK the open would wait for a writer forever (the test would time out).
  const std::string fifo = dir + "/fifo";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  s = readFileBytes(fifo, 1024, &bytes);
  EXPECT_EQ(s.code(), StatusCode::kInvalidArgument);
  EXPECT_NE(s.message().find("not a regular file"), std::string::npos) << s.message();

  const std::string big = dir + "/big";
  ASSERT_TRUE(writeFileAtomically(big, std::vector<std::uint8_t>(2048, 7), {}).isOk());
  s = readFileBytes(big, 1024, &bytes);
  EXPECT_EQ(s.code(), StatusCode::kInvalidArgument);
  ASSERT_TRUE(readFileBytes(big, 2048, &bytes).isOk());
  EXPECT_EQ(bytes, std::vector<std::uint8_t>(2048, 7));

  ::unlink(fifo.c_str());
  ::unlink(big.c_str());
  ::rmdir(dir.c_str());
}

// writePartsAtomically: the file is its parts one after another (empty ones included), and
// it replaces an older, longer file whole; the single-buffer writer gives the same bytes.
TEST(FileIo, PartsAreWrittenOneAfterAnother) {
  char pattern[] = "/tmp/prt-file-io-test-XXXXXX";
  ASSERT_NE(::mkdtemp(pattern), nullptr);
  const std::string dir = pattern, path = dir + "/parts";
  ASSERT_TRUE(writeFileAtomically(path, std::vector<std::uint8_t>(5000, 9)).isOk());
  const std::vector<std::uint8_t> a = {1, 2, 3}, b, c(3000, 4), d = {5};
  const std::span<const std::uint8_t> parts[] = {a, b, c, d};
  ASSERT_TRUE(writePartsAtomically(path, parts).isOk());
  std::vector<std::uint8_t> want(3 + 3000 + 1, 4);  // a, c, d
  want[0] = 1;
  want[1] = 2;
  want[2] = 3;
  want.back() = 5;
  std::vector<std::uint8_t> bytes;
  ASSERT_TRUE(readFileBytes(path, 1 << 20, &bytes).isOk());
  EXPECT_EQ(bytes, want);
  // Refused as writeFileAtomically refuses: the parent is not a directory.
  EXPECT_FALSE(writePartsAtomically(path + "/under", parts).isOk());
  ::unlink(path.c_str());
  ::rmdir(dir.c_str());
}

}  // namespace
}  // namespace prt
