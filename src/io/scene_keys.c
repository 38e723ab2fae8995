/* scene_keys.c — the table of scene-file keys, and the help text made from
 * it (`shapedem help scene`, docs/scene-format.md).
 *
 * Invariant: this table is the only list of scene keys. The parser
 * (scene_parse.c) rejects any key not in it, checks types and ranges with
 * its type and range columns, and takes numeric defaults from its default
 * column; sd_scene_print_keys prints the same rows, so the docs describe
 * exactly what the parser does.
 */
#include "io/scene_keys.h"

#include <stdio.h>
#include <string.h>

#include "io/scene.h"
#include "io/scene_analysis.h"
#include "shape/complib.h"
#include "shape/polylib.h"
#include "shape/shape.h"
#include "shape/shape2d.h"

/* Contact-law names come from the public X-macro list (STYLE.md
 * convention 4); the trailing '|' is skipped by the choice readers. */
#define SD_X_CHOICE(e, name, doc) name "|"
#define SD_X_LAW_CHOICE(e, name, doc, needs, traits) name "|"
#define SD_LAW_CHOICES SD_CONTACT_LAWS(SD_X_LAW_CHOICE)
/* Shape type names, in sd_shape_kind order, from the kinds list in
 * shape/shape.h (the same list the world reads desc.kind against). */
#define SD_SHAPE_CHOICES SD_SHAPE_KINDS(SD_X_CHOICE) SD_SHAPE2D_KINDS(SD_X_CHOICE)
/* Built-in polyhedra, from the preset list in shape/polylib.h. */
#define SD_POLY_CHOICES SD_POLY_PRESETS(SD_X_CHOICE)
/* Built-in composites, from the preset list in shape/complib.h; they follow
 * the polyhedra in the choices of shapes[].preset. */
#define SD_COMP_CHOICES SD_COMP_PRESETS(SD_X_CHOICE)

#define ALL SD_KIND_ALL
#define LAT (1u << SD_GEN_LATTICE)
#define RND (1u << SD_GEN_RANDOM)
#define LST (1u << SD_GEN_LIST)
#define CSV (1u << SD_GEN_CSV)
#define PLANE 1u
#define BOX 2u
#define MESH 4u
#define DRUM 8u
/* mesh motion types, in SD_MESH_* order */
#define MFIX 1u
#define MTRA 2u
#define MROT 4u
#define MTAB 8u
/* insert and outlet regions, the bit order of their region choices */
#define IBOX 1u
#define ICYL 2u
#define IDISC 4u
#define IMESH 8u
#define SSPH (1u << SD_SHAPE_SPHERE)
#define SBOX (1u << SD_SHAPE_BOX)
#define SCYL (1u << SD_SHAPE_CYLINDER)
#define SCONE (1u << SD_SHAPE_CONE)
#define SELL (1u << SD_SHAPE_ELLIPSOID)
#define SPOLY (1u << SD_SHAPE_POLYHEDRON)
#define SCOMP (1u << SD_SHAPE_COMPOSITE)
/* planar shape types follow the 3D ones in the type choices (scene.h) */
#define S3D ((1u << SD_SHAPE_KIND_COUNT) - 1u)
/* analysis types, the bit order of their type choices (io/scene_analysis.h) */
#define SD_X_AN_CHOICE(e, name, doc) name "|"
#define SD_AN_TYPE_CHOICES SD_ANALYSIS_TYPES(SD_X_AN_CHOICE)
#define AN(t) (1u << (t))
#define AN_VOX (AN(SD_AN_POROSITY) | AN(SD_AN_RADIAL_POROSITY))
#define AN_NEEDS_REGION (AN_VOX | AN(SD_AN_VELOCITY_FIELD) | AN(SD_AN_SURFACE_ANGLE))
/* the region keys are read for every type (io/scene_analysis.c refuses a
 * region for repose_angle by name), so their section column stays short */
#define AN_REGION ALL
#define AN_BOX ALL
#define AN_CYL ALL
#define AN_BINS (AN(SD_AN_RADIAL_POROSITY) | AN(SD_AN_SPEED_PDF) | AN(SD_AN_SURFACE_ANGLE) | AN(SD_AN_REPOSE_ANGLE))
#define S2(k) (1u << (SD_SHAPE_KIND_COUNT + (k)))
#define SCIRC S2(SD_SHAPE2D_CIRCLE)
#define SELL2 S2(SD_SHAPE2D_ELLIPSE)
#define SPOLY2 S2(SD_SHAPE2D_POLYGON)
#define SBEZ S2(SD_SHAPE2D_POLYBEZIER)
#define SFOUR S2(SD_SHAPE2D_FOURIER)

