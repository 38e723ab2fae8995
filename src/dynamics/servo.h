/* servo.h — the velocity of a servo-controlled wall (single source, SD_HD).
 *
 * Seed 002 §3.2 confines its biaxial sample with walls held at a confining
 * pressure of 100 kPa while the top wall loads it at a prescribed rate. The
 * servo is the usual one of DEM biaxial tests (PFC's wall servo): each step
 * the wall's velocity along its inward normal is
 *
 *     v = G (sigma_target - sigma) + I,   |v| <= v_max,
 *
 * with sigma the normal stress the wall carries (force / contact length in
 * 2D, per unit thickness). Moving the wall by v dt changes the force by
 * about k_sum v dt (k_sum: the normal stiffness of its contacts), so the
 * gain that cancels the stress error in one step is L / (k_sum dt); the
 * automatic gain takes half of it (alpha = 0.5), which converges without
 * overshoot for a stiffness that does not change much in one step.
 *
 * Invariant: no allocation, no printing; plain reals in and out.
 */
#ifndef SD_DYNAMICS_SERVO_H
#define SD_DYNAMICS_SERVO_H

#include "core/base.h"

/* Fraction of the one-step gain used by the automatic gain. */
#define SD_SERVO_ALPHA SD_R(0.5)
/* Integral time of the servo, in steps. A proportional servo lags a wall
 * that has to keep moving (a sample dilating under loading pushes the side
 * walls out at v): its stress error settles at v / G, about 2 % in seed
 * 002's test. The integral term I += (dt / T_i) G e removes that error; T_i
 * of 200 steps is an order above the time the packing takes to pass a wall
 * displacement on (its width over the contact wave speed, about 150 steps
 * there), so the term adds no oscillation. */
#define SD_SERVO_INTEGRAL_STEPS SD_R(200.0)

/* Gain ((m/s)/Pa) from the contact length or area (m or m^2), the summed
 * normal stiffness of the wall's contacts (N/m) and the time step. Returns 0
 * when the wall touches nothing (the caller then moves at the cap). */
SD_HD static SD_INLINE sd_real sd_servo_auto_gain(sd_real area, sd_real k_sum, sd_real dt)
{
    return k_sum > SD_R(0.0) ? SD_SERVO_ALPHA * area / (k_sum * dt) : SD_R(0.0);
}

/* Velocity (m/s) along the wall's normal (into the particles) for a stress
 * error, proportional plus integral: *integral (m/s) is the integral term,
 * updated here and kept within the cap (no wind-up). gain <= 0 means "no
 * contact yet": move at the cap towards the particles when the wall carries
 * too little, away when too much, and forget the integral. */
SD_HD static SD_INLINE sd_real sd_servo_speed(sd_real stress, sd_real target, sd_real gain, sd_real v_max,
                                              sd_real *integral)
{
    sd_real err = target - stress;
    if (!(gain > SD_R(0.0))) {
        *integral = SD_R(0.0);
        return err > SD_R(0.0) ? v_max : (err < SD_R(0.0) ? -v_max : SD_R(0.0));
    }
    *integral = sd_clamp(*integral + gain * err / SD_SERVO_INTEGRAL_STEPS, -v_max, v_max);
    return sd_clamp(gain * err + *integral, -v_max, v_max);
}

#endif
