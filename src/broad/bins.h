/* bins.h — the broad phase as a service under the world: uniform cell bins
 * with a Verlet skin, taking plain arrays of owned and ghost particles and
 * the walls, returning the particle order and the pair lists.
 *
 * The broad phase never sees sd_world (architecture review §9.2, seam 5):
 * the world fills an sd_bins_input, applies the permutation that
 * sd_bins_sort returns to its particle arrays, adds its ghosts, and calls
 * sd_bins_build. Ghosts are particles n_owned .. n_total - 1 in the same
 * arrays, copies of owned particles with a shift (periodic images now, MPI
 * neighbours later); ghost_owner[g - n_owned] is the storage index of the
 * owned original.
 *
 * Invariants: pairs of two ghosts are never made (but one, in a decomposed
 * run: another rank's particle as it is, with the lower id, and a local
 * image; see SD_GHOST_REMOTE); a pair of an owned
 * particle i and a ghost of owned k is kept only when the stable id of i is
 * below that of k (the same contact seen from k, through the image of i, is
 * dropped), so each contact is evaluated once; ghosts get no wall pairs;
 * gather lists cover owned particles only, and a ghost's side of a pair is
 * gathered by its owner. With no ghosts the lists are those of the plain
 * half-stencil search, bit for bit.
 *
 * Composites (seed 004 §2.5, two levels of bounding spheres): a candidate
 * pair with a composite on one side at least, found by the particles'
 * bounding spheres, is expanded into its element pairs whose element
 * bounding spheres are within the skin (a non-composite side is one
 * element, itself), all of kind ELEMENTS and next to each other in the
 * list, elements of i outer, of j inner; their keys carry the element
 * sub-indices. Wall pairs of a composite are expanded the same way, one
 * per element near the feature. The skin test bounds the motion of every
 * surface point, so of every element centre, by half the skin.
 */
#ifndef SD_BROAD_BINS_H
#define SD_BROAD_BINS_H

#include "broad/pairs.h"
#include "dynamics/meshwall.h"
#include "dynamics/walls.h"
#include "shape/shape.h"

/* What a particle is, for the kind of its pairs (contact/kinds.h). */
#define SD_PARTICLE_CLASSES(X)                                           \
    X(SPHERE, "a plain sphere (a disc in the planar mode)")               \
    X(SHAPE, "a 3D shape template (convex narrow phase)")                 \
    X(SHARP_POLY, "a sharp convex polyhedron (a volume law may apply)")   \
    X(SHAPE2D, "a 2D shape template (planar mode)")                        \
    X(COMPOSITE, "a composite of convex elements (seed 004): element pairs")

enum sd_particle_class {
#define SD_X_CLASS(NAME, doc) SD_CLASS_##NAME,
    SD_PARTICLE_CLASSES(SD_X_CLASS)
#undef SD_X_CLASS
    SD_CLASS_COUNT
};

typedef struct sd_bins_input {
    size_t n_owned, n_total;       /* particles; ghosts are n_owned .. n_total - 1 */
    const sd_vec3 *x;              /* m, centres */
    const sd_real *radius;         /* m, bounding radii */
    const uint64_t *id;            /* stable ids; a ghost carries its owner's */
    const int32_t *shape;          /* template index, -1 for a plain sphere */
    const uint8_t *shape_class;    /* per template: enum sd_particle_class */
    /* composites (SD_CLASS_COMPOSITE, seed 004 §2.5): the templates, the
     * element pool and the orientations, for the element bounding spheres
     * of the second level of the search (NULL without composites) */
    const sd_shape *shapes;
    const sd_element *elements;
    const sd_quat *q;
    const int32_t *material;
    const uint32_t *ghost_owner;   /* n_total - n_owned entries */
    size_t material_count;
    const uint8_t *volume_law;     /* material_count^2: 1 when the pair (a, b) has a volume law */
    size_t wall_count;
    const sd_wall_geom *walls;     /* the walls as they are at this rebuild */
    const int32_t *wall_material;
    const sd_mesh_view *meshes;    /* mesh walls' facets and bins (sd_wall_geom.mesh indexes them) */
    size_t mesh_count;
    sd_real skin;                  /* m */
    /* no domain: the world wraps positions into its periodic box and makes
     * the images (world/rebuild.c), so the bins need only the ghosts they
     * are given, and an MPI rank's ghosts will come the same way */
    int threads, parallel;         /* the threading policy, decided by the world */
} sd_bins_input;

