/* render.h — pictures of frames without ParaView: `shapedem render`.
 *
 * A frame is read back from the files a run wrote (docs/output.md): the
 * particles' true shapes from shapes_NNNNNN.vtp when the run wrote it
 * (output.formats: [shapes]), else the particle points of
 * particles_NNNNNN.vtu drawn as spheres of their `radius` (for shaped
 * particles that is the bounding sphere, and the program says so), and the
 * walls of walls_NNNNNN.vtp drawn thin. The picture is an orthographic view
 * painted back to front (painter's algorithm over the cells, back faces
 * culled, Lambert shading) with cairo's image surfaces and written as PNG.
 *
 * Invariants: the reader (read.c) takes any bytes and either fills a frame
 * whose every index is in range or returns SD_ERR_INPUT naming the file and
 * what is wrong; a PNG is written to a temporary and renamed into place, so
 * a failed render leaves nothing half-written. The same frame and options
 * give the same pixels (the sort breaks depth ties by cell index).
 * Without cairo at build time (SHAPEDEM_HAVE_CAIRO undefined) the reader
 * still builds and sd_render_png says rendering was left out.
 */
#ifndef SD_RENDER_RENDER_H
#define SD_RENDER_RENDER_H

#include <shapedem/shapedem.h>
#include <stddef.h>
#include <stdint.h>

#define SD_RENDER_PATH_MAX 4096

/* What one frame draws, in world coordinates (m). */
typedef struct sd_render_frame {
    /* true shapes: polygons (triangles, or 2D outlines), one value each */
    size_t point_count;
    double *points;        /* x y z per point */
    size_t cell_count, conn_count;
    int64_t *conn, *ends;  /* cell k is conn[ends[k-1] .. ends[k]) */
    double *cell_value;    /* the field, per cell */
    double *cell_id;       /* the particle's id, per cell (a particle's cells are consecutive) */
    /* spheres, when the frame has no shapes file: centre, radius, value */
    size_t sphere_count;
    double *centres, *radii, *sphere_value;
    int bounding_spheres;  /* some sphere stands for a shaped particle */
    size_t not_finite;     /* particles left out: a position or radius not finite (a failed run's state) */
    /* walls, drawn as thin outlines */
    size_t wall_point_count;
    double *wall_points;
    size_t wall_cell_count, wall_conn_count;
    int64_t *wall_conn, *wall_ends;
    unsigned char *wall_fit; /* per wall cell: 1 when it bounds the scene (a box, a drum, a mesh), 0 for
                                a plane's square (drawn, never fitted: it is as big as the particles make it
                                and stays where the plane moves); NULL: the file does not say (all fit) */
    int planar;            /* every point in z = 0: a planar (2D) run */
    char field[64];        /* the field drawn ("speed" = |velocity|) */
    char unit[16];         /* its unit ("m/s", "m", "N", ...; "" for a pure number) */
    /* a categorical field (shape, material): the values are indices, the
     * legend names them; category_first is the smallest index (-1 for
     * shape: a plain sphere), names[k] the name of index category_first + k */
    int categorical;
    int category_first;
    size_t category_count;
    char (*names)[64];
    char source[SD_RENDER_PATH_MAX]; /* the file the particles came from */
} sd_render_frame;

/* Loads the frame of `path`: a particles_NNNNNN.vtu or shapes_NNNNNN.vtp
 * (their siblings of the same number are found next to it), with `field`
 * per particle: "speed" (|velocity|) or any particle array (vectors by
 * their magnitude). SD_ERR_INPUT for a missing file, a file that is not a
 * shapedem frame, or a field the frame does not have (the message lists
 * those it has). */
sd_status sd_render_frame_load(const char *path, const char *field, sd_render_frame *out, sd_error *err);
void sd_render_frame_free(sd_render_frame *f);

/* Particles handed over as arrays (a checkpoint's, io/ckpt_particles.h),
 * drawn as spheres of their radius: per particle x (3), v (3), w (3), f
 * (3), q (4), radius, id, shape (-1 a sphere) and material indices, each
 * index within its list of names (64 bytes each, NUL-terminated). */
