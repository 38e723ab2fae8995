/* overlap.h — exact overlap volume of two convex polyhedra and the contact
 * geometry that makes the volume-based force the gradient of a potential.
 *
 * Seed 000 §2.3 (Algorithms II–VI, eqs. 4–9): every face plane of A and B
 * is polar-mapped about an interior point x0 (eqs. 4–5: d = h − n·x0,
 * y = n / d); the intersection I = A ∩ B is the polar of the convex hull of
 * the dual points, built by incremental quickhull; each dual triangle
 * unpolarises into one vertex of I (eqs. 6–8) and the volume is a sum of
 * signed pyramids (eq. 9). This header keeps that structure and changes how
 * it is evaluated, for robustness and speed:
 *
 *  - the hull starts from A's own dual hull, built once per template
 *    (sd_dtri, shape/shape.c: the dual triangles with their vertices), and
 *    B's dual points are inserted one at a time (Algorithm V: visible dual
 *    triangles, horizon loop, a fan of new triangles to the new point);
 *  - the visibility predicate of a dual point y_g = n_g/d_g against the
 *    dual triangle whose unpolarised vertex is w is y_g·(w − x0) > 1, i.e.
 *    n_g·w > h_g: "vertex w lies beyond plane g". It is evaluated in that
 *    primal form, so no division by d ever happens, and the dual triangle
 *    keeps its unpolarised vertex (eq. 8) instead of its dual plane. A new
 *    triangle's vertex is where plane g crosses the primal edge between a
 *    visible vertex and its non-visible neighbour (the two vertices of a
 *    horizon edge lie on the line where its two planes meet);
 *  - so no interior point is needed to build the hull (DESIGN.md's x0
 *    pitfalls — d → 0, thin or tiny overlaps — cannot arise): x0 is only the
 *    reference point of the pyramids, the mean of I's vertices (eq. 9's o),
 *    returned for the caller to keep as a warm hint. A point strictly
 *    inside both bodies (the hint, else the midpoint of the centres) proves
 *    overlap and skips the GJK gate (src/geom/gjk.h), which otherwise
 *    rejects separated pairs before any hull work;
 *  - B's planes farther from x_A than A's bounding radius are skipped, the
 *    others inserted nearest first (they cut the most vertices away);
 *  - a plane of B that coincides with one of A (face-to-face contact,
 *    identical poses) cuts nothing and is recorded as shared, which is the
 *    plane merging of notes/algorithms.md §D.
 *
 * Contact geometry (DESIGN.md "Polyhedron overlap", notes §D): each face of
 * I lies on a plane of A or of B; S_A = Σ a_f n_f over faces on A, T_A =
 * Σ a_f c_f × n_f, likewise for B. Shared faces are left out of both (the
 * antisymmetrised S = ½(S_A − S_B), T = ½(T_A − T_B)), so coplanar side
 * faces cannot tilt the normal. ∂V/∂x_A = S_A, hence F_A = −W′(V) S for a
 * potential W(V) (seed 000 eq. 13 with A_n = |S|); the line of action
 * solves x_c × S = T, x_c taken in the plane through the centroid of I
 * normal to S; the rest, (S·T)/|S|, is a couple about the normal.
 *
 * Invariants: never NaN; 0 ≤ V ≤ min(V_A, V_B) up to rounding; the result
 * is a pure function of the inputs (fixed order everywhere); a full
 * workspace is reported as SD_OVERLAP_OVERFLOW, never truncated; an
 * inconsistent hull (rounding on nearly degenerate input) is rebuilt with a
 * larger tolerance, then reported as SD_OVERLAP_DEGENERATE.
 *
 * Single source (DESIGN.md rule 1): SD_HD, plain structs, no allocation,
 * no printing, a fixed workspace sized by SD_OVERLAP_MAX_PLANES (shape.h).
 */