/* section, key, type, range, choices, applies to, required for, unit, default, meaning */
const sd_scene_key sd_scene_keys[] = {
    {SD_SEC_ROOT, "simulation", SD_KT_MAP, SD_KR_ANY, NULL, ALL, ALL, "", "required",
     "time step, run length and global settings"},
    {SD_SEC_ROOT, "materials", SD_KT_LIST, SD_KR_ANY, NULL, ALL, ALL, "", "required",
     "materials, at least one; their order gives the material index"},
    {SD_SEC_ROOT, "interactions", SD_KT_LIST, SD_KR_ANY, NULL, ALL, 0, "", "[]",
     "overrides for pairs of materials"},
    {SD_SEC_ROOT, "shapes", SD_KT_LIST, SD_KR_ANY, NULL, ALL, 0, "", "[]",
     "shape templates for non-spherical particles, named by particles[].shape; their order "
     "gives the shape index"},
    {SD_SEC_ROOT, "particles", SD_KT_LIST, SD_KR_ANY, NULL, ALL, 0, "", "required",
     "particle generators, at least one (none when pour is given); particle ids follow their "
     "order"},
    {SD_SEC_ROOT, "walls", SD_KT_LIST, SD_KR_ANY, NULL, ALL, 0, "", "[]", "planes, boxes and triangle meshes"},
    {SD_SEC_ROOT, "output", SD_KT_MAP, SD_KR_ANY, NULL, ALL, 0, "", "{}",
     "where and how often results are written"},
    {SD_SEC_ROOT, "pour", SD_KT_MAP, SD_KR_ANY, NULL, ALL, 0, "", "-",
     "solver grid: pour spheres layer by layer from the top (§4.1 of [Naderi 2024]; "
     "docs/grid-solver.md)"},
    {SD_SEC_ROOT, "outlet", SD_KT_MAP, SD_KR_ANY, NULL, ALL, 0, "", "-",
     "solver grid: a rectangular hole in the floor of the box wall; particles falling through "
     "are counted as discharged (§4.2 of [Naderi 2024])"},
    {SD_SEC_ROOT, "insert", SD_KT_LIST, SD_KR_ANY, NULL, ALL, 0, "", "[]",
     "solver cells: particles inserted in a region at a rate or all at once, from a mix of templates and "
     "sphere size laws, each where its bounding sphere overlaps nothing present ([Rakotonirina 2019] §4.1; "
     "docs/physics.md, Insertion and outlets)"},
    {SD_SEC_ROOT, "outlets", SD_KT_LIST, SD_KR_ANY, NULL, ALL, 0, "", "[]",
     "solver cells: regions that remove and count the particles entering them (outlet.csv)"},
    {SD_SEC_ROOT, "analysis", SD_KT_LIST, SD_KR_ANY, NULL, ALL, 0, "", "[]",
     "analyses written as CSV files of the output directory at their own cadence: porosity by voxels "
     "of the true shapes, coordination, velocity fields, speeds, energies, bed height, drum and heap "
     "angles (docs/analysis.md)"},

    {SD_SEC_SIMULATION, "dimension", SD_KT_INT, SD_KR_ANY, NULL, ALL, 0, "", "3",
     "3, or 2: the planar mode (every z, velocity z and gravity z is 0, rotation about z "
     "only, masses per unit thickness of 1 m; shapes: circle, ellipse, polygon, polybezier, "
     "fourier)"},
    {SD_SEC_SIMULATION, "multi_contact", SD_KT_ENUM, SD_KR_ANY, "average|sum", ALL, 0, "", "average",
     "how the contacts of one pair of composites (several touching element pairs) combine: "
     "average (model B of [Rakotonirina 2019], eq. 21: each contact's force divided by "
     "their number, so the contact duration does not depend on it) or sum (model A, eq. 18)"},
    {SD_SEC_SIMULATION, "local_damping", SD_KT_NUMBER, SD_KR_NONNEG, NULL, ALL, 0, "", "0",
     "velocity-based local damping coefficient alpha in [0, 1) (§3.2 of [Huang 2021]): each force "
     "and torque component gets -alpha |unbalanced| sign(velocity); 0 = off"},
    {SD_SEC_SIMULATION, "dt", SD_KT_NUMBER, SD_KR_POS, NULL, ALL, ALL, "s", "required",
     "time step; must not exceed 1/5 of the shortest contact duration"},
    {SD_SEC_SIMULATION, "steps", SD_KT_INT, SD_KR_NONNEG, NULL, ALL, 0, "", "-",
     "number of steps to run; give exactly one of steps and duration"},
    {SD_SEC_SIMULATION, "duration", SD_KT_NUMBER, SD_KR_NONNEG, NULL, ALL, 0, "s", "-",
     "simulated time to run: steps = ceil(duration / dt)"},
    {SD_SEC_SIMULATION, "gravity", SD_KT_VEC3, SD_KR_ANY, NULL, ALL, 0, "m/s^2", "[0, 0, -9.81]",
     "gravitational acceleration"},
    {SD_SEC_SIMULATION, "seed", SD_KT_INT, SD_KR_NONNEG, NULL, ALL, 0, "", "1",
     "seed of every random choice (random generator, radii, velocity jitter)"},
    {SD_SEC_SIMULATION, "threads", SD_KT_INT, SD_KR_NONNEG, NULL, ALL, 0, "", "0",
     "OpenMP threads, at most 1024; 0 = OMP_NUM_THREADS, else the cores not busy at the start"},
    {SD_SEC_SIMULATION, "contact_law", SD_KT_ENUM, SD_KR_ANY, SD_LAW_CHOICES, ALL, 0, "",
     "hertz_mindlin", "default contact law for every pair of materials"},
    {SD_SEC_SIMULATION, "skin", SD_KT_NUMBER, SD_KR_NONNEG, NULL, ALL, 0, "m", "0",
     "Verlet skin of the pair list; 0 = 0.2 x the smallest radius"},
    {SD_SEC_SIMULATION, "max_overlap", SD_KT_NUMBER, SD_KR_NONNEG, NULL, ALL, 0, "", "0.5",
     "the overlap guard (cells solver): a contact deeper than this fraction of the smaller radius "
     "(bounding radius for shapes) stops the run, naming both particles, after writing the state to "
     "failed-STEP.h5 (docs/checkpoints.md); 0 = off"},
    {SD_SEC_SIMULATION, "solver", SD_KT_ENUM, SD_KR_ANY, "cells|grid", ALL, 0, "", "cells",
     "cells: the general engine; grid: the dense grid-stencil solver of [Naderi 2024] for equal "
     "(R_max/R_min <= 2) spheres inside a box wall, same physics (docs/grid-solver.md)"},
    {SD_SEC_SIMULATION, "backend", SD_KT_ENUM, SD_KR_ANY, "auto|cpu|cuda", ALL, 0, "", "auto",
     "where the step runs (either solver): auto (an NVIDIA GPU when shapedem was built with CUDA and "
     "one is usable, else the CPU; summary.txt says which and why), cpu, or cuda (refused, with the "
     "reason, when no GPU is usable); the same bits on both"},
    {SD_SEC_SIMULATION, "periodic", SD_KT_ENUM_LIST, SD_KR_ANY, "x|y|z", ALL, 0, "", "[]",
     "axes with periodic boundaries (LIGGGHTS' boundary p), e.g. [x, y]: a particle leaving the "
     "domain on one side comes back on the other, and contacts act across the boundary; needs "
     "domain, solver cells, no wall across a periodic axis, and a period of at least "
     "2 (2 r_max + skin); not z in dimension 2"},
    {SD_SEC_SIMULATION, "domain", SD_KT_BOX, SD_KR_ANY, NULL, ALL, 0, "m", "-",
     "the periodic box {min: [x, y, z], max: [x, y, z]}; read on the periodic axes, where every "
     "particle must start inside [min, max); frames show positions wrapped into it"},
    {SD_SEC_SIMULATION, "mpi_rebalance_every", SD_KT_INT, SD_KR_NONNEG, NULL, ALL, 0, "", "0",
     "under mpirun (docs/mpi.md): at the first pair-list rebuild after every this many steps, the "
     "split is cut again into equal particle counts, the same grid of boxes (0: the split of the "
     "start is kept); the results do not change"},
    {SD_SEC_SIMULATION, "mpi_split", SD_KT_ENUM_OR_INT3, SD_KR_ONE, "auto|x|y|z", ALL, 0, "", "auto",
     "under mpirun (docs/mpi.md): the grid of boxes, cut by particle count: auto (the rank count "
     "factored into px py pz for the least cut area over the particles' extent), x, y or z (slabs "
     "along that axis), or [px, py, pz] whose product must be the rank count; ignored in a serial "
     "run; the results do not change"},
    {SD_SEC_SIMULATION, "stop_when", SD_KT_MAP, SD_KR_ANY, NULL, ALL, 0, "", "-",
     "end the run before its steps when the particles have come to rest (the keys of "
     "simulation.stop_when); summary.txt says when and why"},

    {SD_SEC_MATERIAL, "name", SD_KT_STRING, SD_KR_NONEMPTY, NULL, ALL, ALL, "", "required",
     "unique name, used by particles, walls and interactions"},
    {SD_SEC_MATERIAL, "density", SD_KT_NUMBER, SD_KR_POS, NULL, ALL, ALL, "kg/m^3", "required",
     "mass density"},
    {SD_SEC_MATERIAL, "youngs_modulus", SD_KT_NUMBER, SD_KR_POS, NULL, ALL, 0, "Pa", "unset",
     "Young's modulus; required when a hertz_mindlin contact involves the material"},
    {SD_SEC_MATERIAL, "poisson_ratio", SD_KT_NUMBER, SD_KR_POISSON, NULL, ALL, 0, "", "0.3",
     "Poisson's ratio"},
    {SD_SEC_MATERIAL, "restitution", SD_KT_NUMBER, SD_KR_UNIT, NULL, ALL, 0, "", "0.5",
     "normal coefficient of restitution"},
    {SD_SEC_MATERIAL, "friction", SD_KT_NUMBER, SD_KR_NONNEG, NULL, ALL, 0, "", "0.5",
     "sliding (Coulomb) friction coefficient"},
    {SD_SEC_MATERIAL, "rolling_friction", SD_KT_NUMBER, SD_KR_NONNEG, NULL, ALL, 0, "", "0",
     "rolling resistance coefficient"},
    {SD_SEC_MATERIAL, "stiffness", SD_KT_NUMBER, SD_KR_NONNEG, NULL, ALL, 0, "N/m", "0",
     "normal stiffness k_n of the linear law; 0 = unset, required when a linear contact "
     "involves the material and its interaction sets no stiffness"},
    {SD_SEC_MATERIAL, "tangential_stiffness_ratio", SD_KT_NUMBER, SD_KR_POS, NULL, ALL, 0, "",
     "0.2857142857142857", "k_t / k_n of the linear law (2/7)"},
    {SD_SEC_MATERIAL, "damping", SD_KT_NUMBER, SD_KR_NONNEG, NULL, ALL, 0, "N s/m", "0",
     "linear law: viscous coefficient eta of the normal and tangential dashpots (eqs. 6 "
     "and 8 of [Naderi 2024]), used instead of the restitution; 0 = damping from the restitution"},
    {SD_SEC_MATERIAL, "volume_stiffness", SD_KT_NUMBER, SD_KR_NONNEG, NULL, ALL, 0, "N/m^3", "0",
     "stiffness k_V of the volume_linear law (F = k_V V, V the overlap volume of two "
     "polyhedra); 0 = unset, required when a volume_linear contact involves the material"},
    {SD_SEC_MATERIAL, "volume_face_omega_dt", SD_KT_NUMBER, SD_KR_UNIT, NULL, ALL, 0, "", "off",
     "volume law: regularise near zero overlap so a face contact is never stiffer than omega dt = this "
     "(0.5 runs [Xu n.d.]'s own moduli at its time steps; a pair takes the smaller of its materials'; "
     "docs/physics.md)"},

    {SD_SEC_INTERACTION, "between", SD_KT_NAME_PAIR, SD_KR_NONEMPTY, NULL, ALL, ALL, "",
     "required", "the two material names (may be the same)"},
    {SD_SEC_INTERACTION, "restitution", SD_KT_NUMBER, SD_KR_UNIT, NULL, ALL, 0, "", "mixed",
     "normal coefficient of restitution of the pair"},
    {SD_SEC_INTERACTION, "friction", SD_KT_NUMBER, SD_KR_NONNEG, NULL, ALL, 0, "", "mixed",
     "sliding friction coefficient of the pair"},
    {SD_SEC_INTERACTION, "rolling_friction", SD_KT_NUMBER, SD_KR_NONNEG, NULL, ALL, 0, "",
     "mixed", "rolling resistance coefficient of the pair"},
    {SD_SEC_INTERACTION, "stiffness", SD_KT_NUMBER, SD_KR_POS, NULL, ALL, 0, "N/m", "mixed",
     "linear-law normal stiffness of the pair"},
    {SD_SEC_INTERACTION, "damping", SD_KT_NUMBER, SD_KR_NONNEG, NULL, ALL, 0, "N s/m", "mixed",
     "linear-law viscous coefficient eta of the pair (0 = from the restitution)"},
    {SD_SEC_INTERACTION, "volume_stiffness", SD_KT_NUMBER, SD_KR_POS, NULL, ALL, 0, "N/m^3", "mixed",
     "volume_linear-law stiffness k_V of the pair"},
    {SD_SEC_INTERACTION, "contact_law", SD_KT_ENUM, SD_KR_ANY, SD_LAW_CHOICES, ALL, 0, "",
     "simulation.contact_law", "contact law of the pair"},

    {SD_SEC_SHAPE, "name", SD_KT_STRING, SD_KR_NONEMPTY, NULL, ALL, ALL, "", "required",
     "unique name, used by particles[].shape"},
    {SD_SEC_SHAPE, "type", SD_KT_ENUM, SD_KR_ANY, SD_SHAPE_CHOICES, ALL, ALL, "", "required",
     "the convex shape; every shape may be rounded (rounding) or given a margin"},
    {SD_SEC_SHAPE, "radius", SD_KT_NUMBER, SD_KR_POS, NULL, SSPH | SCIRC, SSPH | SCIRC, "m", "required",
     "sphere or circle radius"},
    {SD_SEC_SHAPE, "axes", SD_KT_VEC2, SD_KR_POS, NULL, SELL2, SELL2, "m", "required",
     "ellipse semi-axes [a, b] along x, y"},
    {SD_SEC_SHAPE, "points", SD_KT_VEC2_LIST, SD_KR_ANY, NULL, SPOLY2 | SBEZ, SPOLY2 | SBEZ, "m",
     "required",
     "polygon: points whose convex hull is the shape (at least 3, not collinear); polybezier: "
     "3m control points of m cubic Bezier segments P3k..P3k+3 closing on the first point, a "
     "convex curve (any frame: moved to the centroid)"},
    {SD_SEC_SHAPE, "fourier_a", SD_KT_NUM_LIST, SD_KR_ANY, NULL, SFOUR, SFOUR, "m", "required",
     "a_0 .. a_N of the support function p(theta) = a_0/2 + sum a_k cos k theta + b_k sin k "
     "theta (eq. 2 of [Huang 2021]); the series must be convex, p + p'' >= 0 (eq. 5; `shapedem shape "
     "fit-fourier` reduces it)"},
    {SD_SEC_SHAPE, "fourier_b", SD_KT_NUM_LIST, SD_KR_ANY, NULL, SFOUR, 0, "m", "zeros",
     "b_1 .. b_N (one fewer than fourier_a)"},
    {SD_SEC_SHAPE, "size", SD_KT_NUM_OR_VEC3, SD_KR_POS, NULL, SBOX | SCYL | SCONE | SPOLY, SBOX, "m",
     "required (box)",
     "box: full edge lengths [x, y, z]; cylinder: [diameter, -, length] and cone: [base "
     "diameter, -, height], axis z, y ignored (or give diameter and length / height); a number "
     "sets all three. Polyhedron preset: the diameter of its circumscribed sphere (prism and "
     "cylinder presets: [diameter, -, length] like the cylinder)"},
    {SD_SEC_SHAPE, "diameter", SD_KT_NUMBER, SD_KR_POS, NULL, SCYL | SCONE | SPOLY | SCOMP, 0, "m", "size x",
     "cylinder diameter or cone base diameter, with length (cylinder) or height (cone) instead "
     "of size; prism and cylinder presets: the diameter of the circle through the n-gon's corners; "
     "composite presets: see preset"},
    {SD_SEC_SHAPE, "length", SD_KT_NUMBER, SD_KR_POS, NULL, SCYL | SPOLY | SCOMP, 0, "m", "size z",
     "cylinder (and prism or cylinder preset) length along its axis z, with diameter instead of "
     "size; composite presets: see preset"},
    {SD_SEC_SHAPE, "width", SD_KT_NUMBER, SD_KR_POS, NULL, SCOMP, 0, "m", "-",
     "composite presets: arm width (cross2d, lshape, tshape), wall width (ring), bar diameter "
     "(dumbbell)"},
    {SD_SEC_SHAPE, "thickness", SD_KT_NUMBER, SD_KR_POS, NULL, SCOMP, 0, "m", "-",
     "composite presets cross2d, lshape, tshape: thickness along z"},
    {SD_SEC_SHAPE, "count", SD_KT_INT, SD_KR_POS, NULL, SCOMP, 0, "", "-",
     "composite preset ring: number of box segments, 3 to 64"},
    {SD_SEC_SHAPE, "elements", SD_KT_LIST, SD_KR_ANY, NULL, SCOMP, 0, "", "-",
     "composite (glued convex elements, [Rakotonirina 2019]): its convex elements, each a shape listed "
     "before it (shape: name) or inline (type and its size keys), with position and orientation "
     "in the composite's frame; give elements or preset"},
    {SD_SEC_SHAPE, "lattice", SD_KT_INT, SD_KR_POS, NULL, SCOMP, 0, "", "200",
     "composite: points per direction of the voxel lattice (4 to 500) that integrates the volume "
     "counted twice where elements overlap (§2.3 of [Rakotonirina 2019]), or the union itself where "
     "more than 85 percent of the elements' summed volume is shared (long chains of overlapping elements); "
     "without overlaps the mass properties are exact sums"},
    {SD_SEC_SHAPE, "height", SD_KT_NUMBER, SD_KR_POS, NULL, SCONE, 0, "m", "size z",
     "cone height along its axis z (apex up), with diameter instead of size"},
    {SD_SEC_SHAPE, "semi_axes", SD_KT_VEC3, SD_KR_POS, NULL, SELL, SELL, "m", "required",
     "semi-axes a, b, c along x, y, z"},
    {SD_SEC_SHAPE, "vertices", SD_KT_VEC3_LIST, SD_KR_ANY, NULL, SPOLY, 0, "m", "-",
     "points whose convex hull is the shape, at least 4 and not coplanar (any frame: the "
     "template is moved to its centre of mass); give one of vertices, file and preset"},
    {SD_SEC_SHAPE, "file", SD_KT_STRING, SD_KR_NONEMPTY, NULL, SPOLY, 0, "", "-",
     "OBJ file (v and f lines) or STL file (ASCII or binary), relative to the scene file, in m "
     "before scale: a convex mesh (see nonconvex); give one of vertices, file and preset"},
    {SD_SEC_SHAPE, "nonconvex", SD_KT_ENUM, SD_KR_ANY, "reject|hull", SPOLY, 0, "", "reject",
     "a mesh file whose faces are not on its convex hull: reject (an error that says how far "
     "from convex it is) or hull (take the convex hull, with a warning)"},
    {SD_SEC_SHAPE, "preset", SD_KT_ENUM, SD_KR_ANY, SD_POLY_CHOICES SD_COMP_CHOICES, SPOLY | SCOMP, 0, "", "-",
     "a built-in polyhedron, sized by size (circumscribed diameter) or edge: Platonic solids; "
     "prism (sides-gon, axis z); cylinder (the same solid with cap centres, §3.1 of [Xu n.d.]: "
     "sides 20 gives 42 vertices, 80 triangles, 22 faces); random (seeded, faces or "
     "vertex_count); give one of vertices, file and preset. Type composite: a built-in glued "
     "shape, instead of elements: cross2d (tile spacer; length, width, thickness), cross3d "
     "(three cylinders; diameter, length), lshape and tshape (length, width, thickness), ring "
     "(count boxes; diameter, width, length), dumbbell (diameter, length, width), spheres9 and "
     "spheres54 (glued-sphere cylinders of Fig. 10 of [Rakotonirina 2019]; diameter, length); "
     "docs/physics.md shows each"},
    {SD_SEC_SHAPE, "edge", SD_KT_NUMBER, SD_KR_POS, NULL, SPOLY, 0, "m", "-",
     "edge length of a Platonic preset, instead of size"},
    {SD_SEC_SHAPE, "sides", SD_KT_INT, SD_KR_POS, NULL, SPOLY, 0, "", "-",
     "prism and cylinder presets: number of sides n, 3 to 500 (required for them)"},
    {SD_SEC_SHAPE, "faces", SD_KT_INT, SD_KR_POS, NULL, SPOLY, 0, "", "-",
     "random preset: number of faces, 4 to 500 (planes tangent to a sphere at random normals); "
     "give faces or vertex_count"},
    {SD_SEC_SHAPE, "vertex_count", SD_KT_INT, SD_KR_POS, NULL, SPOLY, 0, "", "-",
     "random preset: number of vertices, 4 to 500 (random points on a sphere); give faces or "
     "vertex_count"},
    {SD_SEC_SHAPE, "seed", SD_KT_INT, SD_KR_NONNEG, NULL, SPOLY, 0, "", "1",
     "random preset: seed (the same seed gives the same polyhedron on every machine)"},
    {SD_SEC_SHAPE, "rounding", SD_KT_NUMBER, SD_KR_NONNEG, NULL, ALL, 0, "m", "0",
     "radius of a sphere swept over the shape: edges are rounded and every outer size grows by "
     "2 x rounding"},
    {SD_SEC_SHAPE, "margin", SD_KT_NUMBER, SD_KR_NONNEG, NULL, S3D & ~SCOMP, 0, "m", "0",
     "the outer size stays as given: the core is shrunk by margin and swept by it, so edges "
     "are rounded by margin; give at most one of rounding and margin"},
    {SD_SEC_SHAPE, "scale", SD_KT_NUMBER, SD_KR_POS, NULL, ALL, 0, "", "1",
     "multiplies every length of the shape (sizes, vertices, rounding, margin)"},

    {SD_SEC_ELEMENT, "shape", SD_KT_STRING, SD_KR_NONEMPTY, NULL, ALL, 0, "", "-",
     "name of a convex shape listed before the composite in shapes:; or give type and its "
     "size keys here (an inline element)"},
    {SD_SEC_ELEMENT, "type", SD_KT_ENUM, SD_KR_ANY, "sphere|box|cylinder|ellipsoid", ALL, 0, "", "-",
     "inline element: its convex type (sphere: radius; box: size; cylinder: diameter, length; "
     "ellipsoid: semi_axes)"},
    {SD_SEC_ELEMENT, "radius", SD_KT_NUMBER, SD_KR_POS, NULL, ALL, 0, "m", "-", "inline sphere radius"},
    {SD_SEC_ELEMENT, "size", SD_KT_NUM_OR_VEC3, SD_KR_POS, NULL, ALL, 0, "m", "-",
     "inline box: full edge lengths [x, y, z] (a number sets all three)"},
    {SD_SEC_ELEMENT, "diameter", SD_KT_NUMBER, SD_KR_POS, NULL, ALL, 0, "m", "-", "inline cylinder diameter"},
    {SD_SEC_ELEMENT, "length", SD_KT_NUMBER, SD_KR_POS, NULL, ALL, 0, "m", "-",
     "inline cylinder length along its axis z"},
    {SD_SEC_ELEMENT, "semi_axes", SD_KT_VEC3, SD_KR_POS, NULL, ALL, 0, "m", "-", "inline ellipsoid semi-axes"},
    {SD_SEC_ELEMENT, "rounding", SD_KT_NUMBER, SD_KR_NONNEG, NULL, ALL, 0, "m", "0",
     "inline element: radius of a sphere swept over it"},
    {SD_SEC_ELEMENT, "position", SD_KT_VEC3, SD_KR_ANY, NULL, ALL, 0, "m", "[0, 0, 0]",
     "the element's centre of mass in the composite's frame"},
    {SD_SEC_ELEMENT, "orientation", SD_KT_ORIENTATION, SD_KR_ANY, NULL, ALL, 0, "", "identity",
     "the element's principal frame in the composite's frame: identity or a quaternion "
     "[w, x, y, z] (not random)"},

    {SD_SEC_PARTICLES, "generator", SD_KT_ENUM, SD_KR_ANY, "lattice|random|list|csv", ALL, ALL,
     "", "required", "how the particles are made"},
    {SD_SEC_PARTICLES, "material", SD_KT_STRING, SD_KR_NONEMPTY, NULL, ALL, LAT | RND | CSV, "",
     "required", "material name (list: the default of entries that name none)"},
    {SD_SEC_PARTICLES, "radius", SD_KT_NUM_OR_RANGE, SD_KR_POS, NULL, LAT | RND, 0, "m",
     "required unless shape",
     "sphere radius, or {min, max} for radii uniform in [min, max]; give radius or shape, "
     "exactly one"},
    {SD_SEC_PARTICLES, "shape", SD_KT_STRING, SD_KR_NONEMPTY, NULL, LAT | RND | LST | CSV, 0, "", "-",
     "name of a shape in shapes: the generator makes rigid bodies of that shape instead of "
     "spheres (list, csv: the shape of entries and rows that give neither radius nor shape)"},
    {SD_SEC_PARTICLES, "orientation", SD_KT_ORIENTATION, SD_KR_ANY, NULL, LAT | RND | LST | CSV, 0, "",
     "random",
     "orientation of shaped bodies: identity, random (uniform over all rotations, from "
     "simulation.seed) or a quaternion [w, x, y, z] (normalised)"},
    {SD_SEC_PARTICLES, "origin", SD_KT_VEC3, SD_KR_ANY, NULL, LAT, LAT, "m", "required",
     "centre of the first sphere"},
    {SD_SEC_PARTICLES, "spacing", SD_KT_NUM_OR_VEC3, SD_KR_POS, NULL, LAT, LAT, "m", "required",
     "distance between neighbouring centres, per axis; >= 2 x the largest radius (shapes: "
     "the bounding radius)"},
    {SD_SEC_PARTICLES, "count", SD_KT_INT3, SD_KR_ONE, NULL, LAT, LAT, "", "required",
     "spheres along x, y and z (x varies fastest in id order)"},
    {SD_SEC_PARTICLES, "box", SD_KT_BOX, SD_KR_ANY, NULL, RND, RND, "m", "required",
     "region the spheres (shapes: their bounding spheres) lie fully inside"},
    {SD_SEC_PARTICLES, "number", SD_KT_INT, SD_KR_ONE, NULL, RND, RND, "", "required",
     "number of particles, placed without overlap by random sequential addition (shapes: "
     "their bounding spheres do not overlap)"},
    {SD_SEC_PARTICLES, "spheres", SD_KT_LIST, SD_KR_ANY, NULL, LST, LST, "", "required",
     "the particles, one mapping each (keys under particles[].spheres[]): spheres, or bodies "
     "of a shape"},
    {SD_SEC_PARTICLES, "file", SD_KT_STRING, SD_KR_NONEMPTY, NULL, CSV, CSV, "", "required",
     "CSV file, relative to the scene file; a header naming the columns, in any order: x, y, "
     "z, and radius (a sphere) or shape (a name from shapes; one of the two per row), "
     "optionally vx, vy, vz, qw, qx, qy, qz (orientation, all four or none, normalised), wx, "
     "wy, wz and material (a name; default the generator's); an empty optional cell takes the "
     "generator's value; scripts/frame_to_csv.py writes one from a frame (docs/output.md). Or "
     "a checkpoint of another run (a name ending in .h5, cells solver, same dimension): its "
     "particles of every kind as they were (positions, orientations, velocities, spins), each "
     "template found in shapes by name and of the same kind (a scaled copy an insertion made, "
     "TEMPLATE_iIeEsK, is made again with the same factor from the template of its base's "
     "name), each material by name (else the generator's); docs/checkpoints.md"},
    {SD_SEC_PARTICLES, "shift", SD_KT_VEC3, SD_KR_ANY, NULL, CSV, 0, "m", "[0, 0, 0]",
     "added to every position the file gives (a settled bed moved into new equipment)"},
    {SD_SEC_PARTICLES, "velocity", SD_KT_VEC3, SD_KR_ANY, NULL, ALL, 0, "m/s", "[0, 0, 0]",
     "initial velocity (list entries and CSV columns override it)"},
    {SD_SEC_PARTICLES, "velocity_jitter", SD_KT_NUMBER, SD_KR_NONNEG, NULL, ALL, 0, "m/s", "0",
     "uniform random velocity in [-j, j] added to each component"},
    {SD_SEC_PARTICLES, "angular_velocity", SD_KT_VEC3, SD_KR_ANY, NULL, ALL, 0, "rad/s",
     "[0, 0, 0]", "initial angular velocity, world frame (list entries override it)"},

    {SD_SEC_SPHERE, "position", SD_KT_VEC3, SD_KR_ANY, NULL, ALL, ALL, "m", "required",
     "centre"},
    {SD_SEC_SPHERE, "radius", SD_KT_NUMBER, SD_KR_POS, NULL, ALL, 0, "m",
     "required unless shape", "sphere radius; give radius or shape (here or the generator's)"},
    {SD_SEC_SPHERE, "shape", SD_KT_STRING, SD_KR_NONEMPTY, NULL, ALL, 0, "",
     "generator's shape", "name of a shape in shapes: a rigid body of that shape"},
    {SD_SEC_SPHERE, "orientation", SD_KT_ORIENTATION, SD_KR_ANY, NULL, ALL, 0, "",
     "generator's orientation", "orientation of a shaped body: identity, random or [w, x, y, z]"},
    {SD_SEC_SPHERE, "velocity", SD_KT_VEC3, SD_KR_ANY, NULL, ALL, 0, "m/s",
     "generator's velocity", "initial velocity"},
    {SD_SEC_SPHERE, "angular_velocity", SD_KT_VEC3, SD_KR_ANY, NULL, ALL, 0, "rad/s",
     "generator's angular_velocity", "initial angular velocity, world frame"},
    {SD_SEC_SPHERE, "material", SD_KT_STRING, SD_KR_NONEMPTY, NULL, ALL, 0, "",
     "generator's material", "material name"},

    {SD_SEC_WALL, "name", SD_KT_STRING, SD_KR_NONEMPTY, NULL, ALL, 0, "", "wall0, wall1, ...",
     "name in output and messages"},
    {SD_SEC_WALL, "type", SD_KT_ENUM, SD_KR_ANY, "plane|box|mesh|drum", ALL, ALL, "", "required",
     "an infinite plane, a box container, a triangle mesh read from an STL or OBJ file (§2.4 of "
     "[Xu n.d.]; docs/mesh-walls.md), or an analytic rotating cylindrical drum (3D, cells solver; "
     "docs/physics.md)"},
    {SD_SEC_WALL, "material", SD_KT_STRING, SD_KR_NONEMPTY, NULL, ALL, ALL, "", "required",
     "material name"},
    {SD_SEC_WALL, "point", SD_KT_VEC3, SD_KR_ANY, NULL, PLANE, PLANE, "m", "required",
     "a point on the plane"},
    {SD_SEC_WALL, "normal", SD_KT_VEC3, SD_KR_ANY, NULL, PLANE, PLANE, "", "required",
     "non-zero normal (normalised); particles live on the side it points to"},
    {SD_SEC_WALL, "min", SD_KT_VEC3, SD_KR_ANY, NULL, BOX, BOX, "m", "required",
     "lower corner"},
    {SD_SEC_WALL, "max", SD_KT_VEC3, SD_KR_ANY, NULL, BOX, BOX, "m", "required",
     "upper corner, > min on every axis; particles stay inside"},
    {SD_SEC_WALL, "open", SD_KT_ENUM_LIST, SD_KR_ANY, "xmin|xmax|ymin|ymax|zmin|zmax", BOX, 0, "",
     "[]", "faces left out of the box"},
    {SD_SEC_WALL, "velocity", SD_KT_VEC3, SD_KR_ANY, NULL, PLANE | BOX, 0, "m/s", "[0, 0, 0]",
     "prescribed velocity (loading), applied from move_start to move_end"},
    {SD_SEC_WALL, "move_start", SD_KT_NUMBER, SD_KR_NONNEG, NULL, PLANE | BOX, 0, "s", "0",
     "time the prescribed velocity starts; the strains of biaxial.csv count from the first "
     "start of a non-zero velocity"},
    {SD_SEC_WALL, "move_end", SD_KT_NUMBER, SD_KR_NONNEG, NULL, PLANE | BOX, 0, "s", "never",
     "time the prescribed velocity stops"},
    {SD_SEC_WALL, "servo_stress", SD_KT_NUMBER, SD_KR_NONNEG, NULL, PLANE, 0, "Pa", "0",
     "servo control (§3.2 of [Huang 2021]): each step the plane moves along its normal so the normal "
     "stress it carries (force over the distance between the two opposite planes across it; "
     "2D: per 1 m thickness) tracks this value; 0 = no servo; wins over velocity where both act"},
    {SD_SEC_WALL, "servo_start", SD_KT_NUMBER, SD_KR_NONNEG, NULL, PLANE, 0, "s", "0",
     "time the servo starts"},
    {SD_SEC_WALL, "servo_end", SD_KT_NUMBER, SD_KR_NONNEG, NULL, PLANE, 0, "s", "never",
     "time the servo stops"},
    {SD_SEC_WALL, "servo_gain", SD_KT_NUMBER, SD_KR_NONNEG, NULL, PLANE, 0, "m/(s Pa)", "0",
     "servo gain G: velocity = G (target - stress); 0 = automatic, half the gain that would "
     "cancel the error in one step from the contact stiffness on the wall (docs/physics.md)"},
    {SD_SEC_WALL, "servo_max_speed", SD_KT_NUMBER, SD_KR_NONNEG, NULL, PLANE, 0, "m/s", "0",
     "cap of the servo velocity; 0 = a tenth of the skin per step"},
    {SD_SEC_WALL, "file", SD_KT_STRING, SD_KR_NONEMPTY, NULL, MESH, MESH, "", "required",
     "STL (ASCII or binary) or OBJ file of the mesh, relative to the scene file; checked as it is read "
     "(truncated or inconsistent files, NaN, non-orientable surfaces are errors naming the facet; "
     "degenerate and duplicated facets are dropped and wrongly wound ones turned, with a warning)"},
    {SD_SEC_WALL, "scale", SD_KT_NUMBER, SD_KR_POS, NULL, MESH, 0, "m per file unit", "1",
     "length of one file unit, e.g. 0.001 for a file in mm; applied first"},
    {SD_SEC_WALL, "orientation", SD_KT_ORIENTATION, SD_KR_ANY, NULL, MESH, 0, "", "identity",
     "rotation of the (scaled) file about its origin, identity or a quaternion [w, x, y, z] as for "
     "particles (not random); applied after scale; not together with rotation"},
    {SD_SEC_WALL, "rotation", SD_KT_VEC3, SD_KR_ANY, NULL, MESH, 0, "degrees", "[0, 0, 0]",
     "rotation of the (scaled) file about its origin by angles [rx, ry, rz]: rx about x first, then ry "
     "about y, then rz about z, each right-handed about the fixed world axis (R = Rz Ry Rx); "
     "e.g. [90, 0, 0] turns a file's y axis onto z; not together with orientation"},
    {SD_SEC_WALL, "position", SD_KT_VEC3, SD_KR_ANY, NULL, MESH, 0, "m", "[0, 0, 0]",
     "translation applied last: world = position + R (scale x_file), the pose at t = 0"},
    {SD_SEC_WALL, "side", SD_KT_ENUM, SD_KR_ANY, "inside|outside", MESH, 0, "", "inside",
     "closed parts of the mesh (every edge shared by two facets): inside = particles inside (a drum, "
     "a box), outside = an obstacle; open parts hold particles on the side their facets' right-hand "
     "normals point to (docs/mesh-walls.md)"},
    {SD_SEC_WALL, "weld_tolerance", SD_KT_NUMBER, SD_KR_NONNEG, NULL, MESH, 0, "m", "0",
     "vertices closer than this become one; 0 = 1e-9 of the mesh's bounding-box diagonal"},
    {SD_SEC_WALL, "coplanar_tolerance", SD_KT_NUMBER, SD_KR_NONNEG, NULL, MESH, 0, "rad", "0",
     "neighbouring facets whose normals agree within this angle form one plane group (one contact); "
     "0 = 1e-6"},
    {SD_SEC_WALL, "torque_point", SD_KT_VEC3, SD_KR_ANY, NULL, MESH, 0, "m", "reference point",
     "point the mesh's torque (its walls.csv and stats.csv columns, summary.txt) is taken about, e.g. on a "
     "drum's axis; it moves with the mesh's translation; default: a rotating mesh's axis_point, else "
     "the centre of the mesh's bounding box"},
    {SD_SEC_WALL, "motion", SD_KT_MAP, SD_KR_ANY, NULL, MESH, 0, "", "{type: fixed}",
     "the mesh's rigid motion from its pose at t = 0 (the keys of walls[].motion)"},
    {SD_SEC_WALL, "center", SD_KT_VEC3, SD_KR_ANY, NULL, DRUM, DRUM, "m", "required",
     "drum: the middle of its axis"},
    {SD_SEC_WALL, "axis", SD_KT_VEC3, SD_KR_ANY, NULL, DRUM, 0, "", "[0, 0, 1]",
     "drum: its axis (normalised); it turns right-handed about it"},
    {SD_SEC_WALL, "radius", SD_KT_NUMBER, SD_KR_POS, NULL, DRUM, DRUM, "m", "required",
     "drum: inner radius of the mantle; particles live inside it"},
    {SD_SEC_WALL, "length", SD_KT_NUMBER, SD_KR_POS, NULL, DRUM, DRUM, "m", "required",
     "drum: distance between the end caps, centred on center"},
    {SD_SEC_WALL, "rpm", SD_KT_NUMBER, SD_KR_ANY, NULL, DRUM, 0, "rev/min", "0",
     "drum: turning speed about +axis once spun up (start, ramp; negative turns the other way); contacts see the "
     "particle's motion relative to the turning wall"},
    {SD_SEC_WALL, "start", SD_KT_NUMBER, SD_KR_NONNEG, NULL, DRUM, 0, "s", "0",
     "drum: the time it starts to turn (before it, it rests: fill and settle a bed, then turn it)"},
    {SD_SEC_WALL, "ramp", SD_KT_NUMBER, SD_KR_NONNEG, NULL, DRUM, 0, "s", "0",
     "drum: spin-up time: from start its speed rises linearly from 0 to rpm over ramp (0: at once), "
     "as a rotating mesh's motion.ramp"},
    {SD_SEC_WALL, "caps", SD_KT_ENUM, SD_KR_ANY, "both|none|low|high", DRUM, 0, "", "both",
     "drum: the closed end caps (low: the one at center - length/2 axis); none with the axis along a "
     "periodic axis of simulation.domain gives periodic axial boundaries ([Rakotonirina 2019] §4.2)"},

    {SD_SEC_MESH_MOTION, "type", SD_KT_ENUM, SD_KR_ANY, "fixed|translate|rotate|table", ALL, ALL, "",
     "required", "fixed: rests; translate: constant velocity; rotate: about the axis at rpm; table: "
     "displacement and angle from a CSV time table"},
    {SD_SEC_MESH_MOTION, "velocity", SD_KT_VEC3, SD_KR_ANY, NULL, MTRA, MTRA, "m/s", "required",
     "translation velocity"},
    {SD_SEC_MESH_MOTION, "axis_point", SD_KT_VEC3, SD_KR_ANY, NULL, MROT | MTAB, MROT, "m",
     "required", "a point on the rotation axis, world frame at t = 0 (table: it moves with the "
     "displacement; default [0, 0, 0])"},
    {SD_SEC_MESH_MOTION, "axis", SD_KT_VEC3, SD_KR_ANY, NULL, MROT | MTAB, 0, "", "[0, 0, 1]",
     "direction of the rotation axis (normalised); positive rpm and angles turn right-handed about it"},
    {SD_SEC_MESH_MOTION, "rpm", SD_KT_NUMBER, SD_KR_ANY, NULL, MROT, MROT, "rev/min", "required",
     "rotation speed (negative: the other way)"},
    {SD_SEC_MESH_MOTION, "start", SD_KT_NUMBER, SD_KR_NONNEG, NULL, MTRA | MROT, 0, "s", "0",
     "time the motion starts"},
    {SD_SEC_MESH_MOTION, "ramp", SD_KT_NUMBER, SD_KR_NONNEG, NULL, MTRA | MROT, 0, "s", "0",
     "the speed rises linearly from 0 over this time after start; 0 = at once"},
    {SD_SEC_MESH_MOTION, "table", SD_KT_STRING, SD_KR_NONEMPTY, NULL, MTAB, MTAB, "", "required",
     "CSV file relative to the scene file, rows t, dx, dy, dz, angle_deg (s, m, m, m, degrees about the "
     "axis) with t increasing; an optional header line of names (a first line that starts with a digit, "
     "sign or point is a row, and is refused when it does not parse); a UTF-8 byte-order mark skipped; "
     "blank lines and lines starting with # skipped; "
     "linear between rows, held before the first and after the last"},


    {SD_SEC_OUTPUT, "directory", SD_KT_STRING, SD_KR_ANY, NULL, ALL, 0, "", "\"\"",
     "output directory, relative to the current directory; \"\" = out/NAME for a scene NAME.yaml"},
    {SD_SEC_OUTPUT, "every", SD_KT_INT, SD_KR_ONE, NULL, ALL, 0, "", "steps/100",
     "steps between frames (the default is at least 1)"},
    {SD_SEC_OUTPUT, "stats_every", SD_KT_INT, SD_KR_ONE, NULL, ALL, 0, "", "every/10",
     "steps between rows of stats.csv (the default is at least 1)"},
    {SD_SEC_OUTPUT, "formats", SD_KT_ENUM_LIST, SD_KR_ANY, "vtk|csv|shapes|dump|h5md", ALL, 0, "", "[vtk, csv]",
     "what to write: vtk frames, csv statistics, shapes: with each frame the particles' true shapes as "
     "surfaces (shapes_NNNNNN.vtp, implies vtk), dump: with each frame a snapshot appended to "
     "trajectory.dump, LAMMPS dump text, h5md: with each frame a frame appended to trajectory.h5md, the HDF5 "
     "particle-trajectory standard H5MD (docs/output.md)"},
    {SD_SEC_OUTPUT, "shape_resolution", SD_KT_INT, SD_KR_ONE, NULL, ALL, 0, "", "24",
     "directions per full turn when the shapes files tessellate curved surfaces (8 to 64); flat faces "
     "are drawn exactly"},
    {SD_SEC_OUTPUT, "checkpoint_every", SD_KT_INT, SD_KR_NONNEG, NULL, ALL, 0, "", "0",
     "steps between checkpoints (checkpoint-STEP.h5 in the output directory, docs/checkpoints.md); 0 = none"},
    {SD_SEC_OUTPUT, "checkpoint_minutes", SD_KT_NUMBER, SD_KR_NONNEG, NULL, ALL, 0, "min", "0",
     "minutes of wall time between checkpoints (besides checkpoint_every); 0 = none"},

    {SD_SEC_POUR, "material", SD_KT_STRING, SD_KR_NONEMPTY, NULL, ALL, ALL, "", "required",
     "material of the poured spheres"},
    {SD_SEC_POUR, "radius", SD_KT_NUMBER, SD_KR_POS, NULL, ALL, ALL, "m", "required",
     "radius of the poured spheres"},
    {SD_SEC_POUR, "count", SD_KT_INT, SD_KR_ONE, NULL, ALL, 0, "", "-",
     "spheres to pour in all (give count or fill_height)"},
    {SD_SEC_POUR, "fill_height", SD_KT_NUMBER, SD_KR_POS, NULL, ALL, 0, "m", "-",
     "pour as many spheres as fill the box floor's area up to this height above the floor at "
     "packing_fraction (give count or fill_height)"},
    {SD_SEC_POUR, "packing_fraction", SD_KT_NUMBER, SD_KR_UNIT, NULL, ALL, 0, "", "0.6",
     "packing fraction assumed by fill_height"},
    {SD_SEC_POUR, "height", SD_KT_NUMBER, SD_KR_ANY, NULL, ALL, ALL, "m", "required",
     "z of the centres of each new sheet (inside the box)"},
    {SD_SEC_POUR, "layers_per_second", SD_KT_NUMBER, SD_KR_POS, NULL, ALL, 0, "1/s", "4",
     "feed rate: sheets per second ([Naderi 2024] Table 2: 4 or 8)"},
    {SD_SEC_POUR, "vertical_speed", SD_KT_NUMBER, SD_KR_NONNEG, NULL, ALL, 0, "m/s", "0.5",
     "each sphere starts with a vertical velocity uniform in [-v, v] (§4.1 of [Naderi 2024])"},
    {SD_SEC_POUR, "horizontal_speed", SD_KT_NUMBER, SD_KR_NONNEG, NULL, ALL, 0, "m/s", "0.1",
     "each sphere starts with horizontal velocities uniform in [-v, v] (§4.1 of [Naderi 2024])"},
    {SD_SEC_POUR, "start", SD_KT_NUMBER, SD_KR_NONNEG, NULL, ALL, 0, "s", "0",
     "time of the first sheet"},

    {SD_SEC_OUTLET, "min", SD_KT_VEC2, SD_KR_ANY, NULL, ALL, ALL, "m", "required",
     "[x, y] corner of the hole in the floor (the box wall's zmin face)"},
    {SD_SEC_OUTLET, "max", SD_KT_VEC2, SD_KR_ANY, NULL, ALL, ALL, "m", "required",
     "[x, y] opposite corner of the hole (max > min)"},
    {SD_SEC_OUTLET, "open_at", SD_KT_NUMBER, SD_KR_NONNEG, NULL, ALL, 0, "s", "0",
     "time the hole opens (fill and settle first, then discharge)"},
    {SD_SEC_INSERT, "name", SD_KT_STRING, SD_KR_NONEMPTY, NULL, ALL, 0, "", "insert0, insert1, ...",
     "name in summary.txt and messages"},
    {SD_SEC_INSERT, "region", SD_KT_ENUM, SD_KR_ANY, "box|cylinder|disc|mesh", ALL, ALL, "", "required",
     "where the particles go: every bounding sphere inside the region, but across the seam of a periodic axis "
     "that a box spans whole (disc: centres on the disc; mesh: "
     "inside a closed triangle mesh, by its winding number, clear of its triangles)"},
    {SD_SEC_INSERT, "min", SD_KT_VEC3, SD_KR_ANY, NULL, IBOX, IBOX, "m", "required", "box: lower corner"},
    {SD_SEC_INSERT, "max", SD_KT_VEC3, SD_KR_ANY, NULL, IBOX, IBOX, "m", "required",
     "box: upper corner, > min on every axis"},
    {SD_SEC_INSERT, "center", SD_KT_VEC3, SD_KR_ANY, NULL, ICYL | IDISC, ICYL | IDISC, "m", "required",
     "cylinder: the middle of its axis; disc: its centre"},
    {SD_SEC_INSERT, "axis", SD_KT_VEC3, SD_KR_ANY, NULL, ICYL | IDISC, 0, "", "[0, 0, 1]",
     "cylinder axis, disc normal (normalised)"},
    {SD_SEC_INSERT, "radius", SD_KT_NUMBER, SD_KR_POS, NULL, ICYL | IDISC, ICYL | IDISC, "m", "required",
     "radius of the cylinder or disc"},
    {SD_SEC_INSERT, "length", SD_KT_NUMBER, SD_KR_POS, NULL, ICYL, ICYL, "m", "required",
     "length of the cylinder along its axis"},
    {SD_SEC_INSERT, "file", SD_KT_STRING, SD_KR_NONEMPTY, NULL, IMESH, IMESH, "", "required",
     "mesh: STL or OBJ file of a closed surface (every edge in two triangles once coincident vertices "
     "are one), relative to the scene file; 3D only"},
    {SD_SEC_INSERT, "scale", SD_KT_NUMBER, SD_KR_POS, NULL, IMESH, 0, "m per file unit", "1",
     "mesh: length of one file unit, applied first"},
    {SD_SEC_INSERT, "position", SD_KT_VEC3, SD_KR_ANY, NULL, IMESH, 0, "m", "[0, 0, 0]",
     "mesh: translation applied after scale"},
    {SD_SEC_INSERT, "mix", SD_KT_LIST, SD_KR_ANY, NULL, ALL, ALL, "", "required",
     "what to insert: templates and sphere size laws with their fractions (insert[].mix[])"},
    {SD_SEC_INSERT, "mix_by", SD_KT_ENUM, SD_KR_ANY, "number|mass", ALL, 0, "", "number",
     "whether the mix fractions count particles or mass"},
    {SD_SEC_INSERT, "count", SD_KT_INT, SD_KR_ONE, NULL, ALL, 0, "", "-",
     "particles to insert in all; give count or mass"},
    {SD_SEC_INSERT, "mass", SD_KT_NUMBER, SD_KR_POS, NULL, ALL, 0, "kg", "-", "mass to insert in all"},
    {SD_SEC_INSERT, "rate", SD_KT_NUMBER, SD_KR_POS, NULL, ALL, 0, "1/s", "all at once",
     "particles per second from start; without rate and mass_rate all go in at start"},
    {SD_SEC_INSERT, "mass_rate", SD_KT_NUMBER, SD_KR_POS, NULL, ALL, 0, "kg/s", "-",
     "mass per second from start (instead of rate)"},
    {SD_SEC_INSERT, "start", SD_KT_NUMBER, SD_KR_NONNEG, NULL, ALL, 0, "s", "0", "time of the first particle"},
    {SD_SEC_INSERT, "velocity", SD_KT_VEC3, SD_KR_ANY, NULL, ALL, 0, "m/s", "[0, 0, 0]", "initial velocity"},
    {SD_SEC_INSERT, "velocity_jitter", SD_KT_NUMBER, SD_KR_NONNEG, NULL, ALL, 0, "m/s", "0",
     "uniform random velocity in [-j, j] added to each component"},
    {SD_SEC_INSERT, "orientation", SD_KT_ENUM, SD_KR_ANY, "random|identity", ALL, 0, "", "random",
     "orientation of shaped bodies: uniform over all rotations (about z in 2D), or the template's"},
    {SD_SEC_INSERT, "attempts", SD_KT_INT, SD_KR_ONE, NULL, ALL, 0, "", "100",
     "positions tried per particle (at most 100000) before it waits for the next insertion time (or, "
     "all at once, is given up; after 1000 given up in a row the rest are not tried: the region is "
     "full; [Rakotonirina 2019] §4.1); a position must hold the particle's bounding sphere inside the "
     "plane, box and drum walls, clear of the mesh walls' facets and inside a closed mesh container"},

    {SD_SEC_INSERT_MIX, "material", SD_KT_STRING, SD_KR_NONEMPTY, NULL, ALL, ALL, "", "required",
     "material name"},
    {SD_SEC_INSERT_MIX, "shape", SD_KT_STRING, SD_KR_NONEMPTY, NULL, ALL, 0, "", "a sphere",
     "name of a shape in shapes: bodies of that template (any kind); without it, spheres"},
    {SD_SEC_INSERT_MIX, "fraction", SD_KT_NUMBER, SD_KR_NONNEG, NULL, ALL, 0, "", "1",
     "share of the mix (by number or mass, mix_by); the fractions sum to 1"},
    {SD_SEC_INSERT_MIX, "radius", SD_KT_NUM_OR_RANGE, SD_KR_ANY, NULL, ALL, 0, "m", "-",
     "spheres: a radius, or {min, max} uniform; for normal and lognormal the truncation {min, max}; "
     "with shape: the template's equivalent radius (of the sphere of equal volume, 2D the circle of "
     "equal area), the template scaled to it; without radius and distribution a template keeps its size"},
    {SD_SEC_INSERT_MIX, "distribution", SD_KT_ENUM, SD_KR_ANY, "fixed|uniform|normal|lognormal|table", ALL, 0,
     "", "from radius", "the radius law of the spheres, or of a template's equivalent radius"},
    {SD_SEC_INSERT_MIX, "size_classes", SD_KT_INT, SD_KR_ONE, NULL, ALL, 0, "", "16",
     "a template with a size law: the law is cut into this many classes (at most 32), one scaled copy of "
     "the template each, named TEMPLATE_iIeEsK: continuous laws in classes of equal probability, a table's "
     "classes each cut into size_classes / classes of equal width; a class's copy has the radius of the "
     "class's mean volume, so the mix by mass is the law's (docs/physics.md)"},
    {SD_SEC_INSERT_MIX, "mean", SD_KT_NUMBER, SD_KR_ANY, NULL, ALL, 0, "m", "-", "normal: mean radius"},
    {SD_SEC_INSERT_MIX, "std", SD_KT_NUMBER, SD_KR_NONNEG, NULL, ALL, 0, "m", "-",
     "normal: standard deviation of the radius; mean + 8 std (or the truncation max) at most 10^4 "
     "times the mean"},
    {SD_SEC_INSERT_MIX, "median", SD_KT_NUMBER, SD_KR_ANY, NULL, ALL, 0, "m", "-", "lognormal: median radius"},
    {SD_SEC_INSERT_MIX, "sigma", SD_KT_NUMBER, SD_KR_NONNEG, NULL, ALL, 0, "", "-",
     "lognormal: standard deviation of ln r; median e^(8 sigma) (or the truncation max) at most 10^4 "
     "times the median (sigma <= 1.15 untruncated)"},
    {SD_SEC_INSERT_MIX, "classes", SD_KT_VEC3_LIST, SD_KR_ANY, NULL, ALL, 0, "m, m, -", "-",
     "table: sieve classes [r_lo, r_hi, fraction], the radius uniform within a class; fractions sum to 1"},
    {SD_SEC_INSERT_MIX, "classes_by", SD_KT_ENUM, SD_KR_ANY, "number|mass", ALL, 0, "", "number",
     "table: whether the class fractions count particles or mass"},

    {SD_SEC_OUTLETS, "name", SD_KT_STRING, SD_KR_NONEMPTY, NULL, ALL, 0, "", "outlet0, outlet1, ...",
     "name in outlet.csv and messages"},
    {SD_SEC_OUTLETS, "region", SD_KT_ENUM, SD_KR_ANY, "box|cylinder", ALL, ALL, "", "required",
     "particles whose centre enters the region are removed and counted"},
    {SD_SEC_OUTLETS, "min", SD_KT_VEC3, SD_KR_ANY, NULL, IBOX, IBOX, "m", "required", "box: lower corner"},
    {SD_SEC_OUTLETS, "max", SD_KT_VEC3, SD_KR_ANY, NULL, IBOX, IBOX, "m", "required", "box: upper corner"},
    {SD_SEC_OUTLETS, "center", SD_KT_VEC3, SD_KR_ANY, NULL, ICYL, ICYL, "m", "required",
     "cylinder: the middle of its axis"},
    {SD_SEC_OUTLETS, "axis", SD_KT_VEC3, SD_KR_ANY, NULL, ICYL, 0, "", "[0, 0, 1]", "cylinder axis"},
    {SD_SEC_OUTLETS, "radius", SD_KT_NUMBER, SD_KR_POS, NULL, ICYL, ICYL, "m", "required", "cylinder radius"},
    {SD_SEC_OUTLETS, "length", SD_KT_NUMBER, SD_KR_POS, NULL, ICYL, ICYL, "m", "required", "cylinder length"},
    {SD_SEC_OUTLETS, "open_at", SD_KT_NUMBER, SD_KR_NONNEG, NULL, ALL, 0, "s", "0", "time the outlet opens"},
    {SD_SEC_OUTLETS, "check_every", SD_KT_INT, SD_KR_ONE, NULL, ALL, 0, "", "1",
     "steps between removals (a particle may pass a thin region between checks)"},

    /* analysis: - ... (io/scene_analysis.c, docs/analysis.md); the kinds are the types */
    {SD_SEC_ANALYSIS, "type", SD_KT_ENUM, SD_KR_ANY, SD_AN_TYPE_CHOICES, ALL, ALL, "", "required",
     "what to measure (docs/analysis.md): porosity, radial_porosity, coordination, velocity_field, "
     "speed_pdf, energy, bed_height, surface_angle (a drum), repose_angle (a heap)"},
    {SD_SEC_ANALYSIS, "name", SD_KT_STRING, SD_KR_NONEMPTY, NULL, ALL, 0, "", "the type",
     "name in messages and of the default file (a second entry of a type: TYPE_1, ...)"},
    {SD_SEC_ANALYSIS, "file", SD_KT_STRING, SD_KR_NONEMPTY, NULL, ALL, 0, "", "NAME.csv",
     "the CSV file, a plain name in the output directory"},
    {SD_SEC_ANALYSIS, "every", SD_KT_INT, SD_KR_ONE, NULL, ALL, 0, "", "output.stats_every",
     "steps between rows (a row is also written at step 0 and at the last step)"},
    {SD_SEC_ANALYSIS, "interval", SD_KT_NUMBER, SD_KR_POS, NULL, ALL, 0, "s", "-",
     "simulated time between rows instead of every (rounded to whole steps)"},
    {SD_SEC_ANALYSIS, "region", SD_KT_ENUM, SD_KR_ANY, "box|cylinder", AN_REGION, AN_NEEDS_REGION, "", "all particles",
     "where: the voxels of porosity, the annuli of radial_porosity (cylinder), the slab of velocity_field "
     "(box), the drum of surface_angle (cylinder); coordination, speed_pdf, energy, bed_height: the particles "
     "whose centre lies in it; not for repose_angle"},
    {SD_SEC_ANALYSIS, "min", SD_KT_VEC3, SD_KR_ANY, NULL, AN_BOX, 0, "m", "-", "box region: lower corner"},
    {SD_SEC_ANALYSIS, "max", SD_KT_VEC3, SD_KR_ANY, NULL, AN_BOX, 0, "m", "-",
     "box region: upper corner, > min on every axis (2D: x and y)"},
    {SD_SEC_ANALYSIS, "center", SD_KT_VEC3, SD_KR_ANY, NULL, AN_CYL, 0, "m", "-",
     "cylinder region: the middle of its axis; repose_angle: a point of the heap's vertical axis (default: "
     "the particles' centre of mass)"},
    {SD_SEC_ANALYSIS, "axis", SD_KT_VEC3, SD_KR_ANY, NULL, AN_CYL, 0, "", "[0, 0, 1]",
     "cylinder region: its axis (normalised; 2D: z, the region is a disc of the plane)"},
    {SD_SEC_ANALYSIS, "radius", SD_KT_NUMBER, SD_KR_POS, NULL, AN_CYL, 0, "m", "-", "cylinder region: radius"},
    {SD_SEC_ANALYSIS, "length", SD_KT_NUMBER, SD_KR_POS, NULL, AN_CYL, 0, "m", "- (required in 3D)",
     "cylinder region: length along the axis"},
    {SD_SEC_ANALYSIS, "voxel", SD_KT_NUMBER, SD_KR_POS, NULL, AN_VOX, AN_VOX, "m", "required",
     "voxel edge (2D: pixel); the fraction converges as it shrinks: a tenth of the smallest particle size "
     "gives about 1 % (docs/analysis.md)"},
    {SD_SEC_ANALYSIS, "bins", SD_KT_INT, SD_KR_ONE, NULL, AN_BINS, 0, "", "10 radial, else 20",
     "annuli of radial_porosity, speed classes of speed_pdf, surface columns of surface_angle and "
     "repose_angle (at least 2 there); at most 10000 (a row per bin at every output)"},
    {SD_SEC_ANALYSIS, "cells", SD_KT_VEC2, SD_KR_ONE, NULL, AN(SD_AN_VELOCITY_FIELD), 0, "", "[10, 10]",
     "velocity_field: cells along the plane's two axes (integers)"},
    {SD_SEC_ANALYSIS, "plane", SD_KT_ENUM, SD_KR_ANY, "xy|xz|yz", AN(SD_AN_VELOCITY_FIELD), 0, "", "xz (2D: xy)",
     "velocity_field: the plane of the grid; the box's third axis is the slab's thickness"},
    {SD_SEC_ANALYSIS, "max_speed", SD_KT_NUMBER, SD_KR_POS, NULL, AN(SD_AN_SPEED_PDF), 0, "m/s",
     "the fastest particle", "speed_pdf: top of the last class (faster particles count in it)"},
    {SD_SEC_ANALYSIS, "fraction", SD_KT_NUMBER, SD_KR_UNIT, NULL, AN(SD_AN_BED_HEIGHT), 0, "", "0.95",
     "bed_height: the mass fraction below fraction_height"},
    {SD_SEC_ANALYSIS, "fit", SD_KT_VEC2, SD_KR_NONNEG, NULL, AN(SD_AN_SURFACE_ANGLE) | AN(SD_AN_REPOSE_ANGLE), 0, "",
     "[0.2, 0.8]",
     "the columns fitted: fractions of the drum's diameter (surface_angle) or of the heap's radius "
     "(repose_angle)"},

    {SD_SEC_STOP, "kinetic_energy_below", SD_KT_NUMBER, SD_KR_POS, NULL, ALL, 0, "J", "-",
     "the run stops at the first stats row (every output.stats_every steps) whose kinetic energy, "
     "translational and rotational of all particles, is below this, once after has passed and every "
     "insertion is done; that row, a frame and the analyses' rows are written, and summary.txt says so. "
     "Give this or mean_speed_below"},
    {SD_SEC_STOP, "mean_speed_below", SD_KT_NUMBER, SD_KR_POS, NULL, ALL, 0, "m/s", "-",
     "as kinetic_energy_below, on the mean speed of the particles' centres: a sum of energies is held "
     "up by its fastest few (one rattler on a bed at rest), a mean speed much less"},
    {SD_SEC_STOP, "after", SD_KT_NUMBER, SD_KR_NONNEG, NULL, ALL, 0, "s", "0",
     "simulated time before which the condition is not checked (the particles are still falling); "
     "must be before the run's end"},
};

