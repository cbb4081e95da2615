// Kinetic theory of the tagged-particle VACF of a lattice gas (van der Hoef & Frenkel §3.3-3.4):
// the exact one-step VACF (eq 18 by enumeration, eq 19 in closed form), the Boltzmann diffusion
// coefficient (eq 20), the mean free time (eq 21) and the finite-size plateau (eq 22).
#pragma once

#include "narrows/engines/lgca/moment_propagation.hpp"

namespace narrows::lgca::theory {

// <|c|^2> over links: the mean square velocity of a particle when all links are equally full.
double mean_square_velocity(const Links &links);
// The same for the x component only (<v_x^2> of eq 20).
double mean_square_velocity_x(const Links &links);

// Z(1) = <v(0).v(1)> / <v^2> by summing eq 18 over all 2^b node states with independent
// occupations d. Exact for moment propagation with the equal split over outgoing particles;
// it does not depend on the collision table, because u(s) is conserved by any collision.
double one_step_vacf(const Links &links, double d);

// Eq 19 (Ernst and Naitoh): Z(1) = (1 - d) [1 - (1 - d)^(b-1)] / (d (b - 1)). Its derivation
// needs only sum_k c_k = 0 (so sum_{k != i} c_i.c_k = -c_i^2 for every link i) and the same d
// on every link: it also holds with a rest particle counted in b and with unequal speeds (the
// d'Humieres model, b = 5), as the enumeration of eq 18 confirms (unit test).
double one_step_vacf_closed_form(int b, double d);

// Eq 20: D0 = <v_x^2> [1/2 + Z(1) / (1 - Z(1))].
double boltzmann_diffusion(double v2x, double z1);

// Eq 21: t0 = -1 / ln Z(1) (Z(1) in (0, 1)).
double mean_free_time(double z1);

// Eq 22: the correction (1 - d)/N that turns the normalised VACF measured with fixed total
// momentum P = 0 into the one of the infinite system.
double finite_size_correction(double d, double n);

// Normalised VACF plateau of a periodic system of N particles once the tagged particle's own
// correlations have decayed (t >> t0) but before the momentum it shed, which leaves as sound
// pulses, has come back around the system (t < L / c_s in 1D):
//   Z = <P^2> / (N^2 <v^2>) - (1 - d) / N,
// where m2 = <P^2> / (N <v^2>) describes the ensemble: 0 for P = 0 exactly (Z = -(1 - d)/N,
// the paper's plateau), 1 - d for independent occupations (Z = 0). Once the pulses have spread
// evenly (t >> L^2 / Gamma) the tagged particle moves with the centre of mass, Z -> m2 / N.
double intermediate_plateau(double d, double n, double m2);
double long_time_limit(double n, double m2);

} // namespace narrows::lgca::theory