#ifndef SD_GEOM_OVERLAP_H
#define SD_GEOM_OVERLAP_H

#include "core/mat3.h"
#include "core/quat.h"
#include "geom/gjk.h"
#include "shape/shape.h"

typedef enum { SD_OVERLAP_NONE = 0, SD_OVERLAP_OK, SD_OVERLAP_DEGENERATE, SD_OVERLAP_OVERFLOW } sd_overlap_status;

typedef struct sd_overlap {
    int status;       /* sd_overlap_status; NONE = separated or touching: no force */
    sd_real volume;   /* m^3, V = |A ∩ B| */
    sd_vec3 normal;   /* unit, from A into B: direction of the antisymmetrised area vector S */
    sd_real area;     /* m^2, |S| — the A_n of seed 000 eq. 13 */
    sd_vec3 point;    /* m, world: contact point x_c on the line x_c × S = T, in the plane
                         through the centroid of A∩B normal to S */
    sd_real twist;    /* m^3: (S·T)/|S|, the residual couple about the normal; the couple on A
                         is -W'(V)·twist·normal */
    sd_vec3 x0;       /* m, world: interior point used (mean of the vertices of A∩B; keep per
                         pair and pass back next step as the hint) */
    sd_vec3 centroid; /* m, world: centroid of A∩B */
    sd_vec3 s_a, s_b; /* m^2: S_A and S_B with shared faces left out (closure check:
                         S_A + S_B ≈ 0 when no face is shared) */
    int faces;        /* faces of A∩B (planes that bound it) */
    int vertices;     /* dual triangles of the final hull (vertices of A∩B, a vertex where
                         k > 3 faces meet counted k − 2 times) */
} sd_overlap;

/* Workspace sizes: dual points (planes) of both bodies, and dual triangles
 * (vertices of the intersection): a hull of n points has at most 2n − 4.
 * With SD_OVERLAP_MAX_PLANES = 64 the workspace is about 38 KB (seed 000
 * §2.3 quotes about 20 KB for 48 faces). */
#define SD_OVERLAP_MAX_DUAL (2 * SD_OVERLAP_MAX_PLANES)
#define SD_OVERLAP_MAX_TRIS (2 * SD_OVERLAP_MAX_DUAL)
/* "beyond a plane" means farther than eps = SD_OVERLAP_EPS_REL x L, L the
 * sum of the two bounding radii: well above the rounding of the vertices
 * (~1e-15 L), far below any overlap that matters. */
#define SD_OVERLAP_EPS_REL SD_R(1e-12)
/* A hint must lie this far (relative to L) inside every plane to skip GJK. */
#define SD_OVERLAP_HINT_REL SD_R(1e-9)

typedef struct sd_overlap_workspace {
    /* planes, world orientation, offsets relative to x_A: A's first, then B's */
    sd_vec3 pn[SD_OVERLAP_MAX_DUAL];
    sd_real ph[SD_OVERLAP_MAX_DUAL];
    unsigned char shared[SD_OVERLAP_MAX_DUAL]; /* coincides with a plane of the other body */
    unsigned char done[SD_OVERLAP_MAX_DUAL];   /* face already summed (output pass) */
    int order[SD_OVERLAP_MAX_DUAL];            /* B's planes in insertion order */
    /* dual triangles: vertex (relative to x_A), planes, neighbours */
    sd_vec3 w[SD_OVERLAP_MAX_TRIS];
    sd_real s[SD_OVERLAP_MAX_TRIS]; /* signed distance beyond the plane being inserted */
    int f[SD_OVERLAP_MAX_TRIS][3];
    int nb[SD_OVERLAP_MAX_TRIS][3];
    unsigned char state[SD_OVERLAP_MAX_TRIS]; /* 0 free, 1 live, 2 visible */
    int free_next[SD_OVERLAP_MAX_TRIS];
    int hor_t[3 * SD_OVERLAP_MAX_TRIS], hor_e[3 * SD_OVERLAP_MAX_TRIS]; /* up to 3 per visible triangle */
    int vis[SD_OVERLAP_MAX_TRIS];
    int ha[SD_OVERLAP_MAX_TRIS], hb[SD_OVERLAP_MAX_TRIS], hu[SD_OVERLAP_MAX_TRIS]; /* horizon loop edges */
    sd_vec3 hw[SD_OVERLAP_MAX_TRIS];                                               /* their new vertices */
    int newt[SD_OVERLAP_MAX_TRIS];
    int nslots, free_head, nlive;
} sd_overlap_workspace;