const size_t sd_scene_key_count = sizeof sd_scene_keys / sizeof sd_scene_keys[0];

const char sd_scene_example[] =
    "# Spheres settling in an open-top box.\n"
    "simulation:\n"
    "  dt: 2.0e-6\n"
    "  duration: 0.01\n"
    "  gravity: [0, 0, -9.81]\n"
    "  seed: 7\n"
    "  contact_law: hertz_mindlin\n"
    "materials:\n"
    "  - name: glass\n"
    "    density: 2500\n"
    "    youngs_modulus: 1.0e7\n"
    "    poisson_ratio: 0.3\n"
    "    restitution: 0.5\n"
    "    friction: 0.5\n"
    "  - name: steel\n"
    "    density: 7800\n"
    "    youngs_modulus: 2.0e8\n"
    "interactions:\n"
    "  - between: [glass, steel]\n"
    "    friction: 0.3\n"
    "particles:\n"
    "  - generator: lattice\n"
    "    material: glass\n"
    "    radius: {min: 0.0009, max: 0.0011}\n"
    "    origin: [0.002, 0.002, 0.002]\n"
    "    spacing: 0.0025\n"
    "    count: [4, 4, 4]\n"
    "    velocity_jitter: 0.01\n"
    "  - generator: list\n"
    "    material: glass\n"
    "    spheres:\n"
    "      - {position: [0.005, 0.005, 0.02], radius: 0.001, velocity: [0, 0, -0.5]}\n"
    "walls:\n"
    "  - name: container\n"
    "    type: box\n"
    "    min: [0, 0, 0]\n"
    "    max: [0.012, 0.012, 0.05]\n"
    "    open: [zmax]\n"
    "    material: steel\n"
    "output:\n"
    "  directory: out/example\n"
    "  every: 500\n"
    "  formats: [vtk, csv]\n";

