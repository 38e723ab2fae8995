/* shapedem.h — the public C API of the shapedem DEM engine.
 *
 * Worlds are opaque handles. Everything that can fail returns an sd_status
 * and fills an sd_error (file, line, key and message for scene errors); the
 * library never prints and never exits. Def structs are made by their
 * default function and then edited, e.g.
 *
 *     sd_world_def d = sd_world_def_default();
 *     d.dt = 1e-5;
 *     sd_world *w;
 *     sd_error err;
 *     if (sd_world_create(&d, &w, &err) != SD_OK) { ... err.msg ... }
 *
 * Units are SI throughout (m, kg, s, N, Pa).
 *
 * Every call is safe in every state (a world just created, one not yet
 * prepared, one after a failed call; tests/unit/api_states.c calls each
 * function of these headers in each): a NULL handle, a NULL pointer where
 * something must be read or written, or an index out of range gives an
 * error status (with err filled when given) or, where a call has no
 * status, a neutral value: -1 for an index, 0 for a count, a step or a
 * flag, NaN for a time or a time step, NULL for a name (sd_world_backend
 * and sd_world_backend_note: ""), and out structs zeroed. Destroy and
 * free calls take NULL.
 */
#ifndef SHAPEDEM_SHAPEDEM_H
#define SHAPEDEM_SHAPEDEM_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

#define SD_VERSION_STRING "0.1.0"

/* ---- status and errors ------------------------------------------------ */

typedef enum sd_status {
    SD_OK = 0,
    SD_ERR_INPUT,    /* bad user input (scene, parameters): CLI exit 2 */
    SD_ERR_IO,       /* file could not be read or written */
    SD_ERR_MEMORY,   /* an allocation failed */
    SD_ERR_PHYSICS,  /* the state became invalid (NaN, runaway) */
    SD_ERR_INTERNAL, /* a broken invariant: a bug in shapedem */
    SD_ERR_INTERRUPTED /* sd_world_request_interrupt stopped the call; the world is
                        * consistent and may be stepped or checkpointed: CLI exit 130 */
} sd_status;

typedef struct sd_error {
    sd_status code;
    char file[256]; /* scene file, or "" */
    int line;       /* 1-based line in file, or 0 */
    char key[128];  /* dotted key path, e.g. "materials[1].density", or "" */
    char msg[512];  /* what was expected / what went wrong */
} sd_error;

/* Formats err as "file:line: key: msg" (parts that are empty left out). */
void sd_error_format(const sd_error *err, char *buf, size_t size);
const char *sd_status_name(sd_status s);

/* ---- small value types -------------------------------------------------- */

typedef struct sd_v3d {
    double x, y, z;
} sd_v3d;

/* ---- contact laws ------------------------------------------------------- */

/* X(enum, scene name, description): the list is the single source for the
 * enum, the scene-file names and the help text (STYLE.md convention 4). */
/* What a law needs from the materials of a pair that meets under it: the
 * world checks these at prepare (sd_world_check_params) and the scene
 * loader with the file and line, both from the `needs` column below. */
#define SD_LAW_NEEDS_MODULUS 1u          /* youngs_modulus of both materials, walls included */
#define SD_LAW_NEEDS_PARTICLE_MODULUS 2u /* youngs_modulus of the particles' materials (walls are rigid) */
#define SD_LAW_NEEDS_STIFFNESS 4u        /* stiffness k_n (N/m), of the materials or of their interaction */
#define SD_LAW_NEEDS_VOLUME_STIFFNESS 8u /* volume_stiffness k_V (N/m^3), of the materials or their interaction */
#define SD_LAW_NEEDS_SHARP 16u           /* sharp polyhedra only (type polyhedron, no rounding or margin) */

/* What a law is (the `traits` column), read where code depends on it. */
#define SD_LAW_IS_HERTZ 1u  /* Hertz normal force on the overlap depth: contact time and Rayleigh time from Y* */
#define SD_LAW_IS_LINEAR 2u /* a constant normal stiffness k_n: contact time, servo gain and the grid
                               solver's time-step limit from k_n; elastic energy 1/2 k_n delta^2 */
#define SD_LAW_IS_VOLUME 4u /* force from the overlap volume of two bodies (seed 000; contact/law_volume.h) */

/* The contact laws: X(enum, scene name, doc, needs, traits). The one list
 * behind the enum, the scene names, the help text, the parameter checks and
 * the law switch of contact/law.h (a law without a case there is a -Wswitch
 * warning, an error in -Werror builds such as CI's). */
#define SD_CONTACT_LAWS(X)                                                                       \
    X(SD_LAW_HERTZ_MINDLIN, "hertz_mindlin", "Hertz normal, Mindlin tangential with history (LIGGGHTS form)", \
      SD_LAW_NEEDS_MODULUS, SD_LAW_IS_HERTZ)                                                     \
    X(SD_LAW_LINEAR, "linear", "linear spring-dashpot-Coulomb, damping from restitution (seed 004 eqs. 10, 16)", \
      SD_LAW_NEEDS_STIFFNESS, SD_LAW_IS_LINEAR)                                                  \
    X(SD_LAW_VOLUME, "volume", "polyhedra: energy-conserving overlap-volume law, F = (E1/R1 + E2/R2) A_n V^(1/3) (seed 000 eqs. 12-22)", \
      SD_LAW_NEEDS_PARTICLE_MODULUS | SD_LAW_NEEDS_SHARP, SD_LAW_IS_VOLUME)                      \
    X(SD_LAW_VOLUME_LINEAR, "volume_linear", "polyhedra: linear overlap-volume law F = k_V V with volume_stiffness k_V (N/m^3)", \
      SD_LAW_NEEDS_VOLUME_STIFFNESS | SD_LAW_NEEDS_SHARP, SD_LAW_IS_VOLUME)

