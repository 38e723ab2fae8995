/* shapedem/analysis.h — what users measure on a packing or a flow (issue
 * 16): porosity by a voxel lattice of the true shapes, coordination
 * numbers, energies and speeds, a binned velocity field, the bed height,
 * the free-surface angle of a drum and the angle of repose of a heap. Part
 * of the public API (include after or instead of shapedem.h); the
 * scene's analysis: section (docs/analysis.md) writes each as CSV at a
 * cadence through these calls.
 *
 * Every call reads the world between steps and changes nothing; the
 * particles are those the solver holds (sd_world_get_particle), every kind
 * (spheres, convex shapes, polyhedra, composites, 2D shapes). Heights are
 * measured along "up", -gravity normalised (+z, in 2D +y, without
 * gravity). Results are the same bits for any thread count.
 */
#ifndef SHAPEDEM_ANALYSIS_H
#define SHAPEDEM_ANALYSIS_H

#include <shapedem/process.h>
#include <shapedem/shapedem.h>

#ifdef __cplusplus
extern "C" {
#endif

/* ---- porosity by voxels ([Rakotonirina 2019] §4.1) -------------------------
 * The region (a box, or a cylinder: center, axis, radius, length) is cut
 * into voxels of edge `voxel` (adjusted per axis so they tile a box
 * exactly; a cylinder's lattice is cut in its own frame and keeps the
 * voxels whose centre lies inside). A voxel is solid when its centre is
 * inside the true shape of some particle (a union: overlapping particles
 * count once); periodic images are included. In 2D the voxels are pixels
 * of the plane z = 0 and the region a rectangle or (cylinder) a disc, so
 * the fraction is an area fraction. */
typedef struct sd_porosity_def {
    sd_region_def region; /* SD_REGION_BOX or SD_REGION_CYLINDER */
    double voxel;         /* m, voxel edge, > 0 */
    int radial_bins;      /* cylinder: annuli of equal width about the axis (0: none) */
    int threads;          /* OpenMP threads, <= 0: the world's */
    int cookie;
} sd_porosity_def;

sd_porosity_def sd_porosity_def_default(void);

typedef struct sd_porosity {
    long long voxels;      /* voxel centres in the region */
    long long solid;       /* of those, inside a particle */
    double solid_fraction; /* solid / voxels (packing fraction) */
    double porosity;       /* 1 - solid_fraction */
    double voxel[3];       /* m, the edges used (the cylinder's: u, v, axis) */
    double volume;         /* m^3 (m^2 in 2D): voxels x voxel volume */
} sd_porosity;

/* radial_solid, radial_voxels: radial_bins counts each (bin k spans radii
 * [k, k + 1) R / bins), or NULL. SD_ERR_INPUT for a bad def or more than
 * SD_POROSITY_MAX_VOXELS voxels. */
#define SD_POROSITY_MAX_VOXELS 4000000000LL
sd_status sd_world_porosity(const sd_world *w, const sd_porosity_def *def, sd_porosity *out, long long *radial_solid,
                            long long *radial_voxels, sd_error *err);

/* ---- coordination ------------------------------------------------------------
 * From the current contact list (cells solver): two particles are in
 * contact when one of their pairs (for composites: element pairs) had an
 * overlap > 0 at the last force evaluation; a particle and a wall feature
 * (a plane, a box face, a mesh plane group, the drum) alike. Z_i counts
 * the particles particle i touches; the walls are counted apart. With a
 * region (NULL or kind NONE: all), only the particles whose centre lies
 * in it are counted, with all their contacts (e.g. the core of a drum's
 * bed, away from its walls). */
#define SD_COORDINATION_MAX 24

typedef struct sd_coordination {
    size_t particles;                          /* counted (in the region) */
    long contacts;                             /* particle-particle contacts of the counted particles */
    long wall_contacts;                        /* their particle-wall-feature contacts */
    double mean;                               /* mean Z (2 contacts / particles without a region) */
    double mean_with_walls;                    /* mean of Z + wall contacts */
    size_t rattlers;                           /* particles touching neither a particle nor a wall */
    size_t histogram[SD_COORDINATION_MAX + 1]; /* particles with Z = k; the last entry: Z >= MAX */
} sd_coordination;

sd_status sd_world_coordination(const sd_world *w, const sd_region_def *region, sd_coordination *out,
                                sd_error *err);

/* ---- motion ------------------------------------------------------------------
 * region: only particles whose centre lies in it (NULL or kind NONE: all). */
typedef struct sd_motion_stats {
    size_t particles;
    double mass;                  /* kg */
    double kinetic_translational; /* J, sum m v^2 / 2 */
    double kinetic_rotational;    /* J, sum w_b . I w_b / 2, body frame */
    double mean_speed, max_speed; /* m/s */
    sd_v3d mean_velocity;         /* m/s, by number */
} sd_motion_stats;

sd_status sd_world_motion_stats(const sd_world *w, const sd_region_def *region, sd_motion_stats *out, sd_error *err);

/* Histogram of speeds: bins of equal width over [0, max_speed) (max_speed
 * <= 0: the fastest particle's speed; a speed at or above the top goes in
 * the last bin). counts: bins entries. *top: the upper edge used (m/s). */
sd_status sd_world_speed_histogram(const sd_world *w, const sd_region_def *region, int bins, double max_speed,
                                   size_t *counts, double *top, sd_error *err);

/* Mean velocity per cell of a 2D grid on a plane: the particles whose
 * centre lies in the box region (a slab) are binned by their two in-plane
 * coordinates (plane 0: x, y; 1: x, z; 2: y, z) into cells[0] x cells[1]
 * cells over the box's extent; cell (i, j) is entry i + cells[0] j. */
typedef struct sd_velocity_field_def {
    sd_region_def region; /* SD_REGION_BOX */
    int plane;            /* 0 xy, 1 xz, 2 yz */
    int cells[2];         /* >= 1 each */
    int cookie;
} sd_velocity_field_def;

sd_velocity_field_def sd_velocity_field_def_default(void);
/* count, mean: cells[0] * cells[1] entries (mean 0 where count is 0). */
sd_status sd_world_velocity_field(const sd_world *w, const sd_velocity_field_def *def, size_t *count, sd_v3d *mean,
                                  sd_error *err);

/* ---- bed and surfaces -------------------------------------------------------- */
typedef struct sd_bed_height {
    size_t particles;
    double top;             /* m, the highest point of any particle's true shape, along up */
    double fraction_height; /* m, height below which `fraction` of the mass lies (centres) */
    double mean;            /* m, mass-weighted mean height of the centres */
} sd_bed_height;

sd_status sd_world_bed_height(const sd_world *w, const sd_region_def *region, double fraction, sd_bed_height *out,
                              sd_error *err);

/* A free surface fitted by least squares: the surface height in each of
 * `bins` columns is the highest point of the particles in it; the line
 * through the columns within the fit range gives the angle. */
typedef struct sd_surface_fit {
    double angle; /* degrees, >= 0: the surface's inclination from horizontal */
    double slope; /* -, dh/ds of the fitted line (signed) */
    double rms;   /* m, root mean square of the columns about the line */
    int columns;  /* columns in the fit (at least 2 for an angle; 0: none) */
} sd_surface_fit;

/* Drum (a cylinder region: the drum's inside; its axis not vertical): in
 * the cross section, s = (x - center) . e runs across the drum along the
 * horizontal e = up x axis / |up x axis|; the columns split the diameter
 * [-R, R] and fit[0..1] are the fractions of it fitted (0.2, 0.8: the
 * middle 60 %). Only particles inside the cylinder count. */
sd_status sd_world_drum_surface(const sd_world *w, const sd_region_def *drum, int bins, const double fit[2],
                                sd_surface_fit *out, sd_error *err);

/* Heap: columns are annuli about the vertical line through center (NULL:
 * the particles' centre of mass) out to the heap's radius R, within which
 * 98 % of the centres lie (the few that rolled away are left out);
 * fit[0..1] are fractions of R (0.2, 0.8). slope is dh/dr (negative for a
 * heap). 2D: both flanks, the horizontal distance from the centre as r. */
sd_status sd_world_heap_angle(const sd_world *w, const sd_v3d *center, int bins, const double fit[2],
                              sd_surface_fit *out, sd_error *err);

#ifdef __cplusplus
}
#endif

#endif
