#pragma once
// A NumPy .npy file (format version 1.0, https://numpy.org/doc/stable/reference/generated/
// numpy.lib.format.html) written one record at a time: the array's first dimension grows with
// every append, and close() writes the final shape into the header. The header is written at a
// fixed length up front, so closing rewrites it in place; numpy.load reads the file as it is.
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace drape {

class NpyWriter {
 public:
  /// `descr` is NumPy's type string ("<f8", "<f4", "<i4", "|u1"), `record_shape` the shape of
  /// one record (the array is (records, record_shape...)). Throws OutputError (run_files.hpp)
  /// when the file cannot be written.
  NpyWriter(std::filesystem::path path, std::string descr, std::size_t item_size,
            std::vector<std::size_t> record_shape);
  NpyWriter(const NpyWriter&) = delete;
  NpyWriter& operator=(const NpyWriter&) = delete;
  ~NpyWriter();

  /// Appends one record: item_size x product(record_shape) bytes (native little-endian).
  void append(const void* data);
  /// Writes the final shape into the header and closes the file (also done by the destructor).
  void close();
  std::size_t records() const { return m_records; }

 private:
  void write_header();

  std::filesystem::path m_path;
  std::string m_descr;
  std::size_t m_record_bytes;
  std::vector<std::size_t> m_record_shape;
  std::size_t m_records = 0;
  std::ofstream m_file;
};

}  // namespace drape