/* internal result of one build attempt */
enum { SD_OVL_BUILT = 0, SD_OVL_EMPTY, SD_OVL_INCONSISTENT, SD_OVL_FULL };

SD_HD static SD_INLINE int sd_overlap_tri_new(sd_overlap_workspace *ws)
{
    int t;
    if (ws->free_head >= 0) {
        t = ws->free_head;
        ws->free_head = ws->free_next[t];
    } else {
        if (ws->nslots >= SD_OVERLAP_MAX_TRIS)
            return -1;
        t = ws->nslots++;
    }
    ws->state[t] = 1;
    ws->nlive++;
    return t;
}

SD_HD static SD_INLINE void sd_overlap_tri_free(sd_overlap_workspace *ws, int t)
{
    ws->state[t] = 0;
    ws->free_next[t] = ws->free_head;
    ws->free_head = t;
    ws->nlive--;
}

SD_HD static SD_INLINE int sd_overlap_next(int k)
{
    return k == 2 ? 0 : k + 1;
}

/* Inserts plane g (Algorithm V in the primal form of the predicate):
 * marks the visible dual triangles (vertices beyond g), orders the edges
 * between visible and kept triangles into the horizon loop, and replaces
 * the visible triangles by a fan from the horizon to g. */
SD_HD static SD_INLINE int sd_overlap_insert(sd_overlap_workspace *ws, int g, int na, sd_real eps)
{
    const sd_vec3 n = ws->pn[g];
    const sd_real h = ws->ph[g];
    int nv = 0, near = 0;
    /* branch-free: free slots (state 0) hold stale but finite vertices, are
     * measured too and never marked */
    for (int t = 0; t < ws->nslots; ++t) {
        sd_real s = sd_v3_dot(n, ws->w[t]) - h;
        int live = ws->state[t] != 0, beyond = live & (s > eps);
        ws->s[t] = s;
        ws->state[t] = (unsigned char)(ws->state[t] + beyond);
        ws->vis[nv] = t;
        nv += beyond;
        near |= live & (s >= -eps);
    }
    if (nv == 0) {
        /* cuts nothing. Touching the polytope: is it one of A's planes
         * (same normal and offset)? Then the face is shared (merged). */
        if (near)
            for (int a = 0; a < na; ++a)
                if (sd_v3_dot(ws->pn[a], n) > SD_R(1.0) - SD_R(1e-12) && sd_fabs(ws->ph[a] - h) <= eps) {
                    ws->shared[a] = 1;
                    ws->shared[g] = 1;
                }
        return SD_OVL_BUILT;
    }
    if (nv == ws->nlive)
        return SD_OVL_EMPTY; /* every vertex beyond g: A ∩ B is empty */
    /* horizon: edges from a visible triangle to a kept one */
    int nhor = 0;
    for (int i = 0; i < nv; ++i) {
        int t = ws->vis[i];
        for (int k = 0; k < 3; ++k) {
            ws->hor_t[nhor] = t;
            ws->hor_e[nhor] = k;
            nhor += ws->state[ws->nb[t][k]] != 2;
        }
    }
    if (nhor < 3)
        return SD_OVL_INCONSISTENT;
    if (nhor > SD_OVERLAP_MAX_TRIS)
        return SD_OVL_FULL; /* more new triangles than slots, whatever is freed */
    /* one closed loop: each edge a -> b is followed by the only edge that
     * starts at b. A second loop or a pinched vertex (the visible set is
     * not a disc: rounding on nearly degenerate input) is refused. */
    for (int e = 0; e + 1 < nhor; ++e) {
        int b = ws->f[ws->hor_t[e]][sd_overlap_next(ws->hor_e[e])];
        int found = -1;
        for (int c = e + 1; c < nhor; ++c)
            if (ws->f[ws->hor_t[c]][ws->hor_e[c]] == b) {
                if (found >= 0)
                    return SD_OVL_INCONSISTENT;
                found = c;
            }
        if (found < 0)
            return SD_OVL_INCONSISTENT;
        int tt = ws->hor_t[e + 1], te = ws->hor_e[e + 1];
        ws->hor_t[e + 1] = ws->hor_t[found];
        ws->hor_e[e + 1] = ws->hor_e[found];
        ws->hor_t[found] = tt;
        ws->hor_e[found] = te;
    }
    if (ws->f[ws->hor_t[nhor - 1]][sd_overlap_next(ws->hor_e[nhor - 1])] != ws->f[ws->hor_t[0]][ws->hor_e[0]])
        return SD_OVL_INCONSISTENT;
    /* new vertices: plane g crosses the primal edge from the visible vertex
     * w_t to the kept vertex w_u (both on the line where planes a and b
     * meet); λ in [0, 1] keeps it on that edge whatever the rounding */
    for (int e = 0; e < nhor; ++e) {
        int t = ws->hor_t[e], k = ws->hor_e[e];
        int u = ws->nb[t][k];
        ws->ha[e] = ws->f[t][k];
        ws->hb[e] = ws->f[t][sd_overlap_next(k)];
        ws->hu[e] = u;
        sd_real st = ws->s[t], su = ws->s[u];
        sd_real lam = -su / (st - su); /* st > eps >= su */
        lam = sd_clamp(lam, SD_R(0.0), SD_R(1.0));
        ws->hw[e] = sd_v3_madd(ws->w[u], lam, sd_v3_sub(ws->w[t], ws->w[u]));
    }
    for (int i = 0; i < nv; ++i)
        sd_overlap_tri_free(ws, ws->vis[i]);
    for (int e = 0; e < nhor; ++e) {
        int t = sd_overlap_tri_new(ws);
        if (t < 0)
            return SD_OVL_FULL;
        ws->newt[e] = t;
        ws->f[t][0] = ws->ha[e];
        ws->f[t][1] = ws->hb[e];
        ws->f[t][2] = g;
        ws->w[t] = ws->hw[e];
        int u = ws->hu[e];
        ws->nb[t][0] = u;
        for (int m = 0; m < 3; ++m)
            if (ws->f[u][m] == ws->hb[e] && ws->f[u][sd_overlap_next(m)] == ws->ha[e])
                ws->nb[u][m] = t;
    }
    for (int e = 0; e < nhor; ++e) {
        ws->nb[ws->newt[e]][1] = ws->newt[e + 1 < nhor ? e + 1 : 0];
        ws->nb[ws->newt[e]][2] = ws->newt[e > 0 ? e - 1 : nhor - 1];
    }
    return SD_OVL_BUILT;
}

