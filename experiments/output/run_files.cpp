#include "experiments/output/run_files.hpp"

#include <fmt/format.h>

#include <cerrno>
#include <stdexcept>

namespace drape {

void check_written(const std::ostream& out, const std::filesystem::path& file) {
  if (!out) throw write_failure(file.string());
}

void finish_written(std::ostream& out, const std::filesystem::path& file) {
  out.flush();
  check_written(out, file);
}

std::ofstream open_for_writing(const std::filesystem::path& file) {
  errno = 0;
  std::ofstream out(file);
  check_written(out, file);
  return out;
}

void write_state_csv(const std::filesystem::path& file, const ClothSystem& system,
                     const Eigen::VectorXd& y) {
  std::ofstream out = open_for_writing(file);
  out << "index,row,col,x,y,z,vx,vy,vz,fixed\n";
  const Cloth& cloth = system.cloth();
  const Eigen::Index n3 = 3 * system.num_particles();
  for (int i = 0; i < system.num_particles(); ++i) {
    const Vec3 x = y.segment<3>(3 * i);
    const Vec3 v = y.segment<3>(n3 + 3 * i);
    out << fmt::format("{},{},{},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{}\n", i,
                       cloth.row_of(i), cloth.col_of(i), x.x(), x.y(), x.z(), v.x(), v.y(),
                       v.z(), system.constraints().is_fixed(i) ? 1 : 0);
  }
  finish_written(out, file);
}

void write_dummy_csv(const std::filesystem::path& file, const Dummy& dummy) {
  std::ofstream out = open_for_writing(file);
  out << "index,section,point,x,y,z,nx,ny,nz\n";
  for (int o = 0; o < dummy.size(); ++o) {
    const Vec3 p = dummy.position(o), n = dummy.normal(o);
    out << fmt::format("{},{},{},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g}\n", o,
                       o / dummy.points(), o % dummy.points(), p.x(), p.y(), p.z(), n.x(), n.y(),
                       n.z());
  }
  finish_written(out, file);
}

void write_file_atomic(const std::filesystem::path& file, const std::string& suffix,
                       const std::function<void(std::ostream&)>& write) {
  // rename() replaces the file in one step: summary.json, whose presence marks a complete run
  // folder (docs/outputs.md), and result.json, which marks a finished run, are never half there.
  std::filesystem::path tmp = file;
  tmp += suffix;
  {
    std::ofstream out = open_for_writing(tmp);
    write(out);
    finish_written(out, tmp);
  }
  std::error_code ec;
  std::filesystem::rename(tmp, file, ec);
  if (ec) throw OutputError("cannot write " + file.string() + ": " + ec.message());
}

void write_json(const std::filesystem::path& file, const nlohmann::json& value,
                const std::string& suffix) {
  // A path given on the command line may hold bytes that are not UTF-8 (Linux allows them): they
  // are written as U+FFFD rather than failing the write of a run that is done.
  write_file_atomic(file, suffix, [&](std::ostream& out) {
    out << value.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) << "\n";
  });
}

}  // namespace drape
