/* view.c — the whole decomposed world on rank 0 (mpi.h: sd_mpi_view), so
 * that the run's output (io/run.c, io/output.c, the analyses and the
 * checkpoint writer) reads one world, as in a serial run, and rank 0 writes
 * every file.
 *
 * What each rank sends, all as byte rows of the field lists (mpi/rows.h:
 * a field added to SD_PARTICLE_FIELDS, SD_PAIR_FIELDS or
 * SD_WALL_PAIR_FIELDS travels without a change here, as in comm.c):
 *   - its owned particles;
 *   - the pairs whose body i (the lower stable id: sd_pairs_canonical) it
 *     owns: a pair another rank's ghost takes part in is held by both
 *     ranks, and counted this way once;
 *   - its wall pairs (ghosts have none).
 * Rank 0 puts the particles in stable-id order and the pairs in (kind,
 * key) order, so what the output sums (energies, contacts, wall totals)
 * is summed in an order of stable ids: the same bits on any rank count.
 */
#include <mpi.h>
#include <stdlib.h>
#include <string.h>

#include "core/alloc.h"
#include "core/error.h"
#include "mpi/mpi.h"
#include "mpi/rows.h"
#include "world/mesh.h"
#include "world/process.h"
#include "world/world.h"

/* Byte offset of the particle's id within its row (the field list's order,
 * as the rows are packed; the pairs' keys: mpi/rows.h). */
static size_t sd_view_id_offset(void)
{
    size_t s = 0, at = 0;
    sd_particles probe;
#define SD_X_AT(type, name, ...)                                 \
    if ((const void *)&probe.name == (const void *)&probe.id) \
        at = s;                                               \
    s += sizeof(type);
    SD_PARTICLE_FIELDS(SD_X_AT)
#undef SD_X_AT
    return at;
}

/* ---- sorting on rank 0 ------------------------------------------------------------ */

/* ---- the gather ------------------------------------------------------------------- */

/* This rank's block: three counts, then the particle rows, the pair
 * records (kind, row) and the wall pair records (kind, row). */
static unsigned char *sd_view_pack(const sd_world *w, size_t *bytes)
{
    size_t rs = sd_mpi_row_size(), ps = sd_rows_pair_size(), ws = sd_rows_wpair_size();
    const sd_pair_list *l = &w->pairs;
    const sd_wall_pair_list *wl = &w->wpairs;
    size_t n = w->p.n, np = 0;
    for (size_t e = 0; e < l->n; ++e)
        np += l->i[e] < n;
    size_t total = 3 * sizeof(uint64_t) + n * rs + np * (sizeof(int32_t) + ps) + wl->n * (sizeof(int32_t) + ws);
    unsigned char *buf = sd_malloc(total), *b = buf;
    if (!buf)
        return NULL;
    uint64_t c[3] = {n, np, wl->n};
    memcpy(b, c, sizeof c);
    b += sizeof c;
    for (size_t k = 0; k < n; ++k)
        b = sd_mpi_row_pack(&w->p, k, b);
    for (size_t e = 0; e < l->n; ++e) {
        if (l->i[e] >= n)
            continue; /* the lower id is another rank's ghost here: its owner sends the pair */
        int32_t kind = sd_rows_kind_of(l->kind_start, SD_PAIR_KIND_COUNT, e);
        memcpy(b, &kind, sizeof kind);
        b = sd_rows_pair_pack(l, e, b + sizeof kind);
    }
    for (size_t e = 0; e < wl->n; ++e) {
        int32_t kind = sd_rows_kind_of(wl->kind_start, SD_WALL_PAIR_KIND_COUNT, e);
        memcpy(b, &kind, sizeof kind);
        b = sd_rows_wpair_pack(wl, e, b + sizeof kind);
    }
    *bytes = total;
    return buf;
}

/* The wall totals of g from its wall pairs, in their order (kind, then
 * key): the opposite of each touching pair's force, and its moment about
 * the wall's point, as the CPU backend's wall totals stage sums them
 * (backend/cpu/particles.c) in the order of its gather lists. */
