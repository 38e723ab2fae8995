/* scene.h — a scene file, parsed: plain data between the YAML parser
 * (scene_parse.c) and the world builder (scene_build.c).
 *
 * Invariant: every value here has been type- and range-checked by the parser
 * and carries the line it came from, so the builder can report later errors
 * (overlaps at start, an unstable time step) with file, line and key.
 */
#ifndef SD_IO_SCENE_H
#define SD_IO_SCENE_H

#include <shapedem/scene.h>
#include <shapedem/shapedem.h>
#include <stdio.h>

#define SD_SCENE_NAME_MAX 64
#define SD_SCENE_PATH_MAX 1024

typedef enum sd_gen_kind {
    SD_GEN_LATTICE, /* a block of spheres on a simple cubic lattice */
    SD_GEN_RANDOM,  /* random non-overlapping spheres in a box */
    SD_GEN_LIST,    /* spheres given one by one in the scene */
    SD_GEN_CSV      /* spheres read from a CSV file */
} sd_gen_kind;

/* Orientation of shaped bodies. */
typedef enum sd_scene_orient {
    SD_ORIENT_IDENTITY, /* the template's principal frame along the world axes */
    SD_ORIENT_RANDOM,   /* uniform over rotations, from the generator's stream */
    SD_ORIENT_FIXED     /* a given unit quaternion */
} sd_scene_orient;

typedef struct sd_scene_generator {
    sd_gen_kind kind;
    int line;                     /* line of the generator's entry */
    int material;                 /* index into sd_scene.materials */
    double radius_min, radius_max;/* m; radius uniform in [min, max] (spheres) */
    int shape;                    /* index into sd_scene.shapes, or -1: spheres */
    sd_scene_orient orient;       /* shaped bodies */
    double quat[4];               /* SD_ORIENT_FIXED: (w, x, y, z), unit */
    sd_v3d velocity;              /* m/s, mean initial velocity */
    double velocity_jitter;       /* m/s, uniform +- per component */
    sd_v3d angular_velocity;      /* rad/s, initial */
    /* lattice */
    sd_v3d origin;                /* m, centre of the first sphere */
    sd_v3d spacing;               /* m, per axis */
    int spacing_line;
    int count[3];
    /* random */
    sd_v3d box_lo, box_hi;        /* m, the spheres lie fully inside */
    int box_line;
    long number;
    /* list: spheres given in the scene (material set per entry); for a
     * shaped entry list[k].radius is 0 until generation */
    size_t list_count;
    sd_sphere_def *list;
    int *list_lines;
    int *list_shape;              /* list only: shape index per entry, or -1 */
    sd_scene_orient *list_orient; /* list only */
    double (*list_quat)[4];       /* list only: SD_ORIENT_FIXED quaternions */
    /* csv: path resolved relative to the scene file */
    char file[SD_SCENE_PATH_MAX];
} sd_scene_generator;

/* A shape template (shapes: - ...), as sd_shape_desc will get it. */
typedef struct sd_scene_shape {
    char name[SD_SCENE_NAME_MAX];
    int kind;                     /* sd_shape_kind (shape/shape.h), the type choice */
    sd_v3d size;                  /* m, as sd_shape_desc.size */
    double rounding, margin;      /* m */
    double scale;                 /* - */
    size_t vertex_count;          /* polyhedron */
    sd_v3d *vertices;             /* polyhedron, from the scene or the file */
    char file[SD_SCENE_PATH_MAX]; /* polyhedron file, resolved, or "" */
    char warning[400];            /* polyhedron file taken as its hull (nonconvex: hull), or "" */
    int line;
    /* planar types (dimension 2): kind2d is the sd_shape2d_kind, or -1 for a
     * 3D type; kind is then SD_SHAPE_KIND_COUNT + kind2d (the type choice) */
    int kind2d;
    double axes[2];               /* m, ellipse semi-axes */
    size_t point_count;           /* polygon / polybezier points */
    double *points;               /* m, x0, y0, x1, y1, ... */
    size_t fourier_count;         /* N + 1 values a_0 .. a_N */
    double *fourier_a, *fourier_b;/* m, a_0..a_N and b_1..b_N (zeros when not given) */
    /* type composite (io/scene_shapes.c): its elements, .shape the scene
     * index of a convex shape listed before it. Inline and preset elements
     * are shapes of their own, named NAME.eK (hidden = 1), inserted just
     * before the composite, so shape indices stay the world's. */
    size_t element_count;
    sd_composite_element *elements;
    int lattice;                  /* points per direction, 0 = the default */
    int preset;                   /* composite preset (shape/complib.h), or -1 */
    int hidden;                   /* 1: made here for a composite's inline or preset element,
                                     or for a checkpoint's scaled copy (below) */
    /* a scaled copy that a checkpoint's particles are of (io/scene_from.c:
     * an insertion's size classes, world/scaled.c), appended hidden after
     * the scene's own shapes: 1 + the scene index of the template it
     * copies, 0 for none, -1 for an element copy that the composite copy
     * after it makes; by its factor, as the run gave it. Its scalar fields
     * are the copied template's (kind, rounding), its pointers NULL. */
    int scaled_of;
    double scaled_by;
    size_t entry;                 /* index of its entry in the file's shapes: list (messages);
                                     a scaled copy's: of the generator that reads it */
} sd_scene_shape;

