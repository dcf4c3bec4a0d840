#pragma once
// The built-in dress form of docs/model.md section 3: a torso made from MakeHuman's default female body (CC0),
// whose cross-sections are compiled into the program (core/dummy/data/dress-form/, see
// core/CMakeLists.txt). How it is cut, capped at the shoulders and resampled: docs/dress_form.md.
#include <string_view>
#include <vector>

#include "core/dummy/dummy.hpp"

namespace drape {

/// Height of the dress form's bottom section (the hip line) in the body data, cm.
inline constexpr double kDressFormBottomCm = 75.5;
/// Height of the dress form's top section (the neck base) in the body data, cm.
inline constexpr double kDressFormTopCm = 134.5;

/// The dress form at the body data's own resolution: one section per centimetre from the neck
/// base down to the hip line, 72 rays, in metres (soles at y = 0, +z front), shoulders capped.
DummySections dress_form_profile();
/// The dress form resampled to sections x points (linear in height and angle).
DummySections dress_form_sections(int sections, int points);

namespace detail {

/// The compiled-in body cross-sections (CSV text of mh_default_female_torso_sections.csv).
extern const std::string_view dress_form_sections_csv;

/// One row of the body cross-section table, in centimetres as in the file.
struct BodySection {
  double height = 0.0;
  int flag = 0;  ///< 0 clean torso, 1 arm merged into the slice, 2 neck
  double cx = 0.0;
  double cz = 0.0;
  double girth_poly = 0.0;  ///< perimeter of the polar polygon
  double girth_hull = 0.0;  ///< convex-hull perimeter (a tape-measure girth)
  std::vector<double> radius;  ///< one per ray, every 360/size() degrees from +z towards +x
};

/// Parses the body cross-section CSV ('#' comment lines, one header line, then rows).
std::vector<BodySection> parse_body_sections(std::string_view csv);

/// The shoulder cap at height h_cm of a ray whose radius is r_clean in the last clean section
/// (height clean_cm) and r_top in the top section (height top_cm); see docs/dress_form.md.
double shoulder_cap(double h_cm, double clean_cm, double top_cm, double r_clean, double r_top);

}  // namespace detail
}  // namespace drape