static const char *const sd_section_names[SD_SEC_COUNT] = {
    "(top level)", "simulation", "materials[]", "interactions[]", "shapes[]", "particles[]",
    "particles[].spheres[]", "walls[]", "output", "pour", "outlet", "shapes[].elements[]",
    "insert[]", "insert[].mix[]", "outlets[]", "walls[].motion", "analysis[]",
    "simulation.stop_when",
};

const char *sd_scene_section_name(sd_scene_section sec)
{
    return (unsigned)sec < SD_SEC_COUNT ? sd_section_names[sec] : "?";
}

const char *sd_scene_section_kinds(sd_scene_section sec)
{
    /* The bit order matches sd_gen_kind, the wall kinds (0 plane, 1 box,
     * 2 mesh, 3 drum) and SD_MESH_FIXED .. SD_MESH_TABLE. */
    if (sec == SD_SEC_PARTICLES)
        return "lattice|random|list|csv";
    if (sec == SD_SEC_WALL)
        return "plane|box|mesh|drum";
    if (sec == SD_SEC_MESH_MOTION)
        return "fixed|translate|rotate|table";
    if (sec == SD_SEC_INSERT)
        return "box|cylinder|disc|mesh";
    if (sec == SD_SEC_OUTLETS)
        return "box|cylinder";
    if (sec == SD_SEC_ANALYSIS) /* the type choices, in SD_ANALYSIS_TYPES order */
        return SD_AN_TYPE_CHOICES;
    if (sec == SD_SEC_SHAPE)
        return SD_SHAPE_CHOICES;
    return NULL;
}

