/* check_report.h — what `shapedem check` estimates beyond what the scene
 * states (cli/check_report.c): the particles the run will hold (the pour's
 * included), their mass, the memory, the output size, the run time from a
 * timed trial, and warnings for values that look like a unit mistake.
 */
#ifndef SD_CLI_CHECK_REPORT_H
#define SD_CLI_CHECK_REPORT_H

#include <stdio.h>

#include <shapedem/scene.h>
#include <shapedem/shapedem.h>

#include "cli/check_mesh.h"

typedef struct sd_check_counts {
    size_t now;            /* particles in the world at the start */
    size_t bodies;         /* of which shaped bodies */
    size_t poured;         /* spheres the pour will insert (solver grid) */
    double mass_now;       /* kg (2D: per 1 m of thickness), movable particles at the start */
    double mass_poured;    /* kg, all the pour inserts */
    double rmin, rmax;     /* m, radius (bounding radius for shapes), the pour's included */
    double big_radius;     /* m, the largest radius of a particle of granular density, 0 if none */
    double big_mass;       /* kg, that particle's mass */
    double big_density;    /* kg/m^3, its material's density */
} sd_check_counts;

void sd_check_count(const sd_scene *s, const sd_world *w, sd_check_counts *c);

/* The insertions of a cells scene (insert:), which an empty world at the
 * start cannot show: how many particles they ask for, their mass and
 * radii, and a probe world for the estimates that read particles (time
 * step, contact duration, output size): the scene's world built again
 * with, for each insertion entry, bodies of each of its size classes
 * (the scaled template copies sd_world_add_insertion made) or spheres of
 * its law's smallest and largest radius, at the bottom and the top of
 * the region along gravity, moving at the insertion's velocity with its
 * jitter. Never stepped. */
typedef struct sd_check_insert {
    size_t count;          /* particles the insertions ask for (a mass target: mass / mean mass) */
    double mass;           /* kg, all they insert */
    double rmin, rmax;     /* m, bounding radii (rmin HUGE_VAL when none) */
    size_t probes;         /* bodies added to the probe */
    sd_world *probe;       /* NULL: no insertion, or the probe could not be built (why) */
    char why[300];
} sd_check_insert;

void sd_check_insertions(const sd_scene *s, sd_check_insert *ci);

/* Bytes the grid solver holds per poured sphere, head room included. */
double sd_check_pour_bytes(size_t poured);

/* A world with the scene's definition, materials and interactions and
 * nothing else (the trials' worlds); NULL when the world refuses them. */
sd_world *sd_check_world(const sd_scene *s);

typedef struct sd_check_trial {
    int ok;                /* 0: the trial run failed (msg says why) */
    char msg[512];
    long steps;            /* steps timed */
    size_t particles;      /* particles of the world timed (at the trial's end) */
    int bed;               /* 1: a bed of poured spheres was timed, not the scene's world */
    double seconds;        /* wall time of the timed steps */
    long insert_steps;     /* of those, steps that inserted particles (their placement timed apart) */
    double insert_seconds; /* s, the wall time of those steps */
    long contacts;         /* particle and wall contacts at the trial's end */
    double estimate;       /* s, the whole run (the mesh walls' part included) */
    int threads;
    sd_check_mesh_trial mesh; /* the particles against mesh walls, timed apart (cli/check_mesh.h) */
} sd_check_trial;

/* Times a few steps (about 0.25 s of work, at least 2 steps) of w, or of
 * a bed of the pour's spheres in the scene's walls when the scene pours,
 * and scales the time per particle-step to the run: `total` particles for
 * `steps` steps. With mesh walls, what they add to the particles taken to
 * lie against them is timed apart (sd_check_mesh_time: spheres resting on
 * the facets against the same spheres alone) and added. Steps that insert particles are timed apart: their
 * placement is a cost of the particles inserted, not of every step, so it
 * is added once rather than scaled. w is stepped (the caller only destroys
 * it afterwards). */
void sd_check_time(const sd_scene *s, sd_world *w, size_t total, long steps, sd_check_trial *t);

/* The run time lines of the report from a trial that ran (t->ok): the
 * estimate, what the trial covered, and what it did not time (particles
 * the insertions or the pour add later, the contacts of a settled bed,
 * mesh walls), where the run may take longer. `total` and `steps` as for
 * sd_check_time; poured: the scene pours. Returns the warnings printed. */
int sd_check_print_time(FILE *f, const sd_world *w, const sd_check_trial *t, size_t total, long steps,
                        size_t poured);

/* The shapes a scene's particles take, as the user wrote them (scaled
 * copies of a template for size classes are one shape): "1 shape in 4
 * sizes", "3 shapes (rod in 2 sizes)", "0 shapes". */
void sd_check_shapes_text(const sd_scene *s, const sd_world *w, char *buf, size_t size);

/* Prints a "warning" line for each value that looks like a unit mistake
 * (the scene's values are SI) and returns how many. tc is the shortest
 * contact duration (s), dt the time step. */
int sd_check_units(FILE *f, const sd_scene *s, const sd_check_counts *c, double tc, double dt);

/* The stop: line, when the scene has simulation.stop_when (io/run.c). */
void sd_check_print_stop(FILE *f, const sd_scene *s);

/* The pour: and outlet: lines of the report (solver grid), when given. */
void sd_check_print_grid(FILE *f, const sd_scene *s);

/* The output line: what a run of w would write (io/output.c's estimate)
 * for `total` particles, `frames` frames and `rows` stats rows; poured:
 * the frames are sized with every poured sphere in. */
/* The recommended step's limit and, under the volume law, the face
 * contacts at the scene's dt (regularised range, landing, resting face);
 * the number of warnings printed. */
int sd_check_print_dt(FILE *f, const sd_world *w);

void sd_check_print_output(FILE *f, const sd_scene *s, const sd_world *w, size_t total, long frames, long rows,
                           double end_time, size_t poured);

/* "1.23 MB", "4.5 GB" */
void sd_check_format_bytes(double b, char *buf, size_t size);

/* `check --ranks N`: how the static MPI split (mpi/mpi.h: the grid of
 * boxes simulation.mpi_split asks for, cut by particle count) would share
 * the world's particles out over N ranks: the grid, each rank's box and
 * its particles; a warning line when the split does not fit N. */
void sd_check_print_ranks(FILE *f, const sd_scene *s, const sd_world *w, long ranks);

#endif
