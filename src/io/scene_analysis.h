/* scene_analysis.h — the analysis: section of a scene (issue 16;
 * shapedem/analysis.h, docs/analysis.md): a list of analyses, each
 * written as a CSV file of the run's output directory at its own cadence;
 * parsed here, scheduled by io/run.c.
 */
#ifndef SD_IO_SCENE_ANALYSIS_H
#define SD_IO_SCENE_ANALYSIS_H

#include <shapedem/analysis.h>

#include "io/scene_sections.h"

/* X(enum, scene name, what it writes) — the order of the type choices
 * (io/scene_keys.c: the kind bits of SD_SEC_ANALYSIS follow it). */
#define SD_ANALYSIS_TYPES(X)                                                                                           \
    X(SD_AN_POROSITY, "porosity", "solid fraction and porosity of a region by voxels of the true shapes")              \
    X(SD_AN_RADIAL_POROSITY, "radial_porosity", "the same per annulus of a cylinder")                                  \
    X(SD_AN_COORDINATION, "coordination", "mean coordination number and its distribution")                             \
    X(SD_AN_VELOCITY_FIELD, "velocity_field", "mean velocity per cell of a grid on a plane")                           \
    X(SD_AN_SPEED_PDF, "speed_pdf", "histogram and density of particle speeds")                                        \
    X(SD_AN_ENERGY, "energy", "kinetic energies, mean and largest speed")                                              \
    X(SD_AN_BED_HEIGHT, "bed_height", "highest point, mass-fraction height, mean height")                              \
    X(SD_AN_SURFACE_ANGLE, "surface_angle", "free-surface angle in a drum's cross section")                            \
    X(SD_AN_REPOSE_ANGLE, "repose_angle", "angle of repose of a heap")

typedef enum sd_analysis_type {
#define SD_X_AN_ENUM(e, name, doc) e,
    SD_ANALYSIS_TYPES(SD_X_AN_ENUM)
#undef SD_X_AN_ENUM
        SD_AN_TYPE_COUNT
} sd_analysis_type;

#define SD_SCENE_ANALYSIS_MAX 32
/* The most bins of one analysis (radial_porosity, speed_pdf; columns of
 * surface_angle, repose_angle): each bin of the first two is a row of the
 * file at every output. */
#define SD_AN_BINS_MAX 10000

typedef struct sd_scene_analysis_entry {
    int type; /* sd_analysis_type */
    char name[SD_SCENE_NAME_MAX];
    char file[SD_SCENE_NAME_MAX + 8]; /* in the output directory */
    int line;
    long every;           /* steps between rows, >= 1 */
    sd_region_def region; /* kind SD_REGION_NONE when not given */
    double voxel;         /* m */
    int bins;
    int cells[2], plane; /* velocity_field */
    double max_speed;    /* m/s, 0 = the fastest at each row */
    double fraction;     /* bed_height */
    double fit[2];       /* surface_angle, repose_angle */
    int has_center;
    sd_v3d center; /* repose_angle: a point of the heap's axis */
} sd_scene_analysis_entry;

typedef struct sd_scene_analysis {
    size_t count;
    sd_scene_analysis_entry e[SD_SCENE_ANALYSIS_MAX];
} sd_scene_analysis;

/* Reads analysis: (absent: s->analysis stays NULL); needs simulation and
 * output read first (dt, stats_every). */
sd_status sd_parse_analysis(sd_parse *p, yaml_node_t *root);
void sd_scene_analysis_free(sd_scene *s);

/* The run's CSV series (io/run.c): opened with the run (NULL when the
 * scene has none or there is no output directory); the steps from done
 * to the next row due (LONG_MAX when none); the rows due at done (every
 * entry at the first call, then at multiples of every and at last, the
 * run's final step); closed with the run. Errors name the file. */
typedef struct sd_analysis_run sd_analysis_run;
/* resume_step > 0: a restart at that step; each file keeps its rows
 * before it and goes on (sd_fs_resume_csv), and the first rows come when
 * their entries fall due, as in the uninterrupted run. */
sd_status sd_analysis_run_open(const sd_scene *s, const char *dir, long resume_step, sd_analysis_run **out,
                               sd_error *err);
long sd_analysis_run_next(const sd_analysis_run *a, long done);
/* About how many bytes the analysis files of a run of `steps` steps will
 * hold (headers, and rows as long as their columns at 10 bytes each, an
 * estimate for `shapedem check`); *files gets their number. */
double sd_analysis_estimate_bytes(const sd_scene *s, long steps, size_t *files);
sd_status sd_analysis_run_rows(sd_analysis_run *a, const sd_world *w, long done, long last, sd_error *err);
void sd_analysis_run_close(sd_analysis_run *a);

#endif