const sd_scene_key *sd_scene_key_find(sd_scene_section sec, const char *key)
{
    for (size_t i = 0; i < sd_scene_key_count; ++i)
        if (sd_scene_keys[i].section == sec && strcmp(sd_scene_keys[i].key, key) == 0)
            return &sd_scene_keys[i];
    return NULL;
}

const char *sd_scene_range_text(sd_scene_range r)
{
    switch (r) {
    case SD_KR_POS: return "> 0";
    case SD_KR_NONNEG: return ">= 0";
    case SD_KR_UNIT: return "in (0, 1]";
    case SD_KR_POISSON: return "in (-1, 0.5)";
    case SD_KR_ONE: return ">= 1";
    case SD_KR_NONEMPTY: return "non-empty";
    case SD_KR_ANY: break;
    }
    return "";
}

int sd_scene_range_ok(sd_scene_range r, double v)
{
    switch (r) {
    case SD_KR_POS: return v > 0.0;
    case SD_KR_NONNEG: return v >= 0.0;
    case SD_KR_UNIT: return v > 0.0 && v <= 1.0;
    case SD_KR_POISSON: return v > -1.0 && v < 0.5;
    case SD_KR_ONE: return v >= 1.0;
    case SD_KR_NONEMPTY:
    case SD_KR_ANY: break;
    }
    return 1;
}