typedef enum sd_contact_law {
#define SD_X_ENUM(e, name, doc, needs, traits) e,
    SD_CONTACT_LAWS(SD_X_ENUM)
#undef SD_X_ENUM
    SD_LAW_COUNT
} sd_contact_law;

const char *sd_contact_law_name(sd_contact_law law);
/* Returns SD_LAW_COUNT when the name is unknown. */
sd_contact_law sd_contact_law_from_name(const char *name);
/* The law's needs and traits columns (SD_LAW_NEEDS_*, SD_LAW_IS_*); 0 for
 * an unknown law. */
unsigned sd_contact_law_needs(sd_contact_law law);
unsigned sd_contact_law_traits(sd_contact_law law);

/* ---- materials and interactions ----------------------------------------- */

typedef struct sd_material_def {
    const char *name;
    double density;           /* kg/m^3, > 0 */
    double youngs_modulus;    /* Pa, > 0 (Hertz-Mindlin) */
    double poisson_ratio;     /* -, in (-1, 0.5) */
    double restitution;       /* -, in (0, 1] */
    double friction;          /* -, sliding friction coefficient, >= 0 */
    double rolling_friction;  /* -, rolling resistance coefficient, >= 0 */
    double stiffness;         /* N/m, normal stiffness k_n of the linear law (0: unset) */
    double tangential_stiffness_ratio; /* -, k_t / k_n for the linear law */
    double damping;           /* N s/m, linear law: viscous coefficient eta used instead of the
                                 restitution (seed 001 eqs. 6, 8); 0 = from restitution */
    double volume_stiffness;  /* N/m^3, k_V of the volume_linear law (0: unset) */
    double volume_face_omega_dt; /* -, volume law: caps a face contact's stiffness at zero overlap
                                    to omega dt = this (in (0, 1]; 0: seed 000's law unchanged);
                                    contact/law_volume.h, docs/physics.md */
    int cookie;               /* set by sd_material_def_default */
} sd_material_def;

sd_material_def sd_material_def_default(void);

/* Overrides for one pair of materials; a negative value keeps the value
 * mixed from the two materials (see docs/physics.md). */
typedef struct sd_interaction_def {
    double restitution;
    double friction;
    double rolling_friction;
    double stiffness;             /* linear law k_n, N/m */
    double damping;               /* linear law eta, N s/m */
    double volume_stiffness;      /* volume_linear law k_V, N/m^3 */
    int law;                      /* sd_contact_law, or -1 to keep the world's */
    int cookie;
} sd_interaction_def;

sd_interaction_def sd_interaction_def_default(void);

/* ---- world -------------------------------------------------------------- */

typedef struct sd_world sd_world;

/* Solvers: the general engine, or the dense grid-stencil solver for
 * monodisperse spheres (seed 001). */
typedef enum sd_solver {
    SD_SOLVER_CELLS = 0, /* cell binning + pair lists: every shape, every feature */
    SD_SOLVER_GRID       /* one particle per grid cell, fixed stencil (seed 001) */
} sd_solver;

/* How the contacts of one composite pair (several touching element pairs,
 * seed 004 §2.6) combine, sd_world_def.multi_contact. */
typedef enum sd_multi_contact {
    SD_MULTI_CONTACT_AVERAGE = 0, /* model B (default, seed 004 eq. 21) */
    SD_MULTI_CONTACT_SUM = 1      /* model A (seed 004 eq. 18) */
} sd_multi_contact;

/* Backends: where the cells solver's stages run, sd_world_def.backend.
 * X(enum, scene name, description): the list behind the enum, the scene's
 * simulation.backend names and the CLI's --backend. */
#define SD_BACKENDS(X)                                                                             \
    X(SD_BACKEND_AUTO, "auto", "CUDA when the library was built with it and a usable device is "   \
                               "present, else the CPU; the run says which it chose")               \
    X(SD_BACKEND_CPU, "cpu", "the CPU's OpenMP loops")                                            \
    X(SD_BACKEND_CUDA, "cuda", "an NVIDIA GPU; the world is refused (SD_ERR_INPUT, saying why) "   \
                               "when none is usable")

typedef enum sd_backend_kind {
#define SD_X_ENUM(e, name, doc) e,
    SD_BACKENDS(SD_X_ENUM)
#undef SD_X_ENUM
    SD_BACKEND_COUNT
} sd_backend_kind;

const char *sd_backend_kind_name(sd_backend_kind kind);
/* Returns SD_BACKEND_COUNT when the name is unknown. */
sd_backend_kind sd_backend_kind_from_name(const char *name);

/* Periodic axes of sd_world_def.periodic. */
enum { SD_PERIODIC_X = 1 << 0, SD_PERIODIC_Y = 1 << 1, SD_PERIODIC_Z = 1 << 2 };