/* One build: A's dual hull, then B's planes, at tolerance eps. */
SD_HD static SD_INLINE int sd_overlap_build(const sd_convex *a, const sd_mat3 *Ra, int na, int nbp,
                                            sd_overlap_workspace *ws, sd_real eps)
{
    const sd_shape *sa = a->shape;
    const int nt = (int)sa->tcount;
    const sd_dtri *dt = a->dtris + sa->tstart;
    ws->nslots = nt;
    ws->free_head = -1;
    ws->nlive = nt;
    for (int t = 0; t < nt; ++t) {
        ws->w[t] = sd_mat3_mulv(*Ra, dt[t].v);
        ws->state[t] = 1;
        for (int k = 0; k < 3; ++k) {
            ws->f[t][k] = dt[t].f[k];
            ws->nb[t][k] = dt[t].nb[k];
        }
    }
    for (int p = 0; p < na + nbp; ++p)
        ws->shared[p] = 0;
    /* a plane at least A's bounding radius from x_A cuts nothing and cannot
     * coincide with a face of A: one comparison instead of a scan. The
     * others go in nearest x_A first (deepest cut, insertion sort, ties by
     * index): they remove the most vertices, so later scans are shorter. */
    const sd_real ra = sa->bound + eps;
    int m = 0;
    for (int g = na; g < na + nbp; ++g) {
        sd_real hg = ws->ph[g];
        if (hg > ra)
            continue;
        int j = m++;
        while (j > 0 && ws->ph[ws->order[j - 1]] > hg) {
            ws->order[j] = ws->order[j - 1];
            --j;
        }
        ws->order[j] = g;
    }
    for (int i = 0; i < m; ++i) {
        int r = sd_overlap_insert(ws, ws->order[i], na, eps);
        if (r != SD_OVL_BUILT)
            return r;
    }
    return SD_OVL_BUILT;
}

