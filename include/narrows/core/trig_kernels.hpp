// fdlibm's k_sin.c and k_cos.c kernels: sin and cos of x for |x| <= pi/4 by minimax polynomials
// (error < 2^-58; without fdlibm's tail of the reduced argument), and the quadrant's swap and
// signs. Plain expressions, without a branch: loops over them vectorise. Their callers reduce
// the argument (rng_batch.cpp from a 32-bit integer angle, the sine force by pi/2).
#pragma once

namespace narrows::trig {

// sin x and cos x for |x| <= pi/4.
inline void kernel_sincos(double x, double &sine, double &cosine) {
  constexpr double S1 = -1.66666666666666324348e-01, S2 = 8.33333333332248946124e-03,
                   S3 = -1.98412698298579493134e-04, S4 = 2.75573137070700676789e-06,
                   S5 = -2.50507602534068634195e-08, S6 = 1.58969099521155010221e-10;
  constexpr double C1 = 4.16666666666666019037e-02, C2 = -1.38888888888741095749e-03,
                   C3 = 2.48015872894767294178e-05, C4 = -2.75573143513906633035e-07,
                   C5 = 2.08757232129817482790e-09, C6 = -1.13596475577881948265e-11;
  const double z = x * x;
  sine = x + x * z * (S1 + z * (S2 + z * (S3 + z * (S4 + z * (S5 + z * S6)))));
  const double hz = 0.5 * z, w = 1.0 - hz;
  cosine =
      w + (((1.0 - w) - hz) + z * z * (C1 + z * (C2 + z * (C3 + z * (C4 + z * (C5 + z * C6))))));
}

// sin and cos of x + q pi/2 from s = sin x, c = cos x: (s, c), (c, -s), (-s, -c), (-c, s).
inline void to_quadrant(unsigned q, double s, double c, double &sine, double &cosine) {
  const bool swap = q & 1u;
  const double s1 = swap ? c : s, c1 = swap ? s : c;
  sine = s1 * ((q & 2u) ? -1.0 : 1.0);
  cosine = c1 * (((q + 1u) & 2u) ? -1.0 : 1.0);
}

} // namespace narrows::trig
