#include "experiments/output/vtk_writer.hpp"

#include <fmt/format.h>

#include <fstream>
#include <stdexcept>

#include "core/dummy/dummy.hpp"
#include "experiments/output/run_files.hpp"

namespace drape {

namespace {

void write_int_values(std::ofstream& out, const std::vector<int>& values) {
  for (const int v : values) out << v << "\n";
}

std::ofstream open_vtk(const std::filesystem::path& file, const std::string& title) {
  std::ofstream out = open_for_writing(file);
  out << "# vtk DataFile Version 3.0\n" << title << "\nASCII\nDATASET POLYDATA\n";
  return out;
}

}  // namespace

void write_cloth_vtk(const std::filesystem::path& file, const ClothSystem& system,
                     const Eigen::VectorXd& y, double t, const ClothFrameData& data) {
  const Cloth& cloth = system.cloth();
  const int n = system.num_particles();
  const int rows = cloth.params.rows, cols = cloth.params.cols;
  std::ofstream out = open_vtk(file, fmt::format("drapelab cloth t={:.17g}", t));
  // ParaView takes a frame's time from this field, so uneven frame times still animate right.
  out << fmt::format("FIELD FieldData 1\nTIME 1 1 double\n{:.17g}\n", t);
  out << fmt::format("POINTS {} double\n", n);
  for (int i = 0; i < n; ++i)
    out << fmt::format("{:.17g} {:.17g} {:.17g}\n", y[3 * i], y[3 * i + 1], y[3 * i + 2]);
  const int quads = std::max(0, rows - 1) * std::max(0, cols - 1);
  out << fmt::format("POLYGONS {} {}\n", quads, 5 * quads);
  for (int r = 0; r + 1 < rows; ++r)
    for (int c = 0; c + 1 < cols; ++c)
      out << fmt::format("4 {} {} {} {}\n", cloth.index(r, c), cloth.index(r, c + 1),
                         cloth.index(r + 1, c + 1), cloth.index(r + 1, c));
  out << fmt::format("POINT_DATA {}\nVECTORS velocity double\n", n);
  const Eigen::Index n3 = 3 * static_cast<Eigen::Index>(n);
  for (int i = 0; i < n; ++i)
    out << fmt::format("{:.17g} {:.17g} {:.17g}\n", y[n3 + 3 * i], y[n3 + 3 * i + 1],
                       y[n3 + 3 * i + 2]);
  std::vector<int> fixed(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) fixed[static_cast<std::size_t>(i)] = system.constraints().is_fixed(i);
  out << "SCALARS fixed int 1\nLOOKUP_TABLE default\n";
  write_int_values(out, fixed);
  // Legacy readers load only the first SCALARS unless told to read all (vtkDataReader::
  // ReadAllScalars); arrays of a FIELD block they always load, so the later flags go there.
  out << fmt::format("FIELD point_flags 2\nheld 1 {} int\n", n);
  write_int_values(out, data.held);
  out << fmt::format("contact 1 {} int\n", n);
  write_int_values(out, data.contact);
  finish_written(out, file);
}

void write_dummy_vtk(const std::filesystem::path& file, const Dummy& dummy) {
  std::ofstream out = open_vtk(file, "drapelab object particles");
  const int n = dummy.size();
  out << fmt::format("POINTS {} double\n", n);
  for (int o = 0; o < n; ++o) {
    const Vec3 p = dummy.position(o);
    out << fmt::format("{:.17g} {:.17g} {:.17g}\n", p.x(), p.y(), p.z());
  }
  out << fmt::format("VERTICES {} {}\n", n, 2 * n);
  for (int o = 0; o < n; ++o) out << "1 " << o << "\n";
  out << fmt::format("POINT_DATA {}\nNORMALS normal double\n", n);
  for (int o = 0; o < n; ++o) {
    const Vec3 v = dummy.normal(o);
    out << fmt::format("{:.17g} {:.17g} {:.17g}\n", v.x(), v.y(), v.z());
  }
  finish_written(out, file);
}

}  // namespace drape
