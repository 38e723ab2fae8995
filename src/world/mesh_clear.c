/* mesh_clear.c — whether an inserted particle may go where it was drawn,
 * as far as the mesh walls are concerned (issue 31: insertion checked the
 * plane, box and drum walls only, so a region crossing a mesh placed
 * particles across its facets or outside a mesh container).
 *
 * A particle's bounding sphere (centre x, radius b) is clear of a mesh
 * when no facet comes closer to x than b (the facets near x through the
 * mesh's facet bins, dynamics/meshwall.h, once they are built; before the
 * first prepare, every facet), and, for a closed mesh, when x lies on its
 * particle side: inside a container, outside an obstacle. The side is the
 * winding number of the closed surface about x (geom/solid_angle.h: about
 * +-1 inside, 0 outside, whatever the facets' orientation), a pass over
 * its facets, paid only by a sphere that touches none. An open mesh has no
 * inside; its facets are kept clear of. Everything is in the mesh's own
 * frame, x mapped by the inverse of the present pose.
 */
#include <math.h>

#include "geom/clip.h"
#include "geom/solid_angle.h"
#include "world/mesh.h"
#include "world/world.h"

/* Up to this many bin cells a query walks the bins; a sphere wider than
 * that (or a mesh not binned yet) is checked against every facet. */
#define SD_CLEAR_MAX_CELLS 512

static int sd_clear_facet(const sd_mesh_view *mv, uint32_t t, sd_vec3 xm, sd_real b2)
{
    const uint32_t *tv = mv->tris[t];
    int feature;
    sd_vec3 c = sd_clip_closest(xm, mv->verts[tv[0]], mv->verts[tv[1]], mv->verts[tv[2]], &feature);
    return sd_v3_norm2(sd_v3_sub(xm, c)) >= b2;
}

/* 1 when no facet of the mesh is closer than b to xm (mesh frame). */
static int sd_clear_facets(const sd_mesh_view *mv, sd_vec3 xm, sd_real b)
{
    const sd_real b2 = b * b;
    if (mv->h > 0 && mv->entry_count > 0) {
        sd_real h = mv->h;
        long i0 = sd_mesh_cell_of(xm.x - b, mv->origin.x, h), i1 = sd_mesh_cell_of(xm.x + b, mv->origin.x, h);
        long j0 = sd_mesh_cell_of(xm.y - b, mv->origin.y, h), j1 = sd_mesh_cell_of(xm.y + b, mv->origin.y, h);
        long k0 = sd_mesh_cell_of(xm.z - b, mv->origin.z, h), k1 = sd_mesh_cell_of(xm.z + b, mv->origin.z, h);
        if ((double)(i1 - i0 + 1) * (double)(j1 - j0 + 1) * (double)(k1 - k0 + 1) <= SD_CLEAR_MAX_CELLS) {
            for (long i = i0; i <= i1; ++i)
                for (long j = j0; j <= j1; ++j)
                    for (long k = k0; k <= k1; ++k) {
                        uint64_t key = sd_mesh_key(i, j, k);
                        for (size_t e = sd_mesh_lower(mv, key); e < mv->entry_count && mv->entry_key[e] == key; ++e)
                            if (!sd_clear_facet(mv, mv->entry_tri[e], xm, b2))
                                return 0;
                    }
            return 1;
        }
    }
    for (size_t t = 0; t < mv->tri_count; ++t)
        if (!sd_clear_facet(mv, (uint32_t)t, xm, b2))
            return 0;
    return 1;
}

/* Winding number of the (closed) mesh about xm (mesh frame). */
static double sd_clear_winding(const sd_mesh_view *mv, sd_vec3 xm)
{
    double sum = 0;
    for (size_t t = 0; t < mv->tri_count; ++t) {
        const uint32_t *tv = mv->tris[t];
        double c[3][3];
        for (int k = 0; k < 3; ++k) {
            sd_vec3 v = mv->verts[tv[k]];
            c[k][0] = (double)v.x - (double)xm.x;
            c[k][1] = (double)v.y - (double)xm.y;
            c[k][2] = (double)v.z - (double)xm.z;
        }
        sum += sd_solid_angle(c[0], c[1], c[2]);
    }
    return sum / (4 * 3.14159265358979323846);
}

int sd_world_meshes_clear(const sd_world *w, sd_v3d x, double b)
{
    const sd_vec3 xw = sd_v3((sd_real)x.x, (sd_real)x.y, (sd_real)x.z);
    for (size_t k = 0; k < w->mesh_count; ++k) {
        const sd_mesh_store *s = &w->meshes[k];
        const sd_wall_geom *g = &w->walls[s->wall].geom;
        const sd_mesh_view *mv = &w->mesh_views[k];
        sd_vec3 xm = sd_mesh_to_frame(g->q, g->trans, xw);
        if (!sd_clear_facets(mv, xm, (sd_real)b))
            return 0;
        if (s->closed_side != 0) {
            int inside = fabs(sd_clear_winding(mv, xm)) >= 0.5;
            if (inside != (s->closed_side == SD_TRIMESH_INSIDE))
                return 0;
        }
    }
    return 1;
}