typedef struct sd_world_def {
    int dimension;          /* 3, or 2: the planar mode (z = 0, rotation about z only,
                               masses per unit thickness of 1 m; docs/physics.md) */
    double dt;              /* s, time step */
    sd_v3d gravity;         /* m/s^2 */
    uint64_t seed;          /* random seed for generators */
    int threads;            /* OpenMP threads; 0 = OMP_NUM_THREADS or all cores */
    sd_contact_law law;     /* default contact law */
    double skin;            /* m, Verlet skin; 0 = 0.2 x smallest radius */
    sd_solver solver;       /* SD_SOLVER_CELLS by default */
    double local_damping;   /* -, in [0, 1): velocity-based local (non-viscous) damping of
                               seed 002 §3.2: each force and torque component gets
                               -alpha |unbalanced| sign(velocity); 0 = off */
    unsigned periodic;      /* SD_PERIODIC_X | _Y | _Z: the axes that are periodic, with
                               period domain_hi - domain_lo (cells solver; not z in 2D) */
    sd_v3d domain_lo, domain_hi; /* m, the periodic box; read on the periodic axes only */
    int multi_contact;      /* SD_MULTI_CONTACT_AVERAGE (model B, default, seed 004 eq. 21) or
                               SD_MULTI_CONTACT_SUM (model A, eq. 18): composite pairs */
    sd_backend_kind backend; /* SD_BACKEND_AUTO by default; for either solver */
    int device;             /* >= 0, the CUDA backend's device slot: it runs on device
                               (device mod the devices present); 0 by default; under
                               mpirun each rank's node-local rank (docs/mpi.md) */
    double max_overlap;     /* -, the overlap guard: a contact deeper than this fraction of the
                               smaller radius stops the step with SD_ERR_PHYSICS (0.5 by
                               default; 0 = off; cells solver) */
    int cookie;
} sd_world_def;

sd_world_def sd_world_def_default(void);

sd_status sd_world_create(const sd_world_def *def, sd_world **out, sd_error *err);
void sd_world_destroy(sd_world *w);

/* Returns the new material's index (>= 0) or -1 with err filled. */
int sd_world_add_material(sd_world *w, const sd_material_def *def, sd_error *err);
/* Index of a material by name, or -1. */
int sd_world_find_material(const sd_world *w, const char *name);
/* Name of material index (as given to sd_world_add_material, "" when it had
 * none), or NULL past the last; frames name materials with it. */
const char *sd_world_material_name(const sd_world *w, size_t index);
sd_status sd_world_set_interaction(sd_world *w, int mat_a, int mat_b, const sd_interaction_def *def,
                                   sd_error *err);

typedef struct sd_sphere_def {
    sd_v3d position;          /* m */
    sd_v3d velocity;          /* m/s */
    sd_v3d angular_velocity;  /* rad/s */
    double radius;            /* m, > 0 */
    int material;             /* index from sd_world_add_material */
} sd_sphere_def;

/* Appends n spheres; stable ids continue from the last one given. */
sd_status sd_world_add_spheres(sd_world *w, size_t n, const sd_sphere_def *defs, sd_error *err);

/* ---- shapes and bodies ---------------------------------------------------- */

/* A shape template. Every shape is a convex core swept by a sphere:
 *   kind "sphere"     size.x = radius
 *   kind "box"        size = full edge lengths
 *   kind "cylinder"   size.x = diameter, size.z = length (axis z)
 *   kind "cone"       size.x = base diameter, size.z = height (axis z, apex up)
 *   kind "ellipsoid"  size = semi-axes
 *   kind "polyhedron" the convex hull of vertices (any frame; size unused)
 * rounding > 0: the core has the given size and is swept by a sphere of that
 * radius (the outer size grows); margin > 0: the outer size is the given
 * size, the core is shrunk by the margin and swept by it (seed 004's
 * shrink / GJK / swell; edges are rounded by the margin). scale multiplies
 * every length. Templates are moved to their principal frame (centre of mass
 * at the origin, principal axes along x, y, z). */
typedef struct sd_shape_desc {
    const char *kind;
    sd_v3d size;               /* m */
    double rounding;           /* m */
    double margin;             /* m */
    double scale;              /* - */
    const sd_v3d *vertices;    /* polyhedron, m */
    size_t vertex_count;
    int cookie;
} sd_shape_desc;

sd_shape_desc sd_shape_desc_default(void);

/* Returns the shape's index (>= 0) or -1 with err filled. */
int sd_world_add_shape(sd_world *w, const char *name, const sd_shape_desc *desc, sd_error *err);
int sd_world_find_shape(const sd_world *w, const char *name);
size_t sd_world_shape_count(const sd_world *w);

typedef struct sd_shape_info {
    const char *name;
    const char *kind;
    double volume;             /* m^3 */
    double bounding_radius;    /* m, about the centre of mass */
    double equivalent_radius;  /* m, of the sphere of the same volume */
    sd_v3d inertia;            /* m^5, principal moments per unit density */
    sd_v3d center_of_mass;     /* m, in the frame the shape was given in */
    double rounding;           /* m, radius swept over the core */
    size_t vertex_count;       /* polyhedron hull vertices */
    size_t face_count;         /* polyhedron welded faces (coplanar triangles merged, seed 000 §2.1) */
    size_t overlap_face_limit; /* most faces the exact overlap volume takes (SD_OVERLAP_MAX_PLANES) */
    sd_v3d axes[3];            /* principal axes (unit, the moments' order) in the frame the shape
                                  was given in */
    size_t element_count;      /* composite: its convex elements, else 0 */
    int lattice;               /* composite: 0 = exact mass sums (no two elements overlap), else the
                                  voxel lattice's points per direction (seed 004 §2.3) */
    double lattice_error;      /* composite with a lattice: estimated relative error of the volume */
    /* dimension 2: volume is the area (m^2, times the 1 m thickness),
     * inertia the polar moment about z (m^4, in all three components),
     * vertex_count the pool values (vertices, control points, coefficients) */
} sd_shape_info;

sd_status sd_world_get_shape(const sd_world *w, size_t index, sd_shape_info *out);

/* A composite template (seed 004): a non-convex particle glued from convex
 * elements that never move relative to each other. Each element is a
 * convex template (from sd_world_add_shape, never a composite) placed in
 * the composite's given frame. The composite is moved to its principal
 * frame like any template (centre of mass at the origin, principal axes
 * along x, y, z); its mass properties are exact sums (parallel-axis
 * theorem) when no two elements overlap, else integrated on the voxel
 * lattice of seed 004 §2.3 (eqs. 7-8) with `lattice` points per direction. */
