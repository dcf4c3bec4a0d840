#pragma once
#include <vector>

#include "integrators/interface/integrator.hpp"
#include "integrators/interface/integrator_declaration.hpp"
#include "integrators/interface/integrator_options.hpp"

namespace drape {

/// Extended position-based dynamics (Macklin, Mueller and Chentanez 2016, "XPBD: position-based
/// simulation of compliant constrained dynamics") with small steps (Macklin et al. 2019, "Small
/// steps in physics simulation"): each step of dt is `substeps` substeps of h; each substep
/// predicts x~ = x + h v', v' = v / (1 + h c_air / m) + h g (air damping by backward Euler, then
/// gravity), puts fixed particles on p(t + h), runs `iterations` sweeps over the constraints with
/// multipliers lambda started at 0, and sets v = (x - x_prev) / h. Springs are the distance
/// constraints C = |x_j - x_i| - L0 with compliance 1/k and XPBD's damping beta = c_s (the
/// model's spring damping exactly); contacts are C = sqrt(2 U_i / k_c) with compliance 1/k_c
/// (xpbd_constraints.hpp), with position-based Coulomb friction (apply_friction). After the step, the model's projection (docs/model.md section 5).
/// Sweeps: `gauss-seidel` over the springs in their colour order (colour_springs), then the
/// contacts; `jacobi` every constraint from one iterate with mass splitting (a particle of n
/// constraints has inverse mass n w in each). Converged, a substep is backward Euler of
/// the springs and contacts up to XPBD's dropped residual (docs/integrators/xpbd.md).
class Xpbd final : public Integrator {
 public:
  /// Reads dt and the keys substeps, iterations and sweep from `options`.
  Xpbd(ClothSystem& system, const IntegratorOptions& options);
  void reset(double t, const Eigen::VectorXd& y) override;
  double step(double t_stop) override;

 private:
  /// One substep of h ending at t_sub.
  void substep(double t_sub, double h);
  /// The multiplier increment of spring e (sweep order) at positions x with the weight
  /// grad C M^-1 grad C^T = `weight`, and its direction u (false for a spring with no free end
  /// or no length).
  bool spring_increment(Eigen::Index e, const double* x, double weight, double inv_h2,
                        double inv_h, double& increment, Vec3& u) const;
  /// The multiplier increment of particle i's contact at x as if its inverse mass were
  /// `inverse_mass`, and the contact's gradient (false: no contact).
  bool contact_increment(int i, const Vec3& x, double inverse_mass, double inv_h2,
                         double& increment, Vec3& gradient) const;
  /// One pass over the springs (sweep order), then the contacts, at positions x: multipliers
  /// booked, moves added to `target` (x itself for Gauss-Seidel), with the weights given.
  void sweep(const double* x, double* target, const Eigen::ArrayXd& spring_weight,
             const Eigen::ArrayXd& contact_weight, double inv_h2, double inv_h);
  /// Position-based Coulomb friction after a substep's sweeps (Macklin et al. 2014, section
  /// 6.1; docs/model.md section 4.12): each contact's tangential displacement over the substep
  /// shrinks by mu times its normal correction w |lambda| |grad C|, down to 0.
  void apply_friction();
  void sweep_gauss_seidel(double inv_h2, double inv_h);
  void sweep_jacobi(double inv_h2, double inv_h);

  double m_dt;
  int m_substeps;
  int m_iterations;
  bool m_jacobi;
  // Springs in sweep order (colour by colour), with what their update needs.
  Eigen::ArrayXi m_first, m_second;
  std::vector<Eigen::Index> m_colour_end;  // springs [end of the previous colour, end) per colour
  Eigen::ArrayXd m_rest, m_compliance, m_damping_ratio;  // L0, 1/k, c_s / k
  // Set at reset() from the fixed particles: inverse masses and Jacobi's split weights.
  Eigen::ArrayXd m_inverse_mass;                      // N, 0 for fixed particles
  Eigen::ArrayXd m_w_first, m_w_second;               // per spring
  Eigen::ArrayXd m_weight;         // per spring, w_i + w_j
  Eigen::ArrayXd m_split_weight;   // per spring, Jacobi: n_i w_i + n_j w_j
  Eigen::ArrayXd m_split_inverse_mass;  // per particle, Jacobi: n_i w_i
  std::vector<int> m_free;  // free particles, ascending
  // Substep scratch, sized once.
  Eigen::VectorXd m_previous;    // 3N, x at the substep's start
  Eigen::VectorXd m_correction;  // 3N, Jacobi's accumulated moves
  Eigen::ArrayXd m_lambda;       // per spring
  Eigen::ArrayXd m_contact_lambda;  // per particle
};

/// The declaration of `xpbd` (registry.cpp).
IntegratorDeclaration xpbd_declaration();

}  // namespace drape
