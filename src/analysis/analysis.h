/* analysis.h — what the analyses of shapedem/analysis.h share: the
 * particles as they see them, regions, the true-shape inside test and a
 * particle's highest point.
 *
 * Invariant: the analyses read the world only through the solver
 * interface (sd_world_get_particle: the grid's spheres count too) and the
 * shape templates, never change it, and gather the particles in storage
 * order, so every sum runs in one fixed order whatever the thread count.
 */
#ifndef SD_ANALYSIS_ANALYSIS_H
#define SD_ANALYSIS_ANALYSIS_H

#include <shapedem/analysis.h>

#include "core/error.h"
#include "core/quat.h"
#include "world/world.h"

/* A particle as the analyses see it. */
typedef struct sd_an_body {
    sd_vec3 x, v, w; /* m, m/s, rad/s (world frame) */
    sd_quat q;       /* principal frame to world */
    sd_real mass;    /* kg (0: fixed, taken as massless in the sums) */
    sd_real bound;   /* m, bounding radius (a sphere's radius) */
    int shape;       /* template (3D: w->shapes, 2D: w->shapes2d), -1 a sphere (a circle in 2D) */
} sd_an_body;

typedef struct sd_an_set {
    size_t n;
    sd_an_body *b;
    sd_vec3 up; /* unit: -gravity, or +z (+y in 2D) without gravity */
    int dim2;
} sd_an_set;

/* Reads every particle (storage order); SD_ERR_MEMORY on failure. */
sd_status sd_an_gather(const sd_world *w, sd_an_set *out, sd_error *err);
void sd_an_free(sd_an_set *s);

/* A region as the tests need it: box, or cylinder with its unit axis and
 * two unit vectors e1, e2 completing a right-handed frame (e1 x e2 = a). */
typedef struct sd_an_region {
    int kind; /* SD_REGION_NONE (all), _BOX, _CYLINDER */
    sd_vec3 lo, hi;
    sd_vec3 c, a, e1, e2;
    sd_real radius, half; /* m; half length (2D: unbounded along the axis) */
    sd_vec3 blo, bhi;     /* m, its bounding box */
} sd_an_region;

/* SD_ERR_INPUT (key "region") for an empty region or a zero axis. */
sd_status sd_an_region_make(const sd_region_def *r, int dim2, sd_an_region *out, sd_error *err);
int sd_an_region_has(const sd_an_region *r, sd_vec3 x);

/* Is the world point p inside the true shape of b? */
int sd_an_inside(const sd_world *w, const sd_an_body *b, sd_vec3 p);
/* The highest point of b's true shape along unit u (the support). */
sd_real sd_an_top(const sd_world *w, const sd_an_body *b, sd_vec3 u);

/* Body-frame rotational energy of b (J): inertia from the template (mass
 * x second moment per volume), a sphere's 2/5 m r^2 (a disc's 1/2 m r^2). */
double sd_an_rot_energy(const sd_world *w, const sd_an_body *b);

#endif