/* Volume, area vectors and moments of the built intersection (faces from
 * the triangles around each dual point, in their cyclic order). */
SD_HD static SD_INLINE void sd_overlap_measure(sd_overlap_workspace *ws, int na, int np, const sd_convex *a,
                                               const sd_convex *b, sd_overlap *out)
{
    sd_vec3 m = sd_v3_zero();
    int nl = 0;
    for (int t = 0; t < ws->nslots; ++t)
        if (ws->state[t]) {
            m = sd_v3_add(m, ws->w[t]);
            ++nl;
        }
    m = sd_v3_scale(m, SD_R(1.0) / (sd_real)nl);
    for (int p = 0; p < np; ++p)
        ws->done[p] = 0;
    sd_real V = SD_R(0.0);
    sd_vec3 C = sd_v3_zero(), SA = sd_v3_zero(), SB = sd_v3_zero(), TA = sd_v3_zero(), TB = sd_v3_zero();
    int nfaces = 0;
    for (int t0 = 0; t0 < ws->nslots; ++t0) {
        if (!ws->state[t0])
            continue;
        for (int k0 = 0; k0 < 3; ++k0) {
            int p = ws->f[t0][k0];
            if (ws->done[p])
                continue;
            ws->done[p] = 1;
            ++nfaces;
            const sd_vec3 n = ws->pn[p];
            /* walk the triangles around dual point p: each is one corner of
             * face p; fan triangles from the first corner */
            sd_vec3 w0 = ws->w[t0], wp = w0;
            sd_real area = SD_R(0.0);
            sd_vec3 mom = sd_v3_zero();
            int t = t0, k = k0, count = 0;
            for (;;) {
                int u = ws->nb[t][k];
                int j = 0;
                while (j < 2 && ws->f[u][j] != p)
                    ++j;
                t = u;
                k = j;
                if (t == t0 || ++count > SD_OVERLAP_MAX_TRIS)
                    break;
                sd_vec3 wc = ws->w[t];
                if (count >= 2) {
                    sd_real ai = SD_R(0.5) * sd_v3_dot(n, sd_v3_cross(sd_v3_sub(wp, w0), sd_v3_sub(wc, w0)));
                    area += ai;
                    mom = sd_v3_madd(mom, ai / SD_R(3.0), sd_v3_add(w0, sd_v3_add(wp, wc)));
                }
                wp = wc;
            }
            /* the walk's sense is the same for every face of a hull; taking
             * the sign per face keeps a_f >= 0 whatever it is */
            if (area < SD_R(0.0)) {
                area = -area;
                mom = sd_v3_neg(mom);
            }
            /* pyramid from m on face p: height d_f, volume d_f a_f / 3 (eq. 9),
             * centroid m + 3/4 (c_f - m) */
            sd_real d = sd_v3_dot(n, sd_v3_sub(w0, m));
            V += d * area / SD_R(3.0);
            C = sd_v3_add(C, sd_v3_scale(sd_v3_add(sd_v3_scale(m, SD_R(0.25) * area), sd_v3_scale(mom, SD_R(0.75))),
                                         d / SD_R(3.0)));
            if (ws->shared[p])
                continue;
            if (p < na) {
                SA = sd_v3_madd(SA, area, n);
                TA = sd_v3_add(TA, sd_v3_cross(mom, n));
            } else {
                SB = sd_v3_madd(SB, area, n);
                TB = sd_v3_add(TB, sd_v3_cross(mom, n));
            }
        }
    }
    out->faces = nfaces;
    out->vertices = nl;
    if (!(V > SD_R(0.0))) {
        out->status = SD_OVERLAP_NONE;
        return;
    }
    sd_vec3 cen = sd_v3_scale(C, SD_R(1.0) / V);
    sd_vec3 S = sd_v3_scale(sd_v3_sub(SA, SB), SD_R(0.5));
    sd_vec3 T = sd_v3_scale(sd_v3_sub(TA, TB), SD_R(0.5));
    sd_real s2 = sd_v3_norm2(S);
    out->status = SD_OVERLAP_OK;
    out->volume = V;
    out->s_a = SA;
    out->s_b = SB;
    out->centroid = sd_v3_add(a->x, cen);
    out->x0 = sd_v3_add(a->x, m);
    if (s2 > SD_R(0.0) && s2 < SD_R(1e300)) {
        sd_real sn = sd_sqrt(s2);
        out->area = sn;
        out->normal = sd_v3_scale(S, SD_R(1.0) / sn);
        /* x_c = (S × T)/|S|² + λ S with (x_c − centroid)·S = 0 */
        sd_vec3 xc = sd_v3_madd(sd_v3_scale(sd_v3_cross(S, T), SD_R(1.0) / s2), sd_v3_dot(cen, S) / s2, S);
        out->point = sd_v3_add(a->x, xc);
        out->twist = sd_v3_dot(S, T) / sn;
    } else {
        /* every face shared (identical poses): no direction; zero area, so
         * no force, with a deterministic normal along the centres */
        sd_vec3 d = sd_v3_sub(b->x, a->x);
        out->area = SD_R(0.0);
        out->normal = sd_v3_norm2(d) > SD_R(0.0) ? sd_v3_normalize(d) : sd_v3(SD_R(0.0), SD_R(0.0), SD_R(1.0));
        out->point = out->centroid;
        out->twist = SD_R(0.0);
    }
}

