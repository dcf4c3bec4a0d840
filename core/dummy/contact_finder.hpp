#pragma once
// The collision query of the paper's section 2.3 for every cloth particle at every force
// evaluation: its nearest object particle within the threshold delta. Cloth particles move
// little between evaluations, so each keeps a candidate list (a Verlet list, as in molecular
// dynamics): the object particles within delta + skin of an anchor point. While the particle
// stays within `skin` of its anchor, every object particle within delta of it is on the list
// (triangle inequality), so scanning the list gives exactly the grid's answer, ties included.
#include <cmath>
#include <memory>
#include <vector>

#include "core/dummy/dummy.hpp"

namespace drape {

/// Nearest object particle within the collision threshold, per cloth particle, with cached
/// candidate lists. Results equal Dummy::nearest_within(x, threshold) bit for bit.
class ContactFinder {
 public:
  ContactFinder(std::shared_ptr<const Dummy> dummy, double threshold, int num_particles);

  /// Nearest object particle to x (the position of cloth particle i) closer than the threshold.
  NearestObjectParticle nearest(int i, const Vec3& x) const;
  double threshold() const { return m_threshold; }

 private:
  static constexpr int capacity = 24;     // candidates per particle before falling back
  static constexpr int not_built = -1;    // the list has never been built
  static constexpr int overflowed = -2;   // too many candidates: ask the grid directly

  void rebuild(int i, const Vec3& x) const;
  NearestObjectParticle nearest_off_list(int i, const Vec3& x) const;

  std::shared_ptr<const Dummy> m_dummy;
  double m_threshold;
  double m_skin;
  // Caches, invisible in results: mutable so that force evaluation stays a const query. Each
  // particle's entries are written only by the evaluation of that particle (the force loop's
  // threads, core/parallel).
  mutable Eigen::VectorXd m_anchor;          // 3N
  mutable std::vector<int> m_count;          // N: list length, not_built or overflowed
  mutable std::vector<int> m_candidates;     // N * capacity object particle indices, ascending
};

// The force evaluation's hot path, inline: it runs for every cloth particle at every evaluation.

inline NearestObjectParticle ContactFinder::nearest(int i, const Vec3& x) const {
  if (m_count[i] < 0 || (x - m_anchor.segment<3>(3 * i)).squaredNorm() > m_skin * m_skin)
    return nearest_off_list(i, x);
  const double* positions = m_dummy->positions().data();
  const int* list = m_candidates.data() + static_cast<std::ptrdiff_t>(i) * capacity;
  int best = -1;
  double best_d2 = m_threshold * m_threshold;
  // The list is ascending, so a strict comparison keeps the lowest index among ties, as the
  // grid does.
  for (int c = 0; c < m_count[i]; ++c) {
    const double d2 = detail::distance_squared(positions + 3 * list[c], x);
    if (d2 < best_d2) best_d2 = d2, best = list[c];
  }
  if (best < 0) return {};
  return {best, std::sqrt(best_d2)};
}

}  // namespace drape
