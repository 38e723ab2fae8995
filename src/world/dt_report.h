/* dt_report.h — the time-step estimates behind sd_world_recommended_dt
 * (world/material.c) and what set them, for `shapedem check` and the
 * tests (docs/physics.md "Time step"). Host side only. */
#ifndef SD_WORLD_DT_REPORT_H
#define SD_WORLD_DT_REPORT_H

#include <shapedem/shapedem.h>

/* The time-step estimates of sd_world_recommended_dt and what
 * set them (shapedem check prints them; docs/physics.md "Time step"). The
 * volume-law fields are of the stiffest case found (a face landing flat). */
typedef struct sd_dt_report {
    double recommended;    /* s */
    double contact;        /* s, shortest estimated contact duration (stability: dt <= contact / 5) */
    const char *limit;     /* what set the recommended step */
    double speed;          /* m/s, the characteristic impact speed */
    int volume;            /* a volume-law pair can meet */
    double onset;          /* m^3, smallest regularisation volume V0 at the world's dt */
    double onset_depth;    /* m, V0 / A of that face */
    double onset_radius;   /* m, R_eq of that body */
    double impact;         /* s, shortest face-on landing as run (regularised law) */
    double impact_depth;   /* m, its deepest overlap */
    double impact_onset_depth; /* m, V0 / A of that pair */
    int impact_inside;     /* the landing stays inside the regularised range */
    double seed_impact;    /* s, the same landing under seed 000's unregularised law */
    double rest_dt;        /* s, the resting-face limit of seed 000's law (gravity), INFINITY if none */
    double rest_depth;     /* m, its resting overlap under the weight */
    double rest_onset_depth; /* m, V0 / A of that pair */
    int rest_inside;       /* the resting face sits inside the regularised range at the world's dt */
    int volume_skipped;    /* out of memory: the volume-law estimates were not made (the fields
                              above and the recommended step leave them out) */
    double mesh_depth;     /* m, the deepest overlap of an elastic impact at `speed` on a mesh wall (the
                              smallest particle of each material, Hertz or linear law; 0: none) */
    double mesh_radius;    /* m, that particle's radius (bounding radius for shapes) */
    double guard;          /* simulation.max_overlap: the overlap guard's fraction of the radius (0: off) */
} sd_dt_report;
void sd_world_dt_report(const sd_world *w, sd_dt_report *r);

#endif