SD_HD static SD_INLINE sd_overlap sd_overlap_none(const sd_convex *a, int status)
{
    sd_overlap o;
    o.status = status;
    o.volume = o.area = o.twist = SD_R(0.0);
    o.normal = sd_v3(SD_R(0.0), SD_R(0.0), SD_R(1.0));
    o.point = o.x0 = o.centroid = a->x;
    o.s_a = o.s_b = sd_v3_zero();
    o.faces = o.vertices = 0;
    return o;
}

/* A and B are sharp polyhedra (radius 0, kind SD_SHAPE_POLYHEDRON) with
 * their planes and dual triangles (sd_convex.planes / .dtris). Force on A
 * for a potential W(V): F_A = -W'(V)·area·normal, torque on A about its
 * centre x_A: (point - x_A) × F_A - W'(V)·twist·normal. B gets the opposite
 * force and its own torque. x0_hint: the previous step's x0 of this pair
 * (have_hint = 1) — if it is still inside both bodies the GJK gate is
 * skipped. */
SD_HD static SD_INLINE sd_overlap sd_overlap_polyhedra(const sd_convex *a, const sd_convex *b, sd_vec3 x0_hint,
                                                       int have_hint, sd_overlap_workspace *ws)
{
    const sd_shape *sa = a->shape, *sb = b->shape;
    if (!a->planes || !a->dtris || !b->planes || sa->fcount < 4 || sb->fcount < 4 || sa->tcount < 4)
        return sd_overlap_none(a, SD_OVERLAP_DEGENERATE);
    if (sa->fcount > SD_OVERLAP_MAX_PLANES || sb->fcount > SD_OVERLAP_MAX_PLANES || sa->tcount > SD_OVERLAP_MAX_TRIS)
        return sd_overlap_none(a, SD_OVERLAP_OVERFLOW);
    const int na = (int)sa->fcount, nbp = (int)sb->fcount, np = na + nbp;
    const sd_real L = sa->bound + sb->bound;
    const sd_mat3 Ra = sd_quat_to_mat3(a->q), Rb = sd_quat_to_mat3(b->q);
    const sd_vec3 dx = sd_v3_sub(b->x, a->x);
    if (!sd_gjk_finite(dx) || !(L > SD_R(0.0)))
        return sd_overlap_none(a, SD_OVERLAP_DEGENERATE);
    /* the planes in the world's orientation, offsets about x_A */
    const sd_plane *pa = a->planes + sa->fstart, *pb = b->planes + sb->fstart;
    for (int p = 0; p < na; ++p) {
        ws->pn[p] = sd_mat3_mulv(Ra, pa[p].n);
        ws->ph[p] = pa[p].h;
    }
    for (int p = 0; p < nbp; ++p) {
        sd_vec3 n = sd_mat3_mulv(Rb, pb[p].n);
        ws->pn[na + p] = n;
        ws->ph[na + p] = pb[p].h + sd_v3_dot(n, dx);
    }
    /* gate: a point strictly inside every plane proves overlap (the hint,
     * else the midpoint of the centres, right for deep overlaps); otherwise
     * GJK decides (the clipping below would find an empty intersection
     * too, but GJK is cheaper for the pairs that are apart) */
    sd_vec3 x = have_hint && sd_gjk_finite(x0_hint) ? sd_v3_sub(x0_hint, a->x) : sd_v3_scale(dx, SD_R(0.5));
    sd_real slack = SD_R(1e300);
    for (int p = 0; p < np; ++p)
        slack = sd_min(slack, ws->ph[p] - sd_v3_dot(ws->pn[p], x));
    int inside = slack > SD_OVERLAP_HINT_REL * L;
    if (!inside) {
        sd_gjk_result g = sd_gjk_distance(a, b, sd_v3_zero());
        if (g.status == SD_GJK_SEPARATED && g.distance > SD_R(0.0))
            return sd_overlap_none(a, SD_OVERLAP_NONE);
    }
    sd_real eps = SD_OVERLAP_EPS_REL * L;
    int r = SD_OVL_INCONSISTENT;
    for (int attempt = 0; attempt < 3 && r == SD_OVL_INCONSISTENT; ++attempt, eps *= SD_R(100.0))
        r = sd_overlap_build(a, &Ra, na, nbp, ws, eps);
    if (r == SD_OVL_EMPTY)
        return sd_overlap_none(a, SD_OVERLAP_NONE);
    if (r == SD_OVL_FULL)
        return sd_overlap_none(a, SD_OVERLAP_OVERFLOW);
    if (r == SD_OVL_INCONSISTENT)
        return sd_overlap_none(a, SD_OVERLAP_DEGENERATE);
    sd_overlap o = sd_overlap_none(a, SD_OVERLAP_NONE);
    sd_overlap_measure(ws, na, np, a, b, &o);
    if (o.status != SD_OVERLAP_OK)
        return sd_overlap_none(a, SD_OVERLAP_NONE);
    return o;
}

#endif
