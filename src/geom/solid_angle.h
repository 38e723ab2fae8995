/* solid_angle.h — the signed solid angle a triangle subtends at a point
 * (van Oosterom and Strackee, IEEE Trans. Biomed. Eng. 30, 1983: tan(W/2)
 * = det[a b c] / (|a||b||c| + (a.b)|c| + (a.c)|b| + (b.c)|a|), with a, b,
 * c the corners seen from the point). Summed over a closed surface and
 * divided by 4 pi it is the winding number: +-1 inside, 0 outside, the
 * sign that of the triangles' orientation. Host code: the insertion's
 * inside tests of mesh regions and mesh walls; its atan2 is core/math.h's,
 * as every header of geom/ (tests/cli/sd_hd_libm.sh), which rounds to 1 ulp
 * of libm's and cannot move a winding number's 0 or +-1.
 */
#ifndef SD_GEOM_SOLID_ANGLE_H
#define SD_GEOM_SOLID_ANGLE_H

#include <math.h>

#include "core/math.h"

/* sr, corners a, b, c already relative to the point */
static inline double sd_solid_angle(const double a[3], const double b[3], const double c[3])
{
    double la = sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]), lb = sqrt(b[0] * b[0] + b[1] * b[1] + b[2] * b[2]);
    double lc = sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
    double det = a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) +
                 a[2] * (b[0] * c[1] - b[1] * c[0]);
    double ab = a[0] * b[0] + a[1] * b[1] + a[2] * b[2], ac = a[0] * c[0] + a[1] * c[1] + a[2] * c[2];
    double bc = b[0] * c[0] + b[1] * c[1] + b[2] * c[2];
    return 2 * sd_math_atan2(det, la * lb * lc + ab * lc + ac * lb + bc * la);
}

#endif