typedef struct sd_composite_element {
    int shape;               /* convex template index from sd_world_add_shape */
    sd_v3d position;         /* m, the element's centre of mass in the composite's given frame */
    double orientation[4];   /* (w,x,y,z) element principal frame -> composite given frame; zero = identity */
} sd_composite_element;

typedef struct sd_composite_desc {
    const sd_composite_element *elements;
    size_t element_count;
    int lattice;             /* points per direction of the voxel lattice for overlapping
                                elements (seed 004 §2.3); 0 = default */
    int cookie;
} sd_composite_desc;

sd_composite_desc sd_composite_desc_default(void);
/* Returns a shape index usable in sd_body_def.shape, or -1 with err filled. */
int sd_world_add_composite(sd_world *w, const char *name, const sd_composite_desc *desc, sd_error *err);

/* A built-in composite (the scene's `preset:`; `shapedem help scene` lists
 * them with the parameters each takes): cross2d, cross3d, lshape, tshape,
 * ring, dumbbell, spheres9, spheres54. Parameters a preset does not take
 * must stay 0. */
typedef struct sd_composite_preset_def {
    const char *preset;      /* its name, e.g. "cross3d" */
    double length;           /* m */
    double diameter;         /* m */
    double width;            /* m */
    double thickness;        /* m */
    int count;               /* ring segments */
    int cookie;
} sd_composite_preset_def;

sd_composite_preset_def sd_composite_preset_def_default(void);
/* Adds the element templates of preset def to w (named NAME.e0, NAME.e1,
 * ..., one per distinct part size) and fills out[0 .. *n) with the
 * elements (cap >= 64 always suffices), ready for sd_composite_desc (to
 * edit, or to glue with other elements). SD_ERR_INPUT naming the parameter
 * when one is missing, not positive, out of proportion or not taken by the
 * preset. */
sd_status sd_composite_preset(sd_world *w, const char *name, const sd_composite_preset_def *def,
                              sd_composite_element *out, size_t cap, size_t *n, sd_error *err);
/* sd_composite_preset, then sd_world_add_composite with the default
 * lattice: the composite's shape index, or -1 with err filled. */
int sd_world_add_composite_preset(sd_world *w, const char *name, const sd_composite_preset_def *def, sd_error *err);

/* A planar shape template (dimension 2 only; its index is used by
 * sd_body_def.shape like a 3D template's). Kinds (seed 002):
 *   "circle"      radius
 *   "ellipse"     semi_axes (along x, y), optionally rounded by radius
 *   "polygon"     the convex hull of points (x0, y0, x1, y1, ...), optionally rounded
 *   "polybezier"  3m control points of m cubic Bezier segments closing on the
 *                 first point, a convex curve, optionally rounded
 *   "fourier"     support function p(theta) = a0/2 + sum a_k cos k theta + b_k sin k theta
 *                 (seed 002 eq. 2): fourier_a = a_0..a_N, fourier_b = b_1..b_N; must be
 *                 convex (p + p'' >= 0, eq. 5: reduce it with `shapedem shape fit-fourier`)
 * Templates are moved to their centroid; masses are per unit thickness (1 m). */
typedef struct sd_shape2d_def {
    const char *kind;
    double radius;              /* m: circle radius; other kinds: rounding (>= 0) */
    double semi_axes[2];        /* m, ellipse */
    const double *points;       /* m, x0, y0, x1, y1, ... (polygon, polybezier) */
    size_t point_count;         /* points, not doubles */
    const double *fourier_a;    /* m, a_0 .. a_N */
    const double *fourier_b;    /* m, b_1 .. b_N */
    int order;                  /* N */
    int cookie;
} sd_shape2d_def;

sd_shape2d_def sd_shape2d_def_default(void);
/* Returns the shape's index (>= 0) or -1 with err filled; dimension 2 only. */
int sd_world_add_shape2d(sd_world *w, const char *name, const sd_shape2d_def *def, sd_error *err);

/* A rigid body of a shape template. In dimension 2 the position has z = 0
 * and the orientation is a rotation about z, (cos(a/2), 0, 0, sin(a/2));
 * bodies of a circle template are plain circles (shape -1 in queries). */
typedef struct sd_body_def {
    sd_v3d position;           /* m, centre of mass */
    sd_v3d velocity;           /* m/s */
    sd_v3d angular_velocity;   /* rad/s, world frame */
    double orientation[4];     /* (w, x, y, z) principal frame to world; zero = identity */
    int shape;                 /* index from sd_world_add_shape */
    int material;
} sd_body_def;

sd_status sd_world_add_bodies(sd_world *w, size_t n, const sd_body_def *defs, sd_error *err);

/* Walls. Returns the wall index (>= 0) or -1 with err filled. */
int sd_world_add_plane(sd_world *w, const char *name, sd_v3d point, sd_v3d normal, int material,
                       sd_error *err);

/* Box faces, for sd_world_add_box's open_faces mask. */
enum {
    SD_BOX_XMIN = 1 << 0,
    SD_BOX_XMAX = 1 << 1,
    SD_BOX_YMIN = 1 << 2,
    SD_BOX_YMAX = 1 << 3,
    SD_BOX_ZMIN = 1 << 4,
    SD_BOX_ZMAX = 1 << 5
};
/* A container: particles stay inside [lo, hi]; faces in open_faces are absent. */
int sd_world_add_box(sd_world *w, const char *name, sd_v3d lo, sd_v3d hi, unsigned open_faces,
                     int material, sd_error *err);