/* "a|b|c|" -> "a, b, c" */
static void sd_choices_text(const char *choices, char *buf, size_t size)
{
    size_t used = 0;
    buf[0] = '\0';
    for (const char *p = choices; *p && used + 1 < size;) {
        size_t n = strcspn(p, "|");
        if (n > 0) {
            int w = snprintf(buf + used, size - used, "%s%.*s", used ? ", " : "", (int)n, p);
            used += w > 0 ? (size_t)w : 0;
        }
        p += n;
        if (*p == '|')
            ++p;
    }
}

const char *sd_scene_type_text(const sd_scene_key *k, char *buf, size_t size)
{
    const char *r = sd_scene_range_text(k->range);
    const char *sp = r[0] ? " " : "";
    char ch[160];
    switch (k->type) {
    case SD_KT_MAP: snprintf(buf, size, "mapping"); break;
    case SD_KT_LIST: snprintf(buf, size, "list of mappings"); break;
    case SD_KT_NUMBER: snprintf(buf, size, "number%s%s", sp, r); break;
    case SD_KT_INT: snprintf(buf, size, "integer%s%s", sp, r); break;
    case SD_KT_STRING: snprintf(buf, size, "%sstring", k->range == SD_KR_NONEMPTY ? "non-empty " : ""); break;
    case SD_KT_ENUM:
        sd_choices_text(k->choices, ch, sizeof ch);
        snprintf(buf, size, "one of: %s", ch);
        break;
    case SD_KT_ENUM_LIST:
        sd_choices_text(k->choices, ch, sizeof ch);
        snprintf(buf, size, "list of: %s", ch);
        break;
    case SD_KT_VEC3: snprintf(buf, size, "[x, y, z]%s%s", sp, r); break;
    case SD_KT_INT3: snprintf(buf, size, "[nx, ny, nz] integers%s%s", sp, r); break;
    case SD_KT_ENUM_OR_INT3:
        sd_choices_text(k->choices, ch, sizeof ch);
        snprintf(buf, size, "one of: %s, or [nx, ny, nz] integers%s%s", ch, sp, r);
        break;
    case SD_KT_NUM_OR_VEC3: snprintf(buf, size, "number or [x, y, z]%s%s", sp, r); break;
    case SD_KT_NUM_OR_RANGE: snprintf(buf, size, "number or {min, max}%s%s", sp, r); break;
    case SD_KT_BOX: snprintf(buf, size, "{min: [x, y, z], max: [x, y, z]}"); break;
    case SD_KT_NAME_PAIR: snprintf(buf, size, "[name, name]"); break;
    case SD_KT_ORIENTATION: snprintf(buf, size, "identity, random or [w, x, y, z]"); break;
    case SD_KT_VEC3_LIST: snprintf(buf, size, "list of [x, y, z]"); break;
    case SD_KT_VEC2: snprintf(buf, size, "[x, y]%s%s", sp, r); break;
    case SD_KT_VEC2_LIST: snprintf(buf, size, "list of [x, y]"); break;
    case SD_KT_NUM_LIST: snprintf(buf, size, "list of numbers"); break;
    }
    return buf;
}

