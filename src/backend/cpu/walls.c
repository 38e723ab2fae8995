/* walls.c — the CPU backend's loops over particle-wall pairs: one loop per
 * wall-pair kind (contact/kinds.h), each calling its item function
 * (backend/items.h). No physics here.
 *
 * Invariant: every item writes only its own wall pair's slots (DESIGN.md
 * rule 4). Spheres and convex shapes against walls are of even cost
 * (static schedule); the volume law's exact half-space overlaps are not
 * (dynamic chunks). The broad phase keeps the list in kind segments
 * (kind_start); the gather and the wall totals read it in wall order
 * through the gather lists, so the segments change no sum.
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
        SD_CPU_EACH(s->exec, e, e0, e1, sd_item_wall_sphere(v, o, e));
        break;
    case SD_WALL_PAIR_CONVEX:
        SD_CPU_EACH(s->exec, e, e0, e1, sd_item_wall_convex(v, o, e));
        break;
    case SD_WALL_PAIR_POLY_VOLUME:
        SD_CPU_EACH_DYNAMIC(s->exec, e, e0, e1, sd_item_wall_poly_volume(v, o, e));
        break;
    case SD_WALL_PAIR_CONVEX2D:
        SD_CPU_EACH(s->exec, e, e0, e1, sd_item_wall_convex2d(v, o, e));
        break;
    case SD_WALL_PAIR_ELEMENTS:
        /* one item per run of a composite's elements against one feature
         * (seed 004 §2.6), found by the thread whose chunk it starts in */
        SD_CPU_EACH_DYNAMIC(s->exec, e, e0, e1, if (!sd_item_wall_elements_starts(o, e0, e)) continue;
                            size_t end = e + 1;
                            while (end < e1 && !sd_item_wall_elements_starts(o, e0, end)) ++end;
                            (void)sd_item_wall_elements(v, o, e, end));
        break;
    case SD_WALL_PAIR_MESH_SPHERE:
        SD_CPU_EACH(s->exec, e, e0, e1, sd_item_mesh_sphere(v, o, e));
        break;
    case SD_WALL_PAIR_MESH_CONVEX:
        SD_CPU_EACH_DYNAMIC(s->exec, e, e0, e1, sd_item_mesh_convex(v, o, e));
        break;
    case SD_WALL_PAIR_MESH_POLY_VOLUME:
        SD_CPU_EACH_DYNAMIC(s->exec, e, e0, e1, sd_item_mesh_poly_volume(v, o, e));
        break;
    case SD_WALL_PAIR_MESH_CONVEX2D:
        SD_CPU_EACH(s->exec, e, e0, e1, sd_item_mesh_convex2d(v, o, e));
        break;
    default:
        break;
    }
}

void sd_cpu_wall_forces(sd_stage *s)
{
    const sd_wall_pair_out *o = &s->wpairs;
    for (int k = 0; k < SD_WALL_PAIR_KIND_COUNT; ++k)
        if (o->kind_start[k + 1] > o->kind_start[k])
            sd_cpu_wall_kind(s, k, o->kind_start[k], o->kind_start[k + 1]);
}