typedef struct sd_bins {
    sd_vec3 lo;            /* m, lower corner */
    sd_real h;             /* m, cell edge */
    int nx, ny, nz;
    size_t ncell, cell_cap;
    size_t sorted_n;       /* particles binned by the last sort (its cells stand if no ghosts came) */
    uint32_t *cell_start;  /* ncell + 1 entries */
    uint32_t *cell;        /* per particle, its cell */
    uint32_t *perm;        /* per owned particle, the order of the last sort */
    uint32_t *item;        /* with ghosts: particles in cell order (NULL order: storage order) */
    uint32_t *pos;         /* with ghosts: position of each particle in item */
    uint32_t *count;       /* per particle and kind, scratch counts */
    uint8_t *slot_kind;    /* per particle, the kinds of its first candidates */
    void *scratch;         /* per particle: the first candidates (also lent to the world as
                              the permutation scratch, 32 bytes per particle) */
    size_t pcap;
    int use_items;
} sd_bins;

/* The ghost_owner of a ghost whose owner lives on another rank (src/mpi/):
 * its pairs with owned particles are all kept (the other rank evaluates the
 * same pair for its own side, none is dropped by the id rule) and its side
 * of a pair is gathered by no one here. */
#define SD_GHOST_REMOTE UINT32_MAX
/* The ghost_owner of another rank's periodic image (its position shifted
 * by a period): like a local image, its pair with an owned particle is kept
 * only from the side with the lower stable id, and gathered by no one here. */
#define SD_GHOST_REMOTE_IMAGE (UINT32_MAX - 1)

/* Bytes of scratch per particle sd_bins_sort lends for the permutation. */
#define SD_BINS_PERMUTE_SCRATCH 32

/* Bins the owned particles and returns in *perm (n_owned entries, owned by
 * the bins) the order that sorts them by cell: new[k] = old[perm[k]]; and
 * in *scratch SD_BINS_PERMUTE_SCRATCH bytes per particle for applying it. */
sd_status sd_bins_sort(sd_bins *b, const sd_bins_input *in, const uint32_t **perm, void **scratch);
/* Builds both pair lists from the (sorted) owned particles and the ghosts,
 * carrying the history of the previous lists by key. */
sd_status sd_bins_build(sd_bins *b, const sd_bins_input *in, sd_pair_list *l, sd_wall_pair_list *wl);
void sd_bins_free(sd_bins *b);
/* The canonical order of every run (broad/canonical.c): every pair
 * evaluated with the lower stable id as i (flip 0), and each owned
 * particle's gather entries sorted by (partner id, own sub-index, partner
 * sub-index), so that its force sum depends on its neighbours' ids only,
 * never on storage order, cells, threads or ranks: the serial run and
 * mpirun -np N give the same bits. */
sd_status sd_pairs_canonical(const sd_bins_input *in, sd_pair_list *l);

/* The kinds of a pair and of a wall pair, from the classes and whether the
 * pair of materials has a volume law. */
SD_HD static SD_INLINE int sd_bins_pair_kind(int ci, int cj, int volume)
{
    if (ci == SD_CLASS_SPHERE && cj == SD_CLASS_SPHERE)
        return SD_PAIR_SPHERES;
    if (ci == SD_CLASS_SHAPE2D || cj == SD_CLASS_SHAPE2D)
        return SD_PAIR_CONVEX2D;
    /* a composite against anything: its element pairs (the volume law, if
     * any, is decided per element pair by the item) */
    if (ci == SD_CLASS_COMPOSITE || cj == SD_CLASS_COMPOSITE)
        return SD_PAIR_ELEMENTS;
    return volume ? SD_PAIR_POLY_VOLUME : SD_PAIR_CONVEX;
}

SD_HD static SD_INLINE int sd_bins_wall_pair_kind(int c, int volume)
{
    if (c == SD_CLASS_SPHERE)
        return SD_WALL_PAIR_SPHERE;
    if (c == SD_CLASS_SHAPE2D)
        return SD_WALL_PAIR_CONVEX2D;
    if (c == SD_CLASS_COMPOSITE)
        return SD_WALL_PAIR_ELEMENTS;
    return volume ? SD_WALL_PAIR_POLY_VOLUME : SD_WALL_PAIR_CONVEX;
}

/* The kind of a pair of a particle and a mesh plane group (a composite:
 * its elements against the group, one run per group). */
SD_HD static SD_INLINE int sd_bins_mesh_pair_kind(int c, int volume)
{
    if (c == SD_CLASS_SPHERE)
        return SD_WALL_PAIR_MESH_SPHERE;
    if (c == SD_CLASS_SHAPE2D)
        return SD_WALL_PAIR_MESH_CONVEX2D;
    if (c == SD_CLASS_COMPOSITE)
        return SD_WALL_PAIR_ELEMENTS; /* one run per plane group (items.h) */
    return volume ? SD_WALL_PAIR_MESH_POLY_VOLUME : SD_WALL_PAIR_MESH_CONVEX;
}

#endif
