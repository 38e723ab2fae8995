/* shapedem/process.h — process set-ups of the cells solver (issue 16):
 * insertion of particles into a region, outlets that remove and count
 * them. Part of the public API (include after or instead of shapedem.h).
 *
 * Insertion (seed 004 §4.1, random sequential addition with retries):
 * each particle takes an entry of the mix (a template, or a sphere with a
 * size distribution), a random position in the region (its bounding
 * sphere inside the region; a mesh region: its centre inside the closed
 * mesh by the winding number, the sphere clear of every triangle) and,
 * for shaped bodies, a random orientation
 * uniform over all rotations, from the insertion's own stream of the
 * world's seed; a position is taken when the bounding sphere overlaps the
 * bounding sphere of no particle present (of any insertion or generator,
 * periodic images included), else another is tried, up to `attempts`.
 * Particles are inserted between steps: all at once at `start`, or at a
 * rate (particles/s or kg/s) from `start` on. What does not fit is tried
 * again at the next insertion time (a rate) or given up (all at once);
 * sd_world_get_insertion says how many were asked for, how many went in
 * and why the others did not.
 *
 * Outlets: a region (box or cylinder) that removes every particle whose
 * centre lies in it, from open_at on, checked every check_every steps;
 * each counts the particles and mass it removed. At any time, particles
 * present + removed = initial + inserted (sd_world_get_process).
 *
 * The grid solver has its own pour and floor outlet (sd_world_set_pour,
 * sd_world_set_outlet); these calls are for the cells solver.
 */
#ifndef SHAPEDEM_PROCESS_H
#define SHAPEDEM_PROCESS_H

#include <shapedem/shapedem.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef enum sd_region_kind {
    SD_REGION_NONE,     /* not given */
    SD_REGION_BOX,      /* lo, hi */
    SD_REGION_CYLINDER, /* center (the middle of its axis), axis, radius, length */
    SD_REGION_DISC,     /* center, axis (its normal), radius: centres on a flat disc (insertion only) */
    SD_REGION_MESH      /* the inside of a closed triangle mesh (insertion only, 3D) */
} sd_region_kind;

typedef struct sd_region_def {
    int kind;          /* sd_region_kind */
    sd_v3d lo, hi;     /* m, box corners */
    sd_v3d center;     /* m */
    sd_v3d axis;       /* cylinder axis or disc normal, any length > 0 */
    double radius;     /* m */
    double length;     /* m, cylinder */
    /* mesh: a closed surface (every edge shared by exactly two triangles),
     * world frame, either winding; copied by sd_world_add_insertion */
    const sd_v3d *vertices;            /* m */
    size_t vertex_count;
    const uint32_t (*triangles)[3];
    size_t triangle_count;
} sd_region_def;

/* Radius distribution of inserted spheres (m). */
typedef enum sd_size_kind {
    SD_SIZE_FIXED,     /* a */
    SD_SIZE_UNIFORM,   /* uniform in [a, b) */
    SD_SIZE_NORMAL,    /* mean a, standard deviation b, truncated to [min, max] */
    SD_SIZE_LOGNORMAL, /* median a, standard deviation b of ln r, truncated to [min, max] */
    SD_SIZE_TABLE      /* sieve classes [lo[k], hi[k]) with fractions (by number, or by mass when
                          by_mass), the radius uniform in its class */
} sd_size_kind;

#define SD_SIZE_CLASSES_MAX 16
/* The most positions tried per particle (sd_insert_def.attempts). */
#define SD_INSERT_ATTEMPTS_MAX 100000
/* An insertion all at once (a count, no rate) stops after this many
 * particles in a row found no free spot: the region is full. */
#define SD_INSERT_GIVE_UP 1000
/* A normal or log-normal law's largest radius (8 standard deviations, or
 * its truncation max) is at most this many times its mean or median. */
#define SD_SIZE_SPREAD_MAX 1e4

typedef struct sd_size_def {
    int kind;                             /* sd_size_kind */
    double a, b;                          /* m (lognormal b: -) */
    double min, max;                      /* m, truncation (normal, lognormal); max 0 = none */
    int classes;                          /* table */
    double lo[SD_SIZE_CLASSES_MAX], hi[SD_SIZE_CLASSES_MAX];
    double fraction[SD_SIZE_CLASSES_MAX]; /* sum to 1 */
    int by_mass;                          /* table fractions by mass */
} sd_size_def;

#define SD_INSERT_MIX_MAX 8

/* Scaled copies a template entry's size law may take (size_classes). */
#define SD_SIZE_SCALES_MAX 32

typedef struct sd_insert_entry {
    int shape;          /* template index (sd_world_add_shape, _shape2d, _composite), -1: a sphere */
    int material;
    sd_size_def size;   /* spheres: their radius. A template: its equivalent radius (of the sphere of
                           equal volume; 2D: the circle of equal area), the template scaled to it;
                           kind SD_SIZE_FIXED with a = 0 (all zero): the template as it is */
    double fraction;    /* share of the mix, by number or (mix_by_mass) by mass; the fractions sum to 1 */
    int size_classes;   /* a template with a size law: the law is cut into this many classes, one
                           scaled copy of the template each (sd_world_add_scaled_shape); 0 = 16, at
                           most SD_SIZE_SCALES_MAX. Continuous laws: classes of equal probability;
                           a sieve table: each class cut into size_classes / classes of equal width.
                           A class's copy has the radius (E[r^3 | class])^(1/3) (2D: r^2, ^(1/2)), so
                           the mean volume, and the mix by mass, are the law's */
} sd_insert_entry;

