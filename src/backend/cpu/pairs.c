/* pairs.c — the CPU backend's loops over particle pairs: one loop per
 * interaction kind segment (contact/kinds.h), each calling that kind's
 * item function (backend/items.h) on every pair of its segment. No physics
 * here.
 *
 * Invariants: every item writes only its own pair's slots, so the forces
 * are the same bits for any thread count (DESIGN.md rule 4): sphere pairs,
 * of even cost, take a static schedule; the narrow-phase kinds, of very
 * uneven cost, dynamic chunks. The narrow-phase statistics (evaluations,
 * iterations and support calls per pair of shape kinds, since the world was
 * created) are tallied by each thread for the pairs it ran and added to the
 * world's counters once per loop: integer sums, exact in any order, and no
 * serial pass over the pairs. The narrow-phase kinds' functions are run by
 * each thread of a team (their loops are orphaned `omp for` constructs,
 * SD_CPU_TEAM), or once when the world is serial.
 */
#include <string.h>

#include "backend/cpu/cpu.h"
#include "backend/cpu/parallel.h"
#include "backend/items.h"

static void sd_cpu_spheres(sd_stage *s, size_t e0, size_t e1)
{
    const sd_step_view *v = &s->v;
    sd_pair_out *o = &s->pairs;
    SD_CPU_EACH(s->exec, e, e0, e1, sd_item_spheres(v, o, e));
}

/* A thread's narrow-phase tallies (3D: evaluations, iterations, support
 * calls per sorted pair of shape kinds). */
typedef struct sd_tally3 {
    long long t[SD_SHAPE_KIND_COUNT][SD_SHAPE_KIND_COUNT][3];
    int any;
} sd_tally3;

static SD_INLINE void sd_tally3_add(sd_tally3 *y, const sd_step_view *v, const sd_pair_out *o, size_t e)
{
    if (o->supports[e] == 0)
        return; /* culled by the bounding spheres */
    int a = sd_item_shape_kind(v, o->i[e]), b = sd_item_shape_kind(v, o->j[e]);
    if (a > b) {
        int t = a;
        a = b;
        b = t;
    }
    y->t[a][b][0] += 1;
    y->t[a][b][1] += o->iters[e];
    y->t[a][b][2] += o->supports[e];
    y->any = 1;
}

static void sd_tally3_flush(sd_stage *s, const sd_tally3 *y)
{
    if (!y->any)
        return;
SD_PRAGMA(omp critical(sd_narrow_tally))
    for (int a = 0; a < SD_SHAPE_KIND_COUNT; ++a)
        for (int b = a; b < SD_SHAPE_KIND_COUNT; ++b)
            for (int c = 0; c < 3; ++c)
                s->narrow[a][b][c] += y->t[a][b][c];
}

/* The 3D convex narrow phase over [e0, e1). */
static void sd_cpu_convex(sd_stage *s, size_t e0, size_t e1)
{
    const sd_step_view *v = &s->v;
    sd_pair_out *o = &s->pairs;
    sd_tally3 y;
    memset(&y, 0, sizeof y);
SD_PRAGMA(omp for schedule(dynamic, 64))
    for (size_t e = e0; e < e1; ++e) {
        sd_item_convex(v, o, e);
        sd_tally3_add(&y, v, o, e);
    }
    sd_tally3_flush(s, &y);
}

/* The volume law over [e0, e1), with one overlap workspace per thread (a
 * few KB to tens of KB, on that thread's stack: never one per pair). A
 * function of its own, so that the convex loop above keeps its narrow
 * phase inlined. */
static void sd_cpu_poly_volume(sd_stage *s, size_t e0, size_t e1)
{
    const sd_step_view *v = &s->v;
    sd_pair_out *o = &s->pairs;
    sd_overlap_workspace ws;
    sd_tally3 y;
    memset(&y, 0, sizeof y);
SD_PRAGMA(omp for schedule(dynamic, 64))
    for (size_t e = e0; e < e1; ++e) {
        sd_item_poly_volume(v, o, e, &ws);
        sd_tally3_add(&y, v, o, e);
    }
    sd_tally3_flush(s, &y);
}