/* Moving walls (plane walls). Within [move_start, move_end) the wall moves
 * at the prescribed velocity (loading); within [servo_start, servo_end) a
 * servo sets its velocity along its normal each step so the normal stress
 * it carries tracks servo_stress (confining pressure). The servo wins where
 * both windows are open; outside both the wall rests. The stress is the
 * normal force over the wall's contact length (2D: times 1 m) or area (3D),
 * measured between the two pairs of opposite plane walls perpendicular to
 * it (one pair in 2D, two in 3D). An end <= start means "never ends". */
typedef struct sd_wall_motion_def {
    sd_v3d velocity;          /* m/s, prescribed velocity */
    double move_start, move_end;   /* s */
    double servo_stress;      /* Pa, > 0 enables the servo (compression positive) */
    double servo_start, servo_end; /* s */
    double servo_gain;        /* (m/s)/Pa; 0 = automatic: half the stable gain from the
                                 contact stiffness on the wall (see docs/physics.md) */
    double servo_max_speed;   /* m/s, cap of the servo velocity; 0 = no cap */
    int cookie;
} sd_wall_motion_def;

sd_wall_motion_def sd_wall_motion_def_default(void);
sd_status sd_world_set_wall_motion(sd_world *w, int wall, const sd_wall_motion_def *def, sd_error *err);

/* ---- triangle-mesh walls (seed 000 §2.4) ----------------------------------
 * A mesh wall is a rigid triangle mesh (a hopper, a drum, a blade). At add
 * time it is welded, cleaned, oriented, grouped into plane groups (connected
 * coplanar facets) and its edges and corners marked active or inactive
 * (src/geom/trimesh.h says the rule); its facets go into spatial bins of
 * their own in the mesh's frame. A particle makes one contact per plane
 * group it touches (history keyed by the group, so sliding across the
 * triangles of one plane keeps the tangential spring); the force is the
 * plane contact weighted by the area of the body's overlap region clipped
 * to the group's triangles (Sutherland-Hodgman), see docs/physics.md.
 * Members may be added before the cookie; existing ones keep their meaning. */
typedef struct sd_mesh_def {
    const sd_v3d *vertices;         /* m, world frame at t = 0 (file scale and placement applied) */
    size_t vertex_count;
    const uint32_t (*triangles)[3]; /* vertex index triples */
    size_t triangle_count;
    int material;
    double weld_tolerance;          /* m; 0 = 1e-9 of the bounding-box diagonal */
    double coplanar_tolerance;      /* rad; facets join a plane group when normals agree within it; 0 = 1e-6 */
    int outside;                    /* closed parts: 0 = particles inside (a drum, a box), 1 = outside (an obstacle) */
    int cookie;
} sd_mesh_def;
sd_mesh_def sd_mesh_def_default(void);
/* Returns the wall index (>= 0) or -1 with err filled. Prepares the mesh
 * (geom/trimesh.h); its reference point (for torques, and the centre of a
 * motion's rotation unless the motion names one) is the centre of its
 * vertices' bounding box. */
int sd_world_add_mesh(sd_world *w, const char *name, const sd_mesh_def *def, sd_error *err);

enum { SD_MESH_FIXED = 0, SD_MESH_TRANSLATE, SD_MESH_ROTATE, SD_MESH_TABLE };
/* The motion of a mesh wall as a rigid body, from its pose at t = 0:
 *   FIXED      rests;
 *   TRANSLATE  moves at `velocity` from `start`, the speed ramping linearly from 0 over `ramp`;
 *   ROTATE     turns about the line (axis_point, axis), right-handed, at `rpm` from `start`,
 *              ramping linearly over `ramp`;
 *   TABLE      rows (t, dx, dy, dz, angle_deg), t increasing: the displacement of the mesh and
 *              its angle about the axis (through axis_point, moving with the displacement),
 *              linear between rows, held before the first and after the last row.
 * Velocities (and the angular velocity about the axis) enter the contact law's relative
 * velocity at each contact point. */
typedef struct sd_mesh_motion_def {
    int kind;                       /* SD_MESH_* */
    sd_v3d velocity;                /* m/s, TRANSLATE */
    sd_v3d axis_point, axis;        /* m, -: ROTATE and TABLE, the axis (right-handed) */
    double rpm;                     /* rev/min, ROTATE */
    double start, ramp;             /* s: the motion starts at `start`, its speed ramps linearly over `ramp` */
    const double *table;            /* TABLE: rows of (t, dx, dy, dz, angle_deg): displacement and angle about the axis */
    size_t table_rows;              /* copied by sd_world_set_mesh_motion */
    int cookie;
} sd_mesh_motion_def;
sd_mesh_motion_def sd_mesh_motion_def_default(void);
sd_status sd_world_set_mesh_motion(sd_world *w, int wall, const sd_mesh_motion_def *def, sd_error *err);
/* The point (m, world frame) about which sd_world_get_wall's torque of wall
 * `wall` is taken (any wall kind; default: the wall's reference point, for
 * a rotating mesh its axis point). The point moves with a mesh's
 * translation. */
sd_status sd_world_set_wall_torque_point(sd_world *w, int wall, sd_v3d point, sd_error *err);
/* Facets, plane groups and the mesh's current pose (world = R x_mesh + t,
 * R from the quaternion (w, x, y, z)); triangle data for output
 * (io/vtk.c). Returns SD_ERR_INPUT when wall is not a mesh. */
typedef struct sd_mesh_info {
    size_t vertex_count, triangle_count, group_count;
    const double *vertices;         /* m, 3 per vertex, mesh frame (= world frame at t = 0) */
    const uint32_t (*triangles)[3];
    const uint32_t *group;          /* plane group per triangle */
    double translation[3];          /* m */
    double rotation[4];             /* (w, x, y, z) */
    sd_v3d velocity, angular_velocity; /* m/s of the reference point, rad/s */
} sd_mesh_info;
sd_status sd_world_get_mesh(const sd_world *w, int wall, sd_mesh_info *out);