typedef struct sd_insert_def {
    const char *name;
    sd_region_def region;
    int entry_count;
    sd_insert_entry entries[SD_INSERT_MIX_MAX];
    int mix_by_mass;
    size_t count;       /* particles in all (or 0 and mass > 0) */
    double mass;        /* kg in all, when count is 0 */
    double rate;        /* particles/s from start; 0 with mass_rate 0: all at once */
    double mass_rate;   /* kg/s from start (instead of rate) */
    double start;       /* s */
    sd_v3d velocity;    /* m/s, initial */
    double velocity_jitter; /* m/s, uniform +- per component */
    int random_orientation; /* 1 (default): shaped bodies uniform over rotations */
    int attempts;       /* positions tried per particle (100; at most SD_INSERT_ATTEMPTS_MAX) */
    int cookie;
} sd_insert_def;

sd_insert_def sd_insert_def_default(void);
sd_size_def sd_size_def_fixed(double radius);

/* Adds an insertion (before or between steps); its index, or -1 with err
 * filled: a region that is empty or not inside the periodic box, a mix
 * whose fractions do not sum to 1, a negative or empty size range, an
 * unknown template or material. A template entry with a size law adds
 * its scaled copies now (named TEMPLATE_iIeEsK: insertion I, or the next
 * number whose names are free, entry E, class K), so add such an insertion before the first step (between
 * steps the new templates make the world prepare again). */
int sd_world_add_insertion(sd_world *w, const sd_insert_def *def, sd_error *err);

/* A copy of template `shape` with every length times scale (volume
 * scale^3, moments scale^5; 2D: area scale^2, polar moment scale^4),
 * any kind: convex, polyhedron, composite (its element templates scaled
 * too, named NAME.eJ) or 2D. Its index, or -1 with err filled. */
int sd_world_add_scaled_shape(sd_world *w, int shape, double scale, const char *name, sd_error *err);

typedef struct sd_insert_info {
    const char *name;
    size_t asked;        /* particles due so far (all of them once the insertion has run out) */
    size_t inserted;
    double mass;         /* kg inserted */
    size_t target;       /* particles in all (count, or inserted so far for a mass target) */
    int done;            /* inserted all it was asked for, or gave up */
    char why[256];       /* why some did not go in, "" when all did */
} sd_insert_info;

size_t sd_world_insertion_count(const sd_world *w);
sd_status sd_world_get_insertion(const sd_world *w, size_t k, sd_insert_info *out);

typedef struct sd_region_outlet_def {
    const char *name;
    sd_region_def region; /* box or cylinder */
    double open_at;       /* s */
    long check_every;     /* steps between checks (1) */
    int cookie;
} sd_region_outlet_def;

sd_region_outlet_def sd_region_outlet_def_default(void);

/* Adds an outlet; its index or -1 with err filled. Cells solver only. */
int sd_world_add_outlet(sd_world *w, const sd_region_outlet_def *def, sd_error *err);

typedef struct sd_outlet_info {
    const char *name;
    size_t removed;      /* particles */
    double mass;         /* kg */
    int open;
} sd_outlet_info;

size_t sd_world_outlet_count(const sd_world *w);
sd_status sd_world_get_outlet(const sd_world *w, size_t k, sd_outlet_info *out);

/* The accounting: present = initial + inserted - removed at every step. */
typedef struct sd_process_info {
    size_t initial;      /* particles at the first step (before any insertion) */
    size_t inserted, removed;
    double inserted_mass, removed_mass; /* kg */
} sd_process_info;

void sd_world_get_process(const sd_world *w, sd_process_info *out);

/* A rotating cylindrical drum, an analytic wall (cells solver, 3D): the
 * particles live inside the mantle of radius `radius` about the axis
 * through `center` (the middle of the axis) along `axis`, between the end
 * caps at +-length/2 (each may be left open: a drum open at both ends with
 * its axis along a periodic axis of the domain has periodic axial
 * boundaries). It turns at rpm about +axis (right-handed), from `start`
 * on, spun up linearly over `ramp` (both 0: at rpm from t = 0): the law sees
 * the particle's velocity relative to the surface, omega x r. Contact for
 * spheres (exact), convex shapes and polyhedra (the tangent plane at the
 * particle's radial projection) and composite elements (the turning speed
 * taken at each contact point, backend/items.h sd_item_drum_relative). */
typedef struct sd_drum_def {
    const char *name;
    sd_v3d center, axis;  /* m; any length > 0 */
    double radius, length;/* m */
    double rpm;           /* rev/min about +axis */
    double start, ramp;   /* s: it turns from `start`, its speed rising linearly from 0 to rpm over `ramp` */
    int open_lo, open_hi; /* leave out the cap at center - length/2 axis (lo) or + (hi) */
    int material;
    int cookie;
} sd_drum_def;

sd_drum_def sd_drum_def_default(void);
/* Adds the drum; its wall index, or -1 with err filled. The scene's
 * `walls: - type: drum` calls it. sd_world_get_wall reports a drum as
 * kind 3: point = center, normal = the unit axis, lo.x = radius, lo.y =
 * length / 2, open_faces bit 2 (the low cap) and 4 (the high cap) set for
 * an open end. */
int sd_world_add_drum(sd_world *w, const sd_drum_def *def, sd_error *err);

/* A loaded scene's warning for outlet k (outlets: section): why no
 * particle can reach it, or "" (NULL past the end). */
struct sd_scene;
const char *sd_scene_outlet_warning(const struct sd_scene *s, size_t k);

#ifdef __cplusplus
}
#endif

#endif
