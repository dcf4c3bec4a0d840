#pragma once
// Parameters of the paper's manipulations (docs/model.md section 7), read from a scene's
// `manipulation` object.
#include "core/cloth/cloth.hpp"

namespace drape {

/// Parameters of the paper's manipulations (docs/model.md section 7).
struct ManipulationParams {
  double hold_threshold = 0.05;  ///< hand-to-candidate distance that starts a hold [m]
  bool release_held = true;      ///< `r` frees the held particle(s) ...
  GridPoint release_pin;         ///< ... or, when release_held is false, this pin
  int attach_iterations = 100;   ///< steps of dynamics before an attached particle is fixed
  /// When positive, seconds of dynamics before an attached particle is fixed, instead of
  /// attach_iterations steps: the same dwell at every step size (docs/model.md section 7).
  double attach_time = 0.0;
  double hold_ramp = 0.0;         ///< seconds a new hold blends onto the hand; 0: the paper's snap
  bool attach_at_contact_distance = false;  ///< attach onto p_o + delta n_o instead of p_o
  double map_top = 1.25;         ///< height of row 0 after mapping [m]
  int map_direction = 1;         ///< +1: columns go towards +x from the centre line
};

}  // namespace drape