/* Biaxial (2D) or box state from the four plane walls with normals +-x and
 * +-y (seed 002 §3.2). Stresses are compression positive; strains are
 * compression positive and measured from the reference size, set when the
 * first prescribed wall motion starts (or by sd_world_biaxial_reference). */
typedef struct sd_biaxial {
    double width, height;     /* m, current distance between the x walls and the y walls */
    double width0, height0;   /* m, reference size */
    double sigma_xx, sigma_yy;/* Pa, mean normal stress on the x walls and on the y walls */
    double strain_axial;      /* -, (height0 - height) / height0 */
    double strain_lateral;    /* -, (width0 - width) / width0 */
    double strain_volumetric; /* -, 1 - width height / (width0 height0) */
    double stress_ratio;      /* -, q/p = (sigma_yy - sigma_xx) / (sigma_yy + sigma_xx) */
    int has_reference;        /* 0 until the reference size is set */
} sd_biaxial;

/* SD_ERR_INPUT when the world lacks the four walls (or is not 2D). */
sd_status sd_world_biaxial(const sd_world *w, sd_biaxial *out);
/* Takes the current size as the reference for the strains. */
sd_status sd_world_biaxial_reference(sd_world *w);

/* ---- pouring and outlets -------------------------------------------------
 * Layer-by-layer pouring of equal spheres (seed 001 §4.1) and a hole in the
 * floor (zmin face) of the domain box (§4.2), the hopper of [Naderi 2024].
 * The grid solver implements them; the cells solver refuses them for now
 * (SD_ERR_INPUT, saying so). Set before sd_world_prepare; an outlet may
 * also be opened between steps. */
typedef struct sd_pour_def {
    double radius;            /* m, of every poured sphere, > 0 */
    int material;             /* index from sd_world_add_material */
    double height;            /* m, z of the centres of each new sheet */
    double layers_per_second; /* 1/s, sheets per second, > 0 (4: seed 001 Table 2, Case I) */
    size_t count;             /* spheres to pour in all */
    double vz_range;          /* m/s, vertical velocity uniform in [-vz, vz] (0.5, seed 001 §4.1) */
    double vh_range;          /* m/s, horizontal velocities uniform in [-vh, vh] (0.1) */
    double start_time;        /* s, time of the first sheet (0) */
    int cookie;
} sd_pour_def;

sd_pour_def sd_pour_def_default(void);

typedef struct sd_outlet_def {
    double x0, x1, y0, y1;    /* m, the hole [x0, x1] x [y0, y1]; x1 > x0, y1 > y0 */
    double open_at;           /* s, simulated time it opens: the first step starting at or
                                 after it runs with the hole (0: at once) */
    int cookie;
} sd_outlet_def;

sd_outlet_def sd_outlet_def_default(void);

sd_status sd_world_set_pour(sd_world *w, const sd_pour_def *def, sd_error *err);
sd_status sd_world_set_outlet(sd_world *w, const sd_outlet_def *def, sd_error *err);
/* 1 and *out filled when the world pours (sd_world_set_pour), else 0. */
int sd_world_get_pour(const sd_world *w, sd_pour_def *out);

/* Computes the initial forces; called by the first sd_world_step when not
 * called before. Fails on bad parameters (e.g. a linear law with no stiffness). */
sd_status sd_world_prepare(sd_world *w, sd_error *err);
sd_status sd_world_step(sd_world *w, long nsteps, sd_error *err);
/* Asks the sd_world_step in progress (or the next one) to stop soon. It
 * only stores a flag, so it may be called from a signal handler or another
 * thread. The cells solver looks at it after each step and before each
 * particle an insertion places (one insertion may try 10^5 positions for
 * each of 10^6 particles: minutes in one call); it then stops with the
 * world between two steps, the particles placed so far in it and the rest
 * of the insertion left to the next call (or to a restart from a
 * checkpoint written now), and returns SD_ERR_INTERRUPTED, which clears
 * the request. The grid solver and a decomposed (MPI) world, whose ranks
 * must take every step together, look at it only between calls: there it
 * stays set until a cells world's step takes it. NULL is ignored. */
void sd_world_request_interrupt(sd_world *w);

/* ---- queries ------------------------------------------------------------ */

size_t sd_world_particle_count(const sd_world *w);
size_t sd_world_wall_count(const sd_world *w);
long sd_world_step_count(const sd_world *w);
double sd_world_time(const sd_world *w);
double sd_world_dt(const sd_world *w);
int sd_world_threads(const sd_world *w);
/* The backend the world runs on ("cpu" or "cuda"), chosen at creation, and
 * why or on what: "not compiled with CUDA", "no CUDA device", the device's
 * name, ... (never NULL). */
const char *sd_world_backend(const sd_world *w);
const char *sd_world_backend_note(const sd_world *w);

typedef struct sd_particle_state {
    uint64_t id;              /* stable id, fixed for the particle's life */
    sd_v3d position, velocity, angular_velocity, force, torque;
    double quat[4];           /* orientation (w, x, y, z) */
    double radius, mass;      /* radius: the sphere's, or the bounding radius */
    int material;
    int shape;                /* template index, or -1 for a plain sphere */
} sd_particle_state;

/* Particles in storage order (which may change at pair-list rebuilds). */
sd_status sd_world_get_particle(const sd_world *w, size_t index, sd_particle_state *out);
/* Storage index of the particle with this stable id, or (size_t)-1. */
size_t sd_world_find_particle(const sd_world *w, uint64_t id);

