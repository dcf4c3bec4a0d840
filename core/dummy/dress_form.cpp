#include "core/dummy/dress_form.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <stdexcept>
#include <string>

#include "core/dummy/dummy_sources.hpp"

namespace drape {

namespace detail {

namespace {

constexpr std::string_view kHeaderStart = "height_cm,flag,cx,cz,girth_poly_cm,girth_hull_cm,";
constexpr int kLeadingColumns = 6;

// Squareness of the shoulder cap (the exponent of a superellipse quadrant): 2 would be a round
// quarter ellipse that starts narrowing right above the armpit; 4 keeps the side nearly
// vertical through the armhole, as on a dress form whose arm plates stand where the arms were,
// and rounds it into the shoulder only over its last few centimetres.
constexpr double kShoulderSquareness = 4.0;

std::vector<double> split_numbers(const std::string& line, int line_number) {
  std::vector<double> values;
  const char* s = line.c_str();
  for (;;) {
    char* end = nullptr;
    const double v = std::strtod(s, &end);
    if (end == s || !std::isfinite(v))
      throw std::invalid_argument("dress-form sections CSV, line " + std::to_string(line_number) +
                                  ": expected a number at '" + std::string(s) + "'");
    values.push_back(v);
    s = end;
    if (*s == '\0' || *s == '\r') return values;
    if (*s != ',')
      throw std::invalid_argument("dress-form sections CSV, line " + std::to_string(line_number) +
                                  ": expected ','");
    ++s;
  }
}

}  // namespace

std::vector<BodySection> parse_body_sections(std::string_view csv) {
  std::vector<BodySection> rows;
  int rays = -1;  // from the header
  int line_number = 0;
  size_t pos = 0;
  while (pos < csv.size()) {
    const size_t eol = std::min(csv.find('\n', pos), csv.size());
    const std::string line(csv.substr(pos, eol - pos));
    pos = eol + 1;
    ++line_number;
    if (line.empty() || line[0] == '#' || line == "\r") continue;
    if (rays < 0) {
      if (line.compare(0, kHeaderStart.size(), kHeaderStart) != 0)
        throw std::invalid_argument("dress-form sections CSV: unexpected header '" + line + "'");
      rays = static_cast<int>(std::count(line.begin(), line.end(), ',')) + 1 - kLeadingColumns;
      continue;
    }
    const std::vector<double> v = split_numbers(line, line_number);
    if (static_cast<int>(v.size()) != kLeadingColumns + rays)
      throw std::invalid_argument("dress-form sections CSV, line " + std::to_string(line_number) +
                                  ": expected " + std::to_string(kLeadingColumns + rays) +
                                  " columns");
    BodySection row;
    row.height = v[0];
    row.flag = static_cast<int>(v[1]);
    row.cx = v[2];
    row.cz = v[3];
    row.girth_poly = v[4];
    row.girth_hull = v[5];
    row.radius.assign(v.begin() + kLeadingColumns, v.end());
    rows.push_back(std::move(row));
  }
  if (rows.empty() || rays < 3)
    throw std::invalid_argument("dress-form sections CSV: no data rows");
  return rows;
}

double shoulder_cap(double h_cm, double clean_cm, double top_cm, double r_clean, double r_top) {
  const double s = std::clamp((h_cm - clean_cm) / (top_cm - clean_cm), 0.0, 1.0);
  return r_top + (r_clean - r_top) *
                     std::pow(1.0 - std::pow(s, kShoulderSquareness), 1.0 / kShoulderSquareness);
}

}  // namespace detail

DummySections dress_form_profile() {
  static const std::vector<detail::BodySection> rows =
      detail::parse_body_sections(detail::dress_form_sections_csv);
  constexpr double kTolCm = 1e-6;
  std::vector<const detail::BodySection*> torso;  // top first
  const detail::BodySection* clean = nullptr;     // highest clean (flag 0) section
  for (auto it = rows.rbegin(); it != rows.rend(); ++it) {
    if (it->height > kDressFormTopCm + kTolCm || it->height < kDressFormBottomCm - kTolCm)
      continue;
    torso.push_back(&*it);
    if (it->flag == 0 && (!clean || it->height > clean->height)) clean = &*it;
  }
  if (torso.size() < 2 || !clean || std::abs(torso.front()->height - kDressFormTopCm) > kTolCm ||
      std::abs(torso.back()->height - kDressFormBottomCm) > kTolCm)
    throw std::logic_error("dress-form sections CSV does not cover the dress form's heights");
  const detail::BodySection& top = *torso.front();

  // Above the last clean section the slices include the arm (flag 1) and then the neck and the
  // shoulder slope (flag 2): every ray is limited by the shoulder cap, which runs from the clean
  // section's radius down to the neck base's radius along the same ray. The body's own radii
  // stay wherever they are smaller (front, back, the real shoulder slope near the neck).
  const int n = static_cast<int>(torso.size());
  const int rays = static_cast<int>(top.radius.size());
  constexpr double kMetresPerCm = 0.01;
  DummySections out;
  out.radius.resize(n, rays);
  for (int k = 0; k < n; ++k) {
    const detail::BodySection& row = *torso[k];
    out.y.push_back(kMetresPerCm * row.height);
    out.cx.push_back(kMetresPerCm * row.cx);
    out.cz.push_back(kMetresPerCm * row.cz);
    for (int j = 0; j < rays; ++j) {
      double r = row.radius[j];
      if (row.height > clean->height)
        r = std::min(r, detail::shoulder_cap(row.height, clean->height, top.height,
                                             clean->radius[j], top.radius[j]));
      out.radius(k, j) = kMetresPerCm * r;
    }
  }
  return out;
}

DummySections dress_form_sections(int sections, int points) {
  return resample_sections(dress_form_profile(), sections, points);
}

}  // namespace drape