typedef struct sd_scene_material {
    char name[SD_SCENE_NAME_MAX];
    sd_material_def def;          /* def.name points at name above */
    int line;
} sd_scene_material;

typedef struct sd_scene_interaction {
    int mat_a, mat_b;
    sd_interaction_def def;
    int line;
} sd_scene_interaction;

typedef struct sd_scene_wall {
    char name[SD_SCENE_NAME_MAX];
    int kind;                     /* 0 plane, 1 box, 2 mesh, 3 drum */
    sd_v3d point, normal;         /* plane; drum: centre (the middle of its axis) and unit axis */
    sd_v3d lo, hi;                /* box */
    unsigned open_faces;          /* SD_BOX_* mask */
    int material;
    int line;
    int has_motion;               /* velocity or servo keys given */
    sd_wall_motion_def motion;    /* prescribed or servo-controlled motion */
    /* kind 2, a triangle mesh (io/scene_mesh.c): the file read, scaled,
     * rotated and placed at load; the world prepares it again when added */
    char file[SD_SCENE_PATH_MAX]; /* resolved against the scene file */
    sd_v3d *mesh_vertices;        /* m, world frame at t = 0 (sd_malloc'd) */
    size_t mesh_vertex_count;
    uint32_t (*mesh_triangles)[3];/* the file's facets (OBJ polygons fanned) */
    size_t mesh_triangle_count;
    double weld_tolerance, coplanar_tolerance; /* m, rad; 0 = the defaults */
    int outside;                  /* side: outside */
    int has_torque_point;
    sd_v3d torque_point;          /* m */
    int has_mesh_motion;          /* motion: given */
    sd_mesh_motion_def mesh_motion; /* .table points at mesh_table */
    double *mesh_table;           /* rows of (t, dx, dy, dz, angle_deg) */
    char warning[400];            /* repairs made to the mesh (dropped, turned facets), or "" */
    /* kind 3, the analytic rotating drum (sd_world_add_drum) */
    double drum_radius, drum_length, drum_rpm; /* m, m, rev/min about +axis */
    double drum_start, drum_ramp;              /* s: turns from start, spun up linearly over ramp */
    int drum_open_lo, drum_open_hi; /* end caps left out (caps: keys) */
} sd_scene_wall;

enum { SD_OUT_VTK = 1 << 0, SD_OUT_CSV = 1 << 1, SD_OUT_SHAPES = 1 << 2, SD_OUT_DUMP = 1 << 3, SD_OUT_H5MD = 1 << 4 };

typedef struct sd_scene_output {
    char directory[SD_SCENE_PATH_MAX]; /* "" = out/<scene file stem> */
    long every;                   /* steps between frames */
    long stats_every;             /* steps between stats.csv rows */
    unsigned formats;             /* SD_OUT_* mask */
    int shape_resolution;         /* directions per turn of the shapes files' curved surfaces */
    long checkpoint_every;        /* steps between checkpoints, 0 = none */
    double checkpoint_minutes;    /* minutes of wall time between checkpoints, 0 = none */
} sd_scene_output;

/* Layer-by-layer pouring and the outlet of the grid solver (seed 001
 * §4.1-4.2; src/grid). */
typedef struct sd_scene_pour {
    int given, line;              /* the pour: section, and its line */
    int material;
    double radius;                /* m */
    double height;                /* m, z of the sheets' centres */
    double rate;                  /* 1/s, sheets per second */
    double vertical_speed;        /* m/s, vz uniform in [-v, v] */
    double horizontal_speed;      /* m/s, vx, vy uniform in [-v, v] */
    double start;                 /* s, first sheet */
    long count;                   /* particles: given, or from fill_height */
    double fill_height;           /* m, 0 = count given */
    double packing_fraction;      /* -, for the count from fill_height */
} sd_scene_pour;

typedef struct sd_scene_outlet {
    int given, line;
    double lo[2], hi[2];          /* m, the hole [x0, x1] x [y0, y1] in the floor */
    double open_at;               /* s */
} sd_scene_outlet;