static void sd_view_wall_totals(sd_world *g)
{
    const sd_wall_pair_list *l = &g->wpairs;
    for (size_t k = 0; k < g->wall_count; ++k) {
        g->walls[k].force = sd_v3_zero();
        g->walls[k].torque = sd_v3_zero();
    }
    for (size_t e = 0; e < l->n; ++e) {
        if (l->delta[e] <= 0 || l->wall[e] >= g->wall_count)
            continue;
        sd_wall *wl = &g->walls[l->wall[e]];
        sd_vec3 fw = sd_v3_neg(l->f[e]);
        wl->force = sd_v3_add(wl->force, fw);
        wl->torque = sd_v3_add(wl->torque, sd_v3_cross(sd_v3_sub(l->c[e], wl->point), fw));
    }
}

/* Rank 0: the received blocks into g. */
static sd_status sd_view_fill(sd_world *g, const unsigned char *all, const int *displ, int size, sd_error *err)
{
    size_t rs = sd_mpi_row_size(), ps = sd_rows_pair_size() + sizeof(int32_t),
           ws = sd_rows_wpair_size() + sizeof(int32_t);
    size_t n = 0, np = 0, nw = 0;
    for (int r = 0; r < size; ++r) {
        uint64_t c[3];
        memcpy(c, all + displ[r], sizeof c);
        n += c[0];
        np += c[1];
        nw += c[2];
    }
    size_t nrec = n > np + nw ? n : np + nw;
    sd_rows_rec *rec = sd_malloc((nrec ? nrec : 1) * sizeof *rec);
    if (!rec || sd_particles_reserve(&g->p, n) != SD_OK || sd_pairs_reserve(&g->pairs, np) != SD_OK ||
        sd_pairs_reserve_walls(&g->wpairs, nw) != SD_OK) {
        sd_free(rec);
        return sd_error_set(err, SD_ERR_MEMORY, "", 0, "", "out of memory gathering %zu particles on rank 0", n);
    }
    size_t id_at = sd_view_id_offset();
    /* the particles, by stable id */
    size_t t = 0;
    for (int r = 0; r < size; ++r) {
        const unsigned char *b = all + displ[r];
        uint64_t c[3];
        memcpy(c, b, sizeof c);
        b += sizeof c;
        for (uint64_t k = 0; k < c[0]; ++k, b += rs) {
            rec[t] = (sd_rows_rec){{0, 0, 0, 0}, b};
            memcpy(&rec[t].k[0], b + id_at, sizeof(uint64_t));
            ++t;
        }
    }
    qsort(rec, n, sizeof *rec, sd_rows_rec_cmp);
    for (size_t k = 0; k < n; ++k)
        sd_mpi_row_unpack(&g->p, k, rec[k].row);
    g->p.n = n;
    g->n_ghost = 0;
    /* the pairs, by (kind, key); then the wall pairs */
    for (int pass = 0; pass < 2; ++pass) {
        t = 0;
        for (int r = 0; r < size; ++r) {
            const unsigned char *b = all + displ[r];
            uint64_t c[3];
            memcpy(c, b, sizeof c);
            b += sizeof c + c[0] * rs;
            if (pass == 1)
                b += c[1] * ps;
            for (uint64_t e = 0; e < c[1 + pass]; ++e, b += pass ? ws : ps) {
                int32_t kind;
                memcpy(&kind, b, sizeof kind);
                sd_rows_rec *q = &rec[t++];
                q->row = b + sizeof kind;
                if (pass == 0)
                    sd_rows_pair_order(kind, q->row, q->k);
                else
                    sd_rows_wpair_order(kind, q->row, q->k);
            }
        }
        qsort(rec, t, sizeof *rec, sd_rows_rec_cmp);
        size_t *kind_start = pass ? g->wpairs.kind_start : g->pairs.kind_start;
        int kinds = pass ? SD_WALL_PAIR_KIND_COUNT : SD_PAIR_KIND_COUNT;
        for (int k = 0; k <= kinds; ++k)
            kind_start[k] = 0;
        for (size_t e = 0; e < t; ++e) {
            int kind = (int)(pass ? rec[e].k[0] >> 32 : rec[e].k[0]);
            kind_start[kind + 1]++;
            if (pass == 0) {
                sd_rows_pair_unpack(&g->pairs, e, rec[e].row);
                /* g's indices (a periodic image's partner is its owner: g has no ghosts) */
                g->pairs.i[e] = (uint32_t)sd_rows_index(g->p.id, n, rec[e].k[1]);
                g->pairs.j[e] = (uint32_t)sd_rows_index(g->p.id, n, rec[e].k[2]);
                g->pairs.flip[e] = 0;
            } else {
                sd_rows_wpair_unpack(&g->wpairs, e, rec[e].row);
                g->wpairs.i[e] = (uint32_t)sd_rows_index(g->p.id, n, rec[e].k[1]);
                g->wpairs.tstart[e] = g->wpairs.tcount[e] = 0; /* the mesh triangles stay on their ranks */
            }
        }
        for (int k = 0; k < kinds; ++k)
            kind_start[k + 1] += kind_start[k];
        if (pass == 0)
            g->pairs.n = t;
        else
            g->wpairs.n = t;
    }
    sd_free(rec);
    sd_view_wall_totals(g);
    return SD_OK;
}

