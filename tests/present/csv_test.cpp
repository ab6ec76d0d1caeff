// Tests for present/csv.cpp and present/file.cpp: numbers read back exactly, failures that a
// buffered write only shows at the end (/dev/full) are reported, bad names are refused.
#include "present/csv.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <random>
#include <sstream>

#include "present/file.hpp"

namespace rigidlab::present {
namespace {

std::string temp_path() {
  char name[] = "/tmp/rigidlab_csv_XXXXXX";
  const int fd = mkstemp(name);
  close(fd);
  return name;
}

TEST(Csv, NumbersReadBackExactlyAndShort) {
  EXPECT_EQ(csv_number(0.1), "0.1");
  EXPECT_EQ(csv_number(-2.5), "-2.5");
  EXPECT_EQ(csv_number(1e-300), "1e-300");
  std::mt19937_64 rng(3);
  for (int i = 0; i < 1000; ++i) {
    double x;
    const std::uint64_t bits = rng();
    std::memcpy(&x, &bits, sizeof x);
    if (!std::isfinite(x)) continue;
    EXPECT_EQ(std::strtod(csv_number(x).c_str(), nullptr), x) << csv_number(x);
  }
}

TEST(Csv, WritesAHeaderAndOneRowPerIndex) {
  const std::string path = temp_path();
  write_csv(path, {Column{"t", {0, 0.5, 1}}, Column{"p.x", {1.0 / 3, -0.0, 1e10}}});
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  EXPECT_EQ(text.str(), "t,p.x\n0,0.3333333333333333\n0.5,-0\n1,1e+10\n");
  std::remove(path.c_str());
}

TEST(Csv, RefusesBadNamesAndRaggedColumns) {
  const std::string path = temp_path();
  EXPECT_THROW(write_csv(path, {Column{"a,b", {1}}}), std::invalid_argument);
  EXPECT_THROW(write_csv(path, {Column{std::string("a\0b", 3), {1}}}), std::invalid_argument);
  EXPECT_THROW(write_csv(path, {Column{"a", {1}}, Column{"b", {1, 2}}}), std::invalid_argument);
  EXPECT_EQ(column_name_problem("ω.x"), "");
  std::remove(path.c_str());
}

TEST(File, ReportsAFullDiskAtTheEnd) {
  try {
    write_csv("/dev/full", {Column{"x", {1, 2, 3}}});
    FAIL() << "no error";
  } catch (const FileError& e) {
    EXPECT_STREQ(e.what(), "cannot write '/dev/full': No space left on device");
  }
  try {
    write_file("/nonexistent-rigidlab-dir/a.svg", "x");
    FAIL() << "no error";
  } catch (const FileError& e) {
    EXPECT_STREQ(e.what(),
                 "cannot open '/nonexistent-rigidlab-dir/a.svg' for writing: No such file or directory");
  }
}

}  // namespace
}  // namespace rigidlab::present