/* Kinds in mask as "lattice, random", or "" when the key applies to all. */
static void sd_kinds_text(sd_scene_section sec, unsigned mask, char *buf, size_t size)
{
    const char *kinds = sd_scene_section_kinds(sec);
    buf[0] = '\0';
    if (!kinds || mask == SD_KIND_ALL)
        return;
    size_t used = 0;
    unsigned bit = 0;
    for (const char *p = kinds; *p; ++bit) {
        size_t n = strcspn(p, "|");
        if (mask & (1u << bit)) {
            int w = snprintf(buf + used, size - used, "%s%.*s", used ? ", " : "", (int)n, p);
            used += w > 0 && (size_t)w < size - used ? (size_t)w : 0;
        }
        p += n;
        if (*p == '|')
            ++p;
    }
}

/* Section column: "particles[] (lattice)" when the key applies to some kinds. */
static void sd_section_text(const sd_scene_key *k, char *buf, size_t size)
{
    char kinds[64];
    sd_kinds_text(k->section, k->kinds, kinds, sizeof kinds);
    if (kinds[0])
        snprintf(buf, size, "%s (%s)", sd_scene_section_name(k->section), kinds);
    else
        snprintf(buf, size, "%s", sd_scene_section_name(k->section));
}

/* Default column: "required", "required (lattice, random)", or the default. */
static void sd_default_text(const sd_scene_key *k, char *buf, size_t size)
{
    char kinds[64];
    if (k->required == 0) {
        snprintf(buf, size, "%s", k->def);
        return;
    }
    sd_kinds_text(k->section, k->required == k->kinds ? SD_KIND_ALL : k->required, kinds,
                  sizeof kinds);
    if (kinds[0])
        snprintf(buf, size, "required (%s)", kinds);
    else
        snprintf(buf, size, "required");
}

