/* walls.c — the CPU backend's loops over particle-wall pairs: one loop per
 * wall-pair kind (contact/kinds.h), each calling its item function
 * (backend/items.h). No physics here.
 *
 * Invariant: every item writes only its own wall pair's slots (DESIGN.md
 * rule 4). Spheres and convex shapes against walls are of even cost
 * (static schedule); the volume law's exact half-space overlaps are not
 * (dynamic chunks). Until the wall pair list is sorted by kind
 * (s->wpairs_mixed), each pair's kind is read from its particle and
 * materials, and the volume-law pairs run in a loop of their own.
 */
#include "backend/cpu/cpu.h"
#include "backend/cpu/parallel.h"
#include "backend/items.h"

static void sd_cpu_wall_kind(sd_stage *s, int kind, size_t e0, size_t e1)
{
    const sd_step_view *v = &s->v;
    sd_wall_pair_out *o = &s->wpairs;
    switch (kind) {
    case SD_WALL_PAIR_SPHERE:
SD_CPU_FOR(s->exec)
        for (size_t e = e0; e < e1; ++e)
            sd_item_wall_sphere(v, o, e);
        break;
    case SD_WALL_PAIR_CONVEX:
SD_CPU_FOR(s->exec)
        for (size_t e = e0; e < e1; ++e)
            sd_item_wall_convex(v, o, e);
        break;
    case SD_WALL_PAIR_POLY_VOLUME:
SD_CPU_FOR_DYNAMIC(s->exec)
        for (size_t e = e0; e < e1; ++e)
            sd_item_wall_poly_volume(v, o, e);
        break;
    case SD_WALL_PAIR_CONVEX2D:
SD_CPU_FOR(s->exec)
        for (size_t e = e0; e < e1; ++e)
            sd_item_wall_convex2d(v, o, e);
        break;
    default:
        break;
    }
}

/* A list whose kinds are interleaved: each pair's kind decided here (the
 * law is looked up only in a world with a volume law). */
static void sd_cpu_wall_mixed(sd_stage *s)
{
    const sd_step_view *v = &s->v;
    sd_wall_pair_out *o = &s->wpairs;
    size_t n = o->n;
    int volume = v->has_volume_law;
SD_CPU_FOR(s->exec)
    for (size_t e = 0; e < n; ++e) {
        uint32_t i = o->i[e];
        if (v->shape[i] < 0)
            sd_item_wall_sphere(v, o, e);
        else if (v->dim2)
            sd_item_wall_convex2d(v, o, e);
        else if (!volume || sd_item_wall_pair_kind(v, i, o->wall[e]) == SD_WALL_PAIR_CONVEX)
            sd_item_wall_convex(v, o, e);
    }
    if (!volume)
        return;
SD_CPU_FOR_DYNAMIC(s->exec)
    for (size_t e = 0; e < n; ++e)
        if (sd_item_wall_pair_kind(v, o->i[e], o->wall[e]) == SD_WALL_PAIR_POLY_VOLUME)
            sd_item_wall_poly_volume(v, o, e);
}

void sd_cpu_wall_forces(sd_stage *s)
{
    const sd_wall_pair_out *o = &s->wpairs;
    if (o->n == 0)
        return;
    if (s->wpairs_mixed) {
        sd_cpu_wall_mixed(s);
        return;
    }
    for (int k = 0; k < SD_WALL_PAIR_KIND_COUNT; ++k)
        if (o->kind_start[k + 1] > o->kind_start[k])
            sd_cpu_wall_kind(s, k, o->kind_start[k], o->kind_start[k + 1]);
}