typedef struct sd_render_particles {
    size_t n;
    const double *x, *v, *w, *f, *q, *radius;
    const uint64_t *id;
    const int32_t *shape, *material;
    size_t shape_count, material_count;
    const char (*shape_names)[64], (*material_names)[64];
    const char *source; /* the file, for messages */
} sd_render_particles;

/* A frame of those particles with `field` (the names of a particle frame:
 * speed, velocity, radius, angular_velocity, force, id, shape, material);
 * SD_ERR_INPUT for another field (the message lists them). */
sd_status sd_render_frame_particles(const sd_render_particles *p, const char *field, sd_render_frame *out,
                                    sd_error *err);

/* The particle files of a frames.pvd (part 0 of each DataSet, in order),
 * resolved against the .pvd's directory: (*paths)[k] for k < *count, each
 * shorter than SD_RENDER_PATH_MAX, in one block with the pointers (sd_free
 * *paths). */
sd_status sd_render_pvd_list(const char *pvd, char ***paths, size_t *count, sd_error *err);

/* The smallest and largest value of the frame's field (0, 0 when empty). */
void sd_render_frame_range(const sd_render_frame *f, double *lo, double *hi);

/* The unit of a particle field of the frames (docs/output.md's table):
 * "m/s" for speed and velocity, "m", "rad/s", "N", or "" (ids, indices,
 * orientations); categorical (shape, material) says the values are indices
 * of names, drawn as a legend rather than a colour scale. */
const char *sd_render_field_unit(const char *field, int *categorical);

/* The colour position (0 .. 1 on the map) of category value v of f: the
 * categories spread evenly over the map, so that an index keeps its colour
 * in every frame of a run. */
double sd_render_category_t(const sd_render_frame *f, double v);

#define SD_RENDER_COLORMAPS(X)                                                                                         \
    X(SD_CMAP_VIRIDIS, "viridis")                                                                                      \
    X(SD_CMAP_COOLWARM, "coolwarm")                                                                                    \
    X(SD_CMAP_GRAY, "gray")

typedef enum sd_render_cmap {
#define SD_X_CMAP(e, name) e,
    SD_RENDER_COLORMAPS(SD_X_CMAP)
#undef SD_X_CMAP
    SD_CMAP_COUNT
} sd_render_cmap;

typedef struct sd_render_def {
    int width, height;      /* pixels */
    double azimuth, elevation; /* degrees: the camera's direction from the scene (front: 0, 0) */
    int colormap;           /* sd_render_cmap */
    int colorbar;           /* draw the colour bar with the field's name and range */
    int fit_walls;          /* fit the bounded walls (boxes, drums, meshes; never planes) into the picture
                               too (else the particles only) */
    int fixed_range;        /* use lo, hi rather than the frame's range */
    double lo, hi;
} sd_render_def;

sd_render_def sd_render_def_default(void);
/* What a picture of f with d shows, in one line for the user: "12
 * particles coloured by speed, 0 .. 0.31 m/s" or "12 particles coloured by
 * shape: sphere (3), cube (9)". */
void sd_render_describe(const sd_render_frame *f, const sd_render_def *d, char *buf, size_t size);
/* Named views: front (looking along +y, z up), top (looking down, y up),
 * iso (from +x... -y, +z at 45 and 35.26 degrees); 0 and the angles set,
 * or -1 for an unknown name. */
int sd_render_view(const char *name, double *azimuth, double *elevation);
/* A colour map by name, or -1. */
int sd_render_colormap_of(const char *name);
/* Colour of t in [0, 1] in map c: r, g, b in [0, 1]. */
void sd_render_colormap(int c, double t, double rgb[3]);

/* 1 when the build has cairo (SHAPEDEM_HAVE_CAIRO), else 0. */
int sd_render_available(void);
/* Draws f with d into the PNG file png (via a temporary, renamed). */
sd_status sd_render_png(const sd_render_frame *f, const sd_render_def *d, const char *png, sd_error *err);

#endif
