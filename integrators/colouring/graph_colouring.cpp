#include "integrators/colouring/graph_colouring.hpp"

#include <algorithm>

namespace drape {

namespace {

// Greedy colouring of members 0..n-1 whose neighbours `neighbours(m, visit)` lists.
template <class Neighbours>
Colouring colour_greedily(int n, Neighbours&& neighbours) {
  std::vector<int> colour(static_cast<std::size_t>(n), -1);
  std::vector<int> taken_by;  // taken_by[c] == m: colour c is used by a neighbour of m
  Colouring colours;
  for (int m = 0; m < n; ++m) {
    neighbours(m, [&](int other) {
      const int c = colour[static_cast<std::size_t>(other)];
      if (c >= 0) taken_by[static_cast<std::size_t>(c)] = m;
    });
    int c = 0;
    while (c < static_cast<int>(colours.size()) && taken_by[static_cast<std::size_t>(c)] == m) ++c;
    if (c == static_cast<int>(colours.size())) {
      colours.emplace_back();
      taken_by.push_back(-1);
    }
    colour[static_cast<std::size_t>(m)] = c;
    colours[static_cast<std::size_t>(c)].push_back(m);
  }
  return colours;
}

// Springs incident to each particle, in spring order.
std::vector<std::vector<int>> incident_springs(int num_particles, const SpringList& springs) {
  std::vector<std::vector<int>> incident(static_cast<std::size_t>(num_particles));
  for (Eigen::Index e = 0; e < springs.size(); ++e) {
    incident[static_cast<std::size_t>(springs.first[e])].push_back(static_cast<int>(e));
    incident[static_cast<std::size_t>(springs.second[e])].push_back(static_cast<int>(e));
  }
  return incident;
}

}  // namespace

Colouring colour_particles(int num_particles, const SpringList& springs) {
  const auto incident = incident_springs(num_particles, springs);
  return colour_greedily(num_particles, [&](int i, auto&& visit) {
    for (int e : incident[static_cast<std::size_t>(i)])
      visit(springs.first[e] == i ? springs.second[e] : springs.first[e]);
  });
}

Colouring colour_springs(int num_particles, const SpringList& springs) {
  const auto incident = incident_springs(num_particles, springs);
  return colour_greedily(static_cast<int>(springs.size()), [&](int e, auto&& visit) {
    for (int end : {springs.first[e], springs.second[e]})
      for (int other : incident[static_cast<std::size_t>(end)])
        if (other != e) visit(other);
  });
}

}  // namespace drape
