/* complib.h — built-in composite shapes (seed 004 §3-4): each preset is a
 * list of convex parts (kind, size as in sd_shape_desc, pose in the
 * composite's given frame), from a few size parameters.
 *
 * Which presets glue without overlap (exact mass sums) and which overlap
 * (the voxel lattice of shape/composite.h) is said per preset; the planar
 * ones (cross2d, lshape, tshape) are flat 3D composites of boxes of a
 * thickness, since composites are 3D only.
 */
#ifndef SD_SHAPE_COMPLIB_H
#define SD_SHAPE_COMPLIB_H

#include <stddef.h>

#include <shapedem/shapedem.h>

/* X(enum, scene name, what it is and the parameters it takes) */
#define SD_COMP_PRESETS(X)                                                                                     \
    X(SD_COMP_CROSS2D, "cross2d",                                                                              \
      "tile spacer: a flat plus of two bars length x width, thickness thick (axis z), 5 boxes glued "          \
      "flush (exact)")                                                                                         \
    X(SD_COMP_CROSS3D, "cross3d",                                                                              \
      "3D cross of seed 004 §4: three orthogonal cylinders of diameter and length through one centre "        \
      "(overlapping: lattice)")                                                                                \
    X(SD_COMP_LSHAPE, "lshape",                                                                                \
      "L: two arms of length (outer) and width, thickness thick, at right angles, 2 boxes glued flush "       \
      "(exact)")                                                                                               \
    X(SD_COMP_TSHAPE, "tshape",                                                                                \
      "T: a bar of length and width with a stem below it making the height length, thickness thick, 2 "       \
      "boxes glued flush (exact)")                                                                             \
    X(SD_COMP_RING, "ring",                                                                                    \
      "hollow cylinder (axis z) of count box segments: outer diameter, wall width, length along the axis; "   \
      "neighbours meet at the outer corners (overlapping: lattice)")                                           \
    X(SD_COMP_DUMBBELL, "dumbbell",                                                                            \
      "two spheres of diameter whose centres are length apart (along x), joined by a bar of diameter width "  \
      "(overlapping: lattice)")                                                                                \
    X(SD_COMP_SPHERES9, "spheres9",                                                                            \
      "glued-sphere cylinder of seed 004 Fig. 10 (axis z), diameter and length: one layer of 9 spheres of "   \
      "diameter length, one on the axis and 8 on a ring touching the mantle (overlapping: lattice)")          \
    X(SD_COMP_SPHERES54, "spheres54",                                                                          \
      "glued-sphere cylinder of seed 004 Fig. 10, diameter and length: two layers of 27 spheres of "          \
      "radius 0.264 length flush with the ends (1 on the axis, rings of 8 and 18, the outer touching the "      \
      "mantle; lattice)")

typedef enum sd_comp_preset {
#define SD_X_ENUM(e, name, doc) e,
    SD_COMP_PRESETS(SD_X_ENUM)
#undef SD_X_ENUM
        SD_COMP_PRESET_COUNT
} sd_comp_preset;

/* Most parts a preset makes (ring: count <= this). */
#define SD_COMP_MAX_PARTS 64

typedef struct sd_comp_def {
    int preset;       /* sd_comp_preset */
    double length;    /* m, see the preset */
    double diameter;  /* m */
    double width;     /* m */
    double thickness; /* m */
    int count;        /* ring segments, 3 .. SD_COMP_MAX_PARTS */
} sd_comp_def;

/* One part: a convex shape (kind and size as sd_shape_desc) and its pose. */
typedef struct sd_comp_part {
    const char *kind;      /* "sphere", "box", "cylinder" */
    sd_v3d size;           /* m, as sd_shape_desc.size */
    sd_v3d position;       /* m, centre of mass in the composite's given frame */
    double orientation[4]; /* (w, x, y, z) part principal frame -> given frame */
} sd_comp_part;

/* Which parameters a preset takes: bits of SD_COMP_USES_* */
enum {
    SD_COMP_USES_LENGTH = 1,
    SD_COMP_USES_DIAMETER = 2,
    SD_COMP_USES_WIDTH = 4,
    SD_COMP_USES_THICKNESS = 8,
    SD_COMP_USES_COUNT = 16
};
unsigned sd_complib_uses(int preset);

const char *sd_complib_name(int preset);
int sd_complib_from_name(const char *name); /* -1 when unknown */

/* The parts of d in out[0 .. *n) (cap >= SD_COMP_MAX_PARTS always
 * suffices). SD_ERR_INPUT naming the parameter ("length", "width", ...)
 * when one is missing, not positive or out of proportion. */
sd_status sd_complib_parts(const sd_comp_def *d, sd_comp_part *out, size_t cap, size_t *n, sd_error *err);

#endif