/* Rules the table cannot say, printed under it in both formats. */
static const char *const sd_scene_rules[] = {
    "Numbers may be written as YAML integers or floats (2500, 1e7, 1.0e-5); keys are "
    "case-sensitive; a key not listed here is an error.",
    "A scene is one YAML document in UTF-8 (a second document, or text after '...', is an "
    "error), at most 64 MiB, with lists and mappings nested at most 64 deep; it may make at most "
    "1e9 particles, and no more than the memory of the machine holds (checked before anything "
    "is built).",
    "simulation: give exactly one of steps and duration; with duration, steps = "
    "ceil(duration / dt).",
    "simulation.dt above 1/5 of the shortest contact duration is rejected (time step above "
    "the stability limit); `shapedem check` prints the recommended step.",
    "Material, interaction and particle values are checked when the scene loads; errors name "
    "the file, the line and the key (e.g. materials[1].density).",
    "particles: one generator per entry, each with its own keys (the section says which). "
    "lattice: count[0] x count[1] x count[2] spheres at origin + (i, j, k) * spacing. "
    "random: random sequential addition inside box, deterministic from simulation.seed; it "
    "fails with an error when the box is too full. list: spheres given one by one. csv: one "
    "particle per row of a CSV file with a header line naming the columns x, y, z, radius or "
    "shape, and optionally vx, vy, vz, qw, qx, qy, qz, wx, wy, wz, material (comma-separated; "
    "blank lines and lines starting with # are skipped).",
    "Particles may not overlap at the start by more than 1 % of the smaller size (a sphere's "
    "radius, half a shape's smallest outer dimension), measured with the true shapes, so a "
    "packing written from a settled run (positions and orientations) loads again; and they "
    "must start inside every wall: with the centre on the side a plane's normal points to, and "
    "inside each closed face of a box (by the true shape, again within 1 % of its size).",
    "Random choices (radii in {min, max}, velocity_jitter, the random generator, random "
    "orientations) come from simulation.seed: the same scene gives the same particles.",
    "shapes: each entry is a template (a convex core swept by a sphere), moved to its principal "
    "frame (centre of mass at the origin, principal axes along x, y, z); a body's mass is the "
    "material's density x the shape's volume. sphere needs radius; box needs size; cylinder "
    "needs size, or diameter and length; cone needs size, or diameter and height; ellipsoid "
    "needs semi_axes; polyhedron needs vertices, file (a convex OBJ or STL mesh) or preset (a "
    "built-in polyhedron with size or edge; prism and cylinder also sides; random also faces or "
    "vertex_count), at least 4 points, not coplanar.",
    "A generator makes spheres (radius) or bodies of one shape (shape: NAME), never both; list "
    "entries each give radius or shape (or take the generator's shape). Shaped bodies are "
    "placed and spaced by their bounding sphere (the smallest sphere about the centre of mass "
    "holding the shape), so generated bodies never start in contact; "
    "orientation random (the default) draws uniform rotations (Shoemake) from the generator's "
    "stream. Spheres and shaped bodies may be mixed in one scene.",
    "pour and outlet need simulation.solver: grid and a box wall (the grid's domain). pour "
    "lays a sheet of spheres every 1/layers_per_second s at height, one per two cells along x "
    "and y (2 radii apart), skipping spots that are taken, until count spheres are poured "
    "(§4.1 of [Naderi 2024]); with fill_height, count = packing_fraction x floor area x fill_height / "
    "sphere volume. particles may then be omitted. outlet opens a hole in the box's floor at "
    "open_at; spheres falling through are removed and counted (stats.csv and summary.txt: "
    "poured, in_domain, discharged, discharged_mass; spheres leaving elsewhere, e.g. an open top, "
    "apart as escaped, escaped_mass; removed, conflicts).",
    "simulation.dimension: 2 is the planar mode (after [Huang 2021]): every position, velocity, gravity "
    "and plane normal has z = 0 (generators place particles at z = 0 and ignore the z range of "
    "their box), rotations are about z (random orientations draw a uniform angle), masses are "
    "per unit thickness (m = density x area x 1 m) and shapes are the planar types circle "
    "(radius), ellipse (axes), polygon (points), polybezier (points) and fourier (fourier_a, "
    "fourier_b), each optionally rounded; spheres (radius) are circles. Box walls keep their x "
    "and y faces (their z range must contain 0). A plane with servo_stress needs two opposite planes across it (their "
    "distance is its contact length); four planes with normals +x, -x, +y, -y make the run "
    "write biaxial.csv (docs/output.md).",
};

/* Plain-text help is read in a terminal, so it is wrapped at print time to
 * SD_HELP_WIDTH columns: the key table's cells wrap inside their columns and
 * a key's meaning goes on the lines under it. The table strings themselves
 * stay one sentence each, as the markdown table needs them. */
#define SD_HELP_WIDTH 100

/* The next line of *p at most width columns: breaks after the last space
 * that fits (a word longer than width is cut). Sets *len to the line's
 * length and advances *p past it and the spaces after it. */
static const char *sd_wrap_next(const char **p, size_t width, size_t *len)
{
    const char *s = *p;
    while (*s == ' ')
        ++s;
    size_t n = strlen(s);
    if (n > width) {
        n = width;
        while (n > 0 && s[n] != ' ')
            --n;
        if (n == 0)
            n = width;
    }
    *len = n;
    *p = s + n;
    while (**p == ' ')
        ++*p;
    return s;
}

/* text wrapped to SD_HELP_WIDTH columns, each line indented by indent
 * spaces; the first line starts with first instead (a list bullet). */
static void sd_print_wrapped(FILE *f, const char *text, int indent, const char *first)
{
    for (int line = 0; *text; ++line) {
        size_t n;
        const char *s = sd_wrap_next(&text, (size_t)(SD_HELP_WIDTH - indent), &n);
        fprintf(f, "%-*s%.*s\n", indent, line == 0 && first ? first : "", (int)n, s);
    }
}

/* One table row of at most four cells, indented by two spaces: each cell
 * wrapped inside its column, the columns side by side, no trailing spaces. */
static void sd_print_row(FILE *f, const char *const *cells, const int *widths, size_t ncols)
{
    const char *rest[4];
    if (ncols > 4)
        ncols = 4;
    for (size_t c = 0; c < ncols; ++c)
        rest[c] = cells[c];
    for (int more = 1; more;) {
        char line[SD_HELP_WIDTH * 2];
        size_t used = 2, end = 0;
        memset(line, ' ', used);
        more = 0;
        for (size_t c = 0; c < ncols; ++c) {
            size_t n;
            const char *s = sd_wrap_next(&rest[c], (size_t)widths[c], &n);
            int w = snprintf(line + used, sizeof line - used, "%.*s%*s", (int)n, s,
                             c + 1 < ncols ? widths[c] - (int)n + 1 : 0, "");
            used += w > 0 && (size_t)w < sizeof line - used ? (size_t)w : 0;
            if (n > 0)
                end = used;
            more |= *rest[c] != '\0';
        }
        while (end > 0 && line[end - 1] == ' ')
            --end;
        fprintf(f, "%.*s\n", (int)end, line);
    }
}

/* A markdown table cell: '|' would end the cell, so it is escaped. */
static void sd_md_cell(FILE *f, const char *text)
{
    for (; *text; ++text) {
        if (*text == '|')
            fputc('\\', f);
        fputc(*text, f);
    }
}

void sd_scene_print_keys(FILE *f, int markdown)
{
    char sec[128], type[192], def[128];
    size_t nrules = sizeof sd_scene_rules / sizeof sd_scene_rules[0];
    if (!f)
        return;
    if (markdown) {
        fprintf(f, "# Scene file format\n\n");
        fprintf(f, "<!-- Generated by `shapedem help scene --markdown` from src/io/scene_keys.c; "
                   "do not edit. -->\n\n");
        fprintf(f, "A scene is a YAML file that describes one simulation: materials, particles, "
                   "walls and output. Run it with `shapedem run SCENE`; check it without running "
                   "with `shapedem check SCENE`. Units are SI. Papers are cited by short name, "
                   "e.g. [Naderi 2024]; [references.md](references.md) gives the full "
                   "references.\n\n");
        fprintf(f, "## Example\n\n```yaml\n%s```\n\n", sd_scene_example);
        fprintf(f, "## Keys\n\n");
        fprintf(f, "| section | key | type | unit | default | meaning |\n");
        fprintf(f, "| --- | --- | --- | --- | --- | --- |\n");
        for (size_t i = 0; i < sd_scene_key_count; ++i) {
            const sd_scene_key *k = &sd_scene_keys[i];
            sd_section_text(k, sec, sizeof sec);
            sd_scene_type_text(k, type, sizeof type);
            sd_default_text(k, def, sizeof def);
            fprintf(f, "| %s | `%s` | %s | %s | %s | ", sec, k->key, type, k->unit, def);
            sd_md_cell(f, k->doc);
            fputs(" |\n", f);
        }
        fprintf(f, "\n## Rules\n\n");
        for (size_t i = 0; i < nrules; ++i)
            fprintf(f, "- %s\n", sd_scene_rules[i]);
        return;
    }
    /* Grouped by section; under each, one row per key and its meaning
     * indented below (the widths fit the longest key, unit and default). */
    static const int widths[4] = {28, 40, 8, 22};
    const char *head[4] = {"key", "type", "unit", "default"};
    char prev[sizeof sec] = "";
    fprintf(f, "Scene file keys (YAML; SI units). Each section lists its keys: type, unit and "
               "default,\nthen the meaning on the lines below. Papers are cited by short name, "
               "e.g. [Naderi 2024];\ndocs/references.md gives the full references.\n\n");
    fprintf(f, "section\n");
    sd_print_row(f, head, widths, 4);
    fprintf(f, "      meaning\n");
    for (size_t i = 0; i < sd_scene_key_count; ++i) {
        const sd_scene_key *k = &sd_scene_keys[i];
        sd_section_text(k, sec, sizeof sec);
        sd_scene_type_text(k, type, sizeof type);
        sd_default_text(k, def, sizeof def);
        if (strcmp(sec, prev) != 0) {
            fprintf(f, "\n%s\n", sec);
            snprintf(prev, sizeof prev, "%s", sec);
        }
        const char *cells[4] = {k->key, type, k->unit, def};
        sd_print_row(f, cells, widths, 4);
        sd_print_wrapped(f, k->doc, 6, NULL);
    }
    fprintf(f, "\nRules:\n");
    for (size_t i = 0; i < nrules; ++i)
        sd_print_wrapped(f, sd_scene_rules[i], 4, "  - ");
}