/* The composite element pairs over [e0, e1): one item per run of element
 * pairs of one composite pair (backend/items.h), so the multi-contact
 * combination of seed 004 §2.6 needs no second pass; runs of very uneven
 * cost, dynamic chunks; each thread finds the runs that start in its
 * chunk. The tallies count the element pairs under the particles' kinds
 * (a composite row). */
static void sd_cpu_elements(sd_stage *s, size_t e0, size_t e1)
{
    const sd_step_view *v = &s->v;
    sd_pair_out *o = &s->pairs;
    sd_overlap_workspace ws;
    sd_tally3 y;
    memset(&y, 0, sizeof y);
SD_PRAGMA(omp for schedule(dynamic, 16))
    for (size_t e = e0; e < e1; ++e) {
        if (!sd_item_elements_starts(o, e0, e))
            continue;
        size_t end = e + 1;
        while (end < e1 && !sd_item_elements_starts(o, e0, end))
            ++end;
        (void)sd_item_elements(v, o, e, end, &ws);
        for (size_t k = e; k < end; ++k)
            sd_tally3_add(&y, v, o, k);
    }
    sd_tally3_flush(s, &y);
}

/* The 2D tallies: evaluations, contacts, support calls, support calls of
 * the contacts per sorted pair of 2D kinds. */
typedef struct sd_tally2 {
    long long t[SD_SHAPE2D_KIND_COUNT][SD_SHAPE2D_KIND_COUNT][4];
    int any;
} sd_tally2;

static void sd_cpu_convex2d(sd_stage *s, size_t e0, size_t e1)
{
    const sd_step_view *v = &s->v;
    sd_pair_out *o = &s->pairs;
    sd_tally2 y;
    memset(&y, 0, sizeof y);
SD_PRAGMA(omp for schedule(dynamic, 64))
    for (size_t e = e0; e < e1; ++e) {
        sd_item_convex2d(v, o, e);
        if (o->supports[e] == 0)
            continue; /* culled by the bounding circles */
        int a = sd_item_shape2d_kind(v, o->i[e]), b = sd_item_shape2d_kind(v, o->j[e]);
        if (a > b) {
            int t = a;
            a = b;
            b = t;
        }
        y.t[a][b][0] += 1;
        y.t[a][b][1] += o->iters[e];
        y.t[a][b][2] += o->supports[e];
        y.t[a][b][3] += o->iters[e] ? o->supports[e] : 0;
        y.any = 1;
    }
    if (y.any) {
SD_PRAGMA(omp critical(sd_narrow_tally))
        for (int a = 0; a < SD_SHAPE2D_KIND_COUNT; ++a)
            for (int b = a; b < SD_SHAPE2D_KIND_COUNT; ++b)
                for (int c = 0; c < 4; ++c)
                    s->narrow2d[a][b][c] += y.t[a][b][c];
    }
}

void sd_cpu_forces(sd_stage *s, sd_pair_kind kind)
{
    const sd_pair_out *o = &s->pairs;
    size_t e0 = o->kind_start[kind], e1 = o->kind_start[kind + 1];
    if (e1 <= e0)
        return;
    switch (kind) {
    case SD_PAIR_SPHERES:
        sd_cpu_spheres(s, e0, e1);
        break;
    case SD_PAIR_CONVEX:
        SD_CPU_TEAM(s->exec, sd_cpu_convex(s, e0, e1));
        break;
    case SD_PAIR_POLY_VOLUME:
        SD_CPU_TEAM(s->exec, sd_cpu_poly_volume(s, e0, e1));
        break;
    case SD_PAIR_CONVEX2D:
        SD_CPU_TEAM(s->exec, sd_cpu_convex2d(s, e0, e1));
        break;
    case SD_PAIR_ELEMENTS:
        SD_CPU_TEAM(s->exec, sd_cpu_elements(s, e0, e1));
        break;
    case SD_PAIR_KIND_COUNT:
        break;
    }
}