/* The public, opaque sd_scene (shapedem/scene.h). */
struct sd_scene {
    char path[SD_SCENE_PATH_MAX];
    sd_world_def world;
    int simulation_line;          /* line of the simulation: key, for errors */
    long steps;                   /* >= 0; from steps or duration/dt */
    long mpi_rebalance_every;     /* simulation.mpi_rebalance_every: steps between re-cuts under mpirun, 0 none */
    int mpi_split[3];             /* simulation.mpi_split (mpi/mpi.h's sd_mpi_split_req): {0, 0, 0} auto; -1 on
                                     one axis: slabs along it; else [px, py, pz] */
    int mpi_split_line;           /* its line, 0 when absent */
    int dt_line;                  /* line of simulation.dt, for errors */
    int backend_line;             /* line of simulation.backend, 0 when absent */
    int backend_cli;              /* 1: the backend was set by the command line (sd_scene_set_backend) */
    /* simulation.stop_when (io/run.c): the run ends at the first stats row
     * at or after stop_after s whose kinetic energy is below stop_ke_below J
     * or, when stop_speed_below > 0, whose mean particle speed is below it */
    int stop_given, stop_line;
    double stop_ke_below, stop_after; /* J, s */
    double stop_speed_below;          /* m/s; 0: the kinetic energy is the condition */
    size_t material_count, interaction_count, generator_count, wall_count, shape_count;
    sd_scene_material *materials;
    sd_scene_shape *shapes;
    sd_scene_interaction *interactions;
    sd_scene_generator *generators;
    sd_scene_wall *walls;
    sd_scene_output output;
    sd_scene_pour pour;
    sd_scene_outlet outlet;
    struct sd_scene_process *process; /* insert: and outlets: (io/scene_process.h), NULL when none */
    struct sd_scene_analysis *analysis; /* analysis: (io/scene_analysis.h), NULL when none */
};

/* sd_scene_load, sd_scene_free and sd_scene_build are declared in
 * shapedem/scene.h. */

/* The vertices of a mesh file (.obj or .stl), read and checked as a scene's
 * polyhedron `file:` is (distinct vertices, convexity unless take_hull,
 * then a warning in warning[], "" otherwise), without a scene: for
 * `shapedem shape info mesh.obj`. *vertices is sd_malloc'd, the caller
 * frees it with sd_free. */
sd_status sd_scene_read_mesh(const char *path, int take_hull, sd_v3d **vertices, size_t *count, char *warning,
                             size_t warning_size, sd_error *err);

/* sd_scene_print_keys (shapedem help scene) is declared there too. */

/* ---- shared by the scene modules and their tests ------------------------ */

/* Every particle of a scene in id order, with where it came from. A shaped
 * body is its bounding sphere in defs (radius = the shape's bounding
 * radius, what the overlap and wall checks use) plus its shape and
 * orientation. */
typedef struct sd_scene_spheres {
    size_t count;
    sd_sphere_def *defs;
    int *shape;                   /* shape index of each particle, or -1: a sphere */
    double (*quat)[4];            /* orientation (w, x, y, z); identity for spheres */
    int *gen;                     /* generator index of each sphere */
    int *entry;                   /* list/csv entry index, or -1 */
    int *line;                    /* scene line (csv: csv-file line) */
} sd_scene_spheres;

/* Runs the generators in order (what sd_scene_build adds to the world).
 * Deterministic from s->world.seed. shape_bound[i] is the bounding radius
 * (m) of scene shape i (sd_world_get_shape); it may be NULL when no
 * generator makes shaped bodies. Fails when the random generator cannot
 * place all its particles, or a lattice is too tight for a shape. */
sd_status sd_scene_generate(const sd_scene *s, const double *shape_bound, sd_scene_spheres *out,
                            sd_error *err);
void sd_scene_spheres_free(sd_scene_spheres *sp);

/* Finds the first sphere j (in id order) that overlaps an earlier sphere i
 * by more than tol x the smaller radius, using a cell grid (O(N)).
 * Returns 1 and sets *i, *j when there is one, 0 when none, -1 when out of
 * memory. */
int sd_scene_find_overlap(size_t n, const sd_sphere_def *defs, double tol, size_t *i, size_t *j);
/* The same, keeping only the pairs for which accept(ctx, i, j) is non-zero
 * (the true shapes' test of the bounding spheres that overlap). */
int sd_scene_find_overlap_if(size_t n, const sd_sphere_def *defs, double tol,
                             int (*accept)(void *ctx, size_t i, size_t j), void *ctx, size_t *i, size_t *j);

#endif
