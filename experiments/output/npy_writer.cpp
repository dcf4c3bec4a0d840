#include "experiments/output/npy_writer.hpp"

#include <fmt/format.h>

#include <functional>
#include <numeric>
#include <stdexcept>

#include "experiments/output/run_files.hpp"

namespace drape {

namespace {

// Magic, version 1.0, the 2-byte header length, then the header dictionary padded with spaces
// and ended by '\n' to this many bytes in all: room for any shape of up to 2^64 records.
constexpr std::size_t kHeaderBytes = 128;
constexpr char kMagic[] = "\x93NUMPY\x01\x00";
constexpr std::size_t kPreamble = 10;  // magic (6) + version (2) + header length (2)

}  // namespace

NpyWriter::NpyWriter(std::filesystem::path path, std::string descr, std::size_t item_size,
                     std::vector<std::size_t> record_shape)
    : m_path(std::move(path)),
      m_descr(std::move(descr)),
      m_record_bytes(std::accumulate(record_shape.begin(), record_shape.end(), item_size,
                                     std::multiplies<>())),
      m_record_shape(std::move(record_shape)),
      m_file(m_path, std::ios::binary) {
  check_written(m_file, m_path);
  write_header();
}

NpyWriter::~NpyWriter() {
  try {
    close();
  } catch (...) {
    // A destructor must not throw; close() called explicitly reports the error.
  }
}

void NpyWriter::write_header() {
  std::string shape = fmt::format("{},", m_records);
  for (std::size_t extent : m_record_shape) shape += fmt::format(" {},", extent);
  if (m_record_shape.size() >= 1) shape.pop_back();  // (n,) keeps its comma, (n, 3) does not
  std::string dict = fmt::format("{{'descr': '{}', 'fortran_order': False, 'shape': ({}), }}",
                                 m_descr, shape);
  dict.resize(kHeaderBytes - kPreamble - 1, ' ');
  dict += '\n';
  const auto length = static_cast<std::uint16_t>(dict.size());
  m_file.seekp(0);
  m_file.write(kMagic, 8);
  const char length_bytes[2] = {static_cast<char>(length & 0xff), static_cast<char>(length >> 8)};
  m_file.write(length_bytes, 2);
  m_file.write(dict.data(), static_cast<std::streamsize>(dict.size()));
  check_written(m_file, m_path);
}

void NpyWriter::append(const void* data) {
  m_file.seekp(0, std::ios::end);
  m_file.write(static_cast<const char*>(data), static_cast<std::streamsize>(m_record_bytes));
  check_written(m_file, m_path);
  ++m_records;
}

void NpyWriter::close() {
  if (!m_file.is_open()) return;
  write_header();
  m_file.close();
  check_written(m_file, m_path);
}

}  // namespace drape