sd_status sd_mpi_view(const sd_mpi *m, const sd_world *w, sd_world *g, sd_error *err)
{
    int rank = sd_mpi_rank(m), size = sd_mpi_size(m); /* at most 64: sd_mpi_attach */
    size_t bytes = 0;
    unsigned char *mine = sd_view_pack(w, &bytes);
    int ok = mine != NULL && bytes <= (size_t)INT32_MAX, all_ok = 0;
    MPI_Allreduce(&ok, &all_ok, 1, MPI_INT, MPI_LAND, MPI_COMM_WORLD);
    if (!all_ok) {
        sd_free(mine);
        return sd_error_set(err, SD_ERR_MEMORY, "", 0, "", "gather for the output: out of memory on %s rank",
                            ok ? "another" : "this");
    }
    int cnt_mine = (int)bytes, cnt[64], displ[64];
    MPI_Gather(&cnt_mine, 1, MPI_INT, cnt, 1, MPI_INT, 0, MPI_COMM_WORLD);
    unsigned char *all = NULL;
    size_t total = 0;
    if (rank == 0) {
        for (int r = 0; r < size; ++r) {
            displ[r] = (int)total;
            total += (size_t)cnt[r];
        }
        all = total <= (size_t)INT32_MAX ? sd_malloc(total ? total : 1) : NULL;
        ok = all != NULL;
    }
    /* rank 0 says whether it can take the rows (the others wait for it) */
    MPI_Bcast(&ok, 1, MPI_INT, 0, MPI_COMM_WORLD);
    if (!ok) {
        sd_free(mine);
        return sd_error_set(err, SD_ERR_MEMORY, "", 0, "", "gather for the output: out of memory on rank 0 (%zu bytes)",
                            total);
    }
    MPI_Gatherv(mine, cnt_mine, MPI_BYTE, all, cnt, displ, MPI_BYTE, 0, MPI_COMM_WORLD);
    sd_free(mine);
    sd_status st = SD_OK;
    if (rank == 0) {
        /* the clock and the walls' state: the same on every rank */
        g->step = w->step;
        g->time = w->time;
        g->rebuilds = w->rebuilds;
        g->next_id = w->next_id;
        g->skin = w->skin;
        /* what a run may change at the world level (world/snapshot.c's
         * SD_WORLD_STATE): an insertion of shapes into a world of spheres
         * sets has_shapes, which the broad phase reads after a restore */
        g->has_shapes = w->has_shapes;
        g->biaxial_ref = w->biaxial_ref;
        for (size_t k = 0; k < g->wall_count && k < w->wall_count; ++k) {
            g->walls[k] = w->walls[k];
            /* the sum of contact stiffness is made again before each use
             * (world/servo.c: a servo wall's over every rank, the others'
             * each rank's own): not gathered, so that no file carries a
             * partial sum that depends on the split */
            g->walls[k].stiffness = SD_R(0.0);
        }
        /* a mesh's pose at the last rebuild and its bins' cell (a
         * checkpoint lists them: world/snapshot.c's SD_MESH_STATE) */
        for (size_t k = 0; k < g->mesh_count && k < w->mesh_count; ++k) {
            g->meshes[k].trans_ref = w->meshes[k].trans_ref;
            g->meshes[k].q_ref = w->meshes[k].q_ref;
            g->meshes[k].h = w->meshes[k].h;
        }
        /* the insertions' and outlets' state (plain bytes: streams, counts,
         * next steps): the same on every rank, the counts and masses those
         * of all ranks (world/process.c, the comm's sums) */
        if (g->process && w->process)
            *g->process = *w->process;
        st = sd_view_fill(g, all, displ, size, err);
    }
    sd_free(all);
    return st;
}
