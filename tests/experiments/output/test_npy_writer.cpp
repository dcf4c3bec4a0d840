// The .npy files of event_trace/ (NumPy format 1.0): the header's bytes, the shape rewritten on
// close, the records read back as they were appended.
#include "experiments/output/npy_writer.hpp"

#include <gtest/gtest.h>

#include <cstring>
#include <fstream>
#include <iterator>

#include "core/io/output_error.hpp"

namespace drape {
namespace {

namespace fs = std::filesystem;

fs::path fresh(const std::string& name) {
  const fs::path dir = fs::path(::testing::TempDir()) / "npy_writer";
  fs::create_directories(dir);
  fs::remove(dir / name);
  return dir / name;
}

std::string bytes_of(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

/// The header dictionary with its padding and newline removed.
std::string header_dict(const std::string& bytes) {
  const std::size_t length = static_cast<unsigned char>(bytes[8]) +
                             256 * static_cast<std::size_t>(static_cast<unsigned char>(bytes[9]));
  std::string dict = bytes.substr(10, length);
  dict.erase(dict.find_last_not_of(" \n") + 1);
  return dict;
}

TEST(NpyWriter, HeaderIsVersionOneAlignedAndCarriesTheFinalShape) {
  const fs::path file = fresh("positions.npy");
  NpyWriter writer(file, "<f8", sizeof(double), {4, 3});
  const double zeros[12] = {};
  for (int k = 0; k < 5; ++k) writer.append(zeros);
  EXPECT_EQ(writer.records(), 5u);
  writer.close();
  const std::string bytes = bytes_of(file);
  EXPECT_EQ(bytes.substr(0, 8), std::string("\x93NUMPY\x01\x00", 8));
  EXPECT_EQ(bytes[8] + 256 * bytes[9], 118) << "128 header bytes in all";
  EXPECT_EQ(bytes[127], '\n');
  EXPECT_EQ(header_dict(bytes), "{'descr': '<f8', 'fortran_order': False, 'shape': (5, 4, 3), }");
  EXPECT_EQ(bytes.size(), 128u + 5 * 12 * sizeof(double));
}

TEST(NpyWriter, RecordsOfOneValueMakeAOneDimensionalArray) {
  const fs::path file = fresh("time.npy");
  {
    NpyWriter writer(file, "<i4", sizeof(std::int32_t), {});
    for (std::int32_t k = 0; k < 3; ++k) writer.append(&k);
  }  // the destructor closes
  const std::string bytes = bytes_of(file);
  EXPECT_EQ(header_dict(bytes), "{'descr': '<i4', 'fortran_order': False, 'shape': (3,), }");
  ASSERT_EQ(bytes.size(), 128u + 3 * 4);
  std::int32_t values[3];
  std::memcpy(values, bytes.data() + 128, sizeof(values));
  EXPECT_EQ(values[0], 0);
  EXPECT_EQ(values[2], 2);
}

TEST(NpyWriter, RecordsReadBackInAppendOrder) {
  const fs::path file = fresh("velocity.npy");
  NpyWriter writer(file, "<f8", sizeof(double), {2});
  const double first[2] = {1.5, -2.25};
  const double second[2] = {1e-300, 6.02e23};
  writer.append(first);
  writer.append(second);
  writer.close();
  writer.close();  // a second close changes nothing
  const std::string bytes = bytes_of(file);
  EXPECT_EQ(header_dict(bytes), "{'descr': '<f8', 'fortran_order': False, 'shape': (2, 2), }");
  double values[4];
  ASSERT_EQ(bytes.size(), 128u + sizeof(values));
  std::memcpy(values, bytes.data() + 128, sizeof(values));
  EXPECT_EQ(values[0], 1.5);
  EXPECT_EQ(values[1], -2.25);
  EXPECT_EQ(values[2], 1e-300);
  EXPECT_EQ(values[3], 6.02e23);
}

TEST(NpyWriter, AnUnwritablePathIsAnOutputErrorNamingIt) {
  const fs::path file = fs::path(::testing::TempDir()) / "npy_writer_no_folder" / "x.npy";
  try {
    NpyWriter writer(file, "<f8", sizeof(double), {3});
    FAIL() << "no error";
  } catch (const OutputError& e) {
    EXPECT_EQ(std::string(e.what()), "cannot write " + file.string() + ": No such file or directory");
  }
}

}  // namespace
}  // namespace drape
