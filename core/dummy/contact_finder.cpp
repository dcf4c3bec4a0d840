#include "core/dummy/contact_finder.hpp"

#include <algorithm>

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
  // One list a thread: the force loop rebuilds lists of different particles at once.
  thread_local std::vector<int> scratch;
  m_anchor.segment<3>(3 * i) = x;
  m_dummy->particles_within(x, m_threshold + m_skin, scratch);
  if (scratch.size() > static_cast<std::size_t>(capacity)) {
    m_count[i] = overflowed;
    return;
  }
  m_count[i] = static_cast<int>(scratch.size());
  std::copy(scratch.begin(), scratch.end(),
            m_candidates.begin() + static_cast<std::ptrdiff_t>(i) * capacity);
}

// A list that is missing, left behind, or too long for the cache.
NearestObjectParticle ContactFinder::nearest_off_list(int i, const Vec3& x) const {
  if (m_count[i] == not_built || (x - m_anchor.segment<3>(3 * i)).squaredNorm() > m_skin * m_skin)
    rebuild(i, x);
  if (m_count[i] == overflowed) return m_dummy->nearest_within(x, m_threshold);
  return nearest(i, x);
}

}  // namespace drape