/* ---- particle fields in bulk, by stable id ----------------------------------
 * Storage order changes at pair-list rebuilds; these calls copy a field of
 * many particles at once in the order of their stable ids (or of the ids
 * the caller lists), so a caller's arrays keep their meaning across steps.
 * Values are doubles, `components` per particle, particle after particle
 * (x0 y0 z0 x1 y1 z1 ...). X(enum, name, member, components, unit,
 * writable, doc): the member column names the sd_particle_state member the value is read
 * from (world/fields.c checks each against it at compile time). */
#define SD_FIELDS(X)                                                                                         \
    X(SD_FIELD_POSITION, "position", position, 3, "m", 1, "position of the centre of mass")                   \
    X(SD_FIELD_VELOCITY, "velocity", velocity, 3, "m/s", 1, "velocity of the centre of mass")                 \
    X(SD_FIELD_ANGULAR_VELOCITY, "angular_velocity", angular_velocity, 3, "rad/s", 1,                         \
      "angular velocity, world frame")                                                                        \
    X(SD_FIELD_ORIENTATION, "orientation", quat, 4, "-", 1,                                                   \
      "orientation (w, x, y, z), body frame to world frame; a unit quaternion")                               \
    X(SD_FIELD_FORCE, "force", force, 3, "N", 0, "total contact force of the last step")                      \
    X(SD_FIELD_TORQUE, "torque", torque, 3, "N m", 0, "total contact torque of the last step")                \
    X(SD_FIELD_RADIUS, "radius", radius, 1, "m", 0, "radius (the bounding radius of a shaped body)")          \
    X(SD_FIELD_MASS, "mass", mass, 1, "kg", 0, "mass (infinite for a fixed body)")

typedef enum sd_field {
#define SD_X_ENUM(e, name, member, components, unit, writable, doc) e,
    SD_FIELDS(SD_X_ENUM)
#undef SD_X_ENUM
    SD_FIELD_COUNT
} sd_field;

/* The field's name ("position", ...; NULL for an unknown field), its
 * values per particle (0 for an unknown field), its unit, and 1 when
 * sd_world_set_field takes it. */
const char *sd_field_name(sd_field field);
size_t sd_field_components(sd_field field);
const char *sd_field_unit(sd_field field);
int sd_field_writable(sd_field field);

/* The stable ids of all particles, increasing, into ids[0 .. n); n must be
 * sd_world_particle_count (else SD_ERR_INPUT, nothing written). */
sd_status sd_world_get_ids(const sd_world *w, uint64_t *ids, size_t n, sd_error *err);
/* Copies a field of n particles into out[0 .. out_len): the particles with
 * ids[0 .. n) in that order, or with ids NULL all particles in increasing
 * id order (n must then be sd_world_particle_count). out_len must be
 * n x sd_field_components(field). SD_ERR_INPUT, naming the first id not
 * present or the size expected, when any is wrong; then nothing is written.
 * Cost O((N + n) log N) for N particles. */
sd_status sd_world_get_field(const sd_world *w, sd_field field, const uint64_t *ids, size_t n, double *out,
                             size_t out_len, sd_error *err);
/* The reverse for a writable field (position, velocity, angular velocity,
 * orientation), with the same ids, n and sizes; the values must be finite,
 * an orientation a unit quaternion (within 1e-6) and, in dimension 2, in
 * the plane (z = 0; rotation about z only). Everything is checked before
 * anything is written. An id listed twice takes its last values. The pair
 * lists are rebuilt at the next step; the forces the next step starts from
 * stay those of the last step (velocity Verlet) until sd_world_prepare
 * computes them for the new state. The grid solver's particles are not
 * writable (SD_ERR_INPUT). A decomposed (MPI) world sees its rank's own
 * particles only. */
sd_status sd_world_set_field(sd_world *w, sd_field field, const uint64_t *ids, size_t n, const double *values,
                             size_t values_len, sd_error *err);

/* ---- the particle arrays themselves (zero-copy views) -------------------------
 * The cells solver's particle arrays in storage order, for a reader that
 * must not copy (the Python binding's numpy views): pointers to the
 * owned particles' values (ghosts are not included), valid until the
 * world's generation changes. The generation counts every change of
 * where the arrays are or which particle a slot holds: growth, added
 * particles, each pair-list rebuild (which reorders, so nearly every
 * sd_world_step and sd_world_prepare), a removal (outlets), a checkpoint
 * restore. sd_world_set_field writes in place and keeps it. A reader
 * compares sd_world_generation with the view's before each read and takes
 * a new view when they differ; the id array beside the values says which
 * particle each row is. Read only: writes go through sd_world_set_field,
 * which keeps the engine's invariants. */
typedef struct sd_state_view {
    uint64_t generation;      /* sd_world_generation when the view was taken */
    size_t n;                 /* owned particles: rows of every array below */
    const double *position;   /* m, 3 per particle */
    const double *velocity;   /* m/s, 3 */
    const double *angular_velocity; /* rad/s, 3, world frame */
    const double *orientation;      /* (w, x, y, z), 4 */
    const double *force;      /* N, 3, of the last step */
    const double *torque;     /* N m, 3, of the last step */
    const double *radius;     /* m, 1 (the bounding radius of a shaped body) */
    const int32_t *material;  /* material index */
    const int32_t *shape;     /* template index, -1 for a plain sphere */
    const uint64_t *id;       /* stable id */
} sd_state_view;

/* The generation of the world's particle arrays (0 for a NULL world). */
uint64_t sd_world_generation(const sd_world *w);
/* Fills *out (zeroed on failure). SD_ERR_INPUT for the grid solver, whose
 * particles live in its grid (use sd_world_get_field), and for a build
 * with single-precision reals. The pointers are NULL when n is 0. */
