#include "core/collision.hpp"

#include <cmath>

namespace drape {

ContactFinder::ContactFinder(std::shared_ptr<const Dummy> dummy, double threshold,
                             int num_particles)
    : m_dummy(std::move(dummy)),
      m_threshold(threshold),
      // Half the threshold: lists of a few particles that last for many steps of a moving cloth.
      m_skin(0.5 * threshold),
      m_anchor(Eigen::VectorXd::Zero(3 * num_particles)),
      m_count(num_particles, not_built),
      m_candidates(static_cast<std::size_t>(num_particles) * capacity) {}

void ContactFinder::rebuild(int i, const Vec3& x) const {
  m_anchor.segment<3>(3 * i) = x;
  m_dummy->particles_within(x, m_threshold + m_skin, m_scratch);
  if (m_scratch.size() > static_cast<std::size_t>(capacity)) {
    m_count[i] = overflowed;
    return;
  }
  m_count[i] = static_cast<int>(m_scratch.size());
  std::copy(m_scratch.begin(), m_scratch.end(),
            m_candidates.begin() + static_cast<std::ptrdiff_t>(i) * capacity);
}

NearestObjectParticle ContactFinder::nearest(int i, const Vec3& x) const {
  if (m_count[i] == not_built || (x - m_anchor.segment<3>(3 * i)).squaredNorm() > m_skin * m_skin)
    rebuild(i, x);
  if (m_count[i] == overflowed) return m_dummy->nearest_within(x, m_threshold);

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