sd_status sd_world_state_view(const sd_world *w, sd_state_view *out, sd_error *err);

typedef struct sd_stats {
    double time;              /* s */
    long step;
    double kinetic_translational;  /* J */
    double kinetic_rotational;     /* J */
    double potential_gravity;      /* J, relative to z = 0 along -g */
    double potential_elastic;      /* J, stored in contact springs */
    long contacts;            /* particle-particle pairs in contact */
    long wall_contacts;       /* particle-wall contacts */
    double max_overlap_ratio; /* max overlap / smaller radius (half the smallest
                                 outer dimension for shapes) */
    double max_speed;         /* m/s */
    long rebuilds;            /* pair-list rebuilds so far */
    size_t pairs;             /* candidate pairs in the list */
} sd_stats;

void sd_world_stats(const sd_world *w, sd_stats *out);

/* Convex narrow-phase work per pair type since the world was created:
 * evaluations that ran GJK (bounding spheres overlapping), their GJK + EPA
 * iterations and support calls (one call = a support point of each body).
 * Seed 002 Table 1 reports 2.9-6 support calls per pair. */
typedef struct sd_narrow_stats {
    const char *kind_a, *kind_b;   /* shape kinds, e.g. "box", "ellipsoid" */
    long long evaluations;
    long long iterations;
    long long support_calls;
    /* planar mode (2D GJK/EPA, seed 002 Table 1 splits contact from no
     * contact): evaluations that found the bodies overlapping, and their
     * support calls; iterations is 0 there (2D counts support calls only) */
    long long contacts;
    long long contact_support_calls;
} sd_narrow_stats;

/* Fills up to max entries (pair types with at least one evaluation) and
 * returns how many there are. */
size_t sd_world_narrow_stats(const sd_world *w, sd_narrow_stats *out, size_t max);

/* ---- profile (STYLE.md convention 9) --------------------------------------
 * Wall time per stage of the step, accumulated since the world was created
 * (a monotonic clock read twice per stage per step; never per pair). The
 * stages of the cells solver are timed by the step itself; "output" is
 * timed by whoever writes the output (the CLI's run loop) through
 * sd_world_profile_add. The grid solver times only output.
 * X(NAME, name, what it covers) */
#define SD_PROFILE_STAGES(X)                                                                        \
    X(REBUILD, rebuild, "skin test and pair-list rebuilds (broad phase)")                           \
    X(SPHERES, spheres, "sphere-sphere (disc-disc) pairs")                                          \
    X(CONVEX, convex, "pairs with a 3D shape: GJK/EPA")                                             \
    X(POLY_VOLUME, poly_volume, "sharp polyhedron pairs under a volume law: exact overlap volume") \
    X(CONVEX2D, convex2d, "pairs with a 2D shape: 2D GJK/EPA")                                     \
    X(ELEMENTS, elements, "composite element pairs (seed 004), their multi-contact combination")    \
    X(WALLS, walls, "particle-wall pairs of every kind, and the wall totals")                       \
    X(INTEGRATION, integration, "gather, kicks and drifts, wall motion, finite check")              \
    X(OUTPUT, output, "frames, statistics and summary (timed by the caller)")

typedef enum sd_profile_stage {
#define SD_X_PROFILE(NAME, name, doc) SD_PROFILE_##NAME,
    SD_PROFILE_STAGES(SD_X_PROFILE)
#undef SD_X_PROFILE
    SD_PROFILE_STAGE_COUNT
} sd_profile_stage;

/* calls: how many times the stage ran. Each step runs the rebuild stage
 * once, each pair kind present in the pair list once, the walls once when
 * there are walls and the integration once; sd_world_prepare runs the
 * first three (its forces), so after a prepare and n steps they count
 * n + 1 and the integration n. The first half kick of each sd_world_step
 * call is timed into the integration without a call of its own. */
typedef struct sd_profile {
    double seconds[SD_PROFILE_STAGE_COUNT]; /* s, wall time */
    long long calls[SD_PROFILE_STAGE_COUNT];
} sd_profile;

void sd_world_profile(const sd_world *w, sd_profile *out);
/* Adds seconds of a stage the caller timed (output) and counts one call. */
void sd_world_profile_add(sd_world *w, sd_profile_stage stage, double seconds);
/* The stage's name ("rebuild", "spheres", ...), NULL out of range. */
const char *sd_profile_stage_name(int stage);

typedef struct sd_wall_info {
    const char *name;
    int kind;                 /* 0 plane, 1 box */
    sd_v3d force;             /* N, total force the particles exert on the wall */
    sd_v3d torque;            /* N m, about the wall's reference point */
    sd_v3d point, normal;     /* plane: point and unit normal */
    sd_v3d lo, hi;            /* box: corners */
    unsigned open_faces;      /* box: open faces mask */
    int material;
    sd_v3d velocity, angular_velocity; /* m/s, rad/s: its motion this step (a drum's spin, ramp included) */
} sd_wall_info;

sd_status sd_world_get_wall(const sd_world *w, size_t index, sd_wall_info *out);

/* Recommended time step (s) for the current particles and walls (seed 004
 * eqs. 12, 16 for the linear law; Rayleigh and Hertz durations otherwise).
 * contact_duration receives the shortest estimated contact duration (s).
 * Any time: a world not prepared has its materials mixed for the estimate
 * (as sd_world_prepare will); infinite when no contact can form (no
 * particle or no material); NaN for a NULL world. */
double sd_world_recommended_dt(const sd_world *w, double *contact_duration);

/* Memory: bytes currently allocated through shapedem's allocator, and the peak. */
size_t sd_memory_in_use(void);
size_t sd_memory_peak(void);

#ifdef __cplusplus
}
#endif

#endif
