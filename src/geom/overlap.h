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
 *    (sd_dtri, shape/shape.c: the dual triangles with their vertices and
 *    twin edges), copied as it is: the work is done in A's principal frame
 *    (B's planes turned by Ra^T Rb), the results turned back at the end;
 *    B's dual points are inserted one at a time (Algorithm V: visible dual
 *    triangles, horizon loop, a fan of new triangles to the new point),
 *    the live triangles kept in consecutive slots;
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
 * With SD_OVERLAP_MAX_PLANES = 64 the workspace is about 31 KB (seed 000
 * §2.3 quotes about 20 KB for 48 faces). */
#define SD_OVERLAP_MAX_DUAL (2 * SD_OVERLAP_MAX_PLANES)
#define SD_OVERLAP_MAX_TRIS (2 * SD_OVERLAP_MAX_DUAL)
#if SD_OVERLAP_MAX_TRIS > 65535
#error "SD_OVERLAP_MAX_PLANES too large: triangle indices are 16-bit (sd_dtri)"
#endif
/* "beyond a plane" means farther than eps = SD_OVERLAP_EPS_REL x L, L the
 * sum of the two bounding radii: well above the rounding of the vertices
 * (~1e-15 L), far below any overlap that matters. */
#define SD_OVERLAP_EPS_REL SD_R(1e-12)
/* A hint must lie this far (relative to L) inside every plane to skip GJK. */
#define SD_OVERLAP_HINT_REL SD_R(1e-9)

/* Triangle and plane indices in the workspace (MAX_TRIS <= 65535). */
typedef uint16_t sd_ovl_idx;

/* One dual triangle of the hull being built: its vertex (relative to x_A,
 * in A's principal frame), planes, neighbours and the edge of each
 * neighbour that leads back — the layout of the stored template (sd_dtri),
 * so a build starts with a plain copy. */
typedef sd_dtri sd_ovl_tri;

typedef struct sd_overlap_workspace {
    /* planes in A's principal frame, offsets relative to x_A: A's first, then B's */
    sd_vec3 pn[SD_OVERLAP_MAX_DUAL];
    sd_real ph[SD_OVERLAP_MAX_DUAL];
    unsigned char shared[SD_OVERLAP_MAX_DUAL]; /* coincides with a plane of the other body */
    unsigned char done[SD_OVERLAP_MAX_DUAL];   /* output pass: face present */
    int hmark[SD_OVERLAP_MAX_DUAL];            /* g + 1: starts a horizon edge while inserting g */
    int order[SD_OVERLAP_MAX_DUAL];            /* B's planes in insertion order */
    sd_real fa[SD_OVERLAP_MAX_DUAL];           /* output pass: twice the signed area of each face */
    sd_vec3 fm[SD_OVERLAP_MAX_DUAL];           /* output pass: six times its first moment about m, less the o_p part */
    /* dual triangles, slots [0, nlive) all live */
    sd_ovl_tri tri[SD_OVERLAP_MAX_TRIS];
    sd_real s[SD_OVERLAP_MAX_TRIS];      /* signed distance beyond the plane being inserted */
    sd_ovl_idx vis[SD_OVERLAP_MAX_TRIS]; /* visible triangles, ascending (output pass: faces present) */
    /* the horizon loop, in order: each new triangle's planes a -> b, its
     * kept neighbour and that one's edge back, its vertex and its slot */
    sd_ovl_idx ha[SD_OVERLAP_MAX_TRIS], hb[SD_OVERLAP_MAX_TRIS], hu[SD_OVERLAP_MAX_TRIS];
    uint8_t hk[SD_OVERLAP_MAX_TRIS];
    sd_vec3 hw[SD_OVERLAP_MAX_TRIS];
    sd_ovl_idx hslot[SD_OVERLAP_MAX_TRIS];
    int nlive;
} sd_overlap_workspace;

/* internal result of one build attempt */
enum { SD_OVL_BUILT = 0, SD_OVL_EMPTY, SD_OVL_INCONSISTENT, SD_OVL_FULL };

SD_HD static SD_INLINE int sd_overlap_next(int k)
{
    return k == 2 ? 0 : k + 1;
}

/* Inserts plane g (Algorithm V in the primal form of the predicate):
 * marks the visible dual triangles (vertices beyond g), walks the edges
 * between visible and kept triangles into the horizon loop, and replaces
 * the visible triangles by a fan from the horizon to g. The live
 * triangles stay in slots [0, nlive): the fan reuses the visible slots,
 * appends what it needs more, and the last live triangles fill the slots
 * left over (their neighbours' links follow through the twin edges). */
SD_HD static SD_INLINE int sd_overlap_insert(sd_overlap_workspace *ws, int g, int na, sd_real eps)
{
    const sd_vec3 n = ws->pn[g];
    const sd_real h = ws->ph[g];
    const int nlive = ws->nlive;
    int nv = 0;
    /* branch-free; "visible" is s > eps, here and below */
    for (int t = 0; t < nlive; ++t) {
        sd_real s = sd_v3_dot(n, ws->tri[t].v) - h;
        ws->s[t] = s;
        ws->vis[nv] = (sd_ovl_idx)t;
        nv += s > eps;
    }
    if (nv == 0) {
        /* cuts nothing. Touching the polytope: is it one of A's planes
         * (same normal and offset)? Then the face is shared (merged). */
        int near = 0;
        for (int t = 0; t < nlive; ++t)
            near |= ws->s[t] >= -eps;
        if (near)
            for (int a = 0; a < na; ++a)
                if (sd_v3_dot(ws->pn[a], n) > SD_R(1.0) - SD_R(1e-12) && sd_fabs(ws->ph[a] - h) <= eps) {
                    ws->shared[a] = 1;
                    ws->shared[g] = 1;
                }
        return SD_OVL_BUILT;
    }
    if (nv == nlive)
        return SD_OVL_EMPTY; /* every vertex beyond g: A ∩ B is empty */
    /* horizon: edges from a visible triangle to a kept one; the first (in
     * slot order) starts the loop */
    int nhor = 0, t0 = -1, k0 = 0;
    for (int i = 0; i < nv; ++i) {
        const sd_ovl_tri *tr = &ws->tri[ws->vis[i]];
        for (int k = 0; k < 3; ++k) {
            int kept = !(ws->s[tr->nb[k]] > eps);
            int first = kept & (nhor == 0);
            t0 = first ? ws->vis[i] : t0;
            k0 = first ? k : k0;
            nhor += kept;
        }
    }
    if (nhor < 3)
        return SD_OVL_INCONSISTENT;
    if (nhor > SD_OVERLAP_MAX_TRIS || nlive - nv + nhor > SD_OVERLAP_MAX_TRIS)
        return SD_OVL_FULL;
    /* one closed loop: after the edge a -> b, turn about b through visible
     * triangles to the next edge to a kept one. A second loop (fewer edges
     * walked than counted) or a pinched vertex (b met twice: the visible
     * set is not a disc, rounding on nearly degenerate input) is refused.
     * New vertices: plane g crosses the primal edge from the visible vertex
     * w_t to the kept vertex w_u (both on the line where planes a and b
     * meet); λ in [0, 1] keeps it on that edge whatever the rounding. */
    {
        int t = t0, k = k0, e = 0, steps = 0;
        const int limit = 3 * nv;
        do {
            const sd_ovl_tri *tr = &ws->tri[t];
            int a = tr->f[k], kn = sd_overlap_next(k);
            if (e >= nhor || ws->hmark[a] == g + 1)
                return SD_OVL_INCONSISTENT;
            ws->hmark[a] = g + 1;
            int u = tr->nb[k];
            ws->ha[e] = (sd_ovl_idx)a;
            ws->hb[e] = tr->f[kn];
            ws->hu[e] = (sd_ovl_idx)u;
            ws->hk[e] = tr->nk[k];
            sd_real st = ws->s[t], su = ws->s[u];
            sd_real lam = -su / (st - su); /* st > eps >= su */
            lam = sd_clamp(lam, SD_R(0.0), SD_R(1.0));
            ws->hw[e] = sd_v3_madd(ws->tri[u].v, lam, sd_v3_sub(ws->tri[t].v, ws->tri[u].v));
            ++e;
            /* turn about b = f[kn] */
            k = kn;
            while (ws->s[ws->tri[t].nb[k]] > eps) {
                if (++steps > limit)
                    return SD_OVL_INCONSISTENT;
                int j = ws->tri[t].nk[k];
                t = ws->tri[t].nb[k];
                k = sd_overlap_next(j);
            }
        } while (t != t0 || k != k0);
        if (e != nhor)
            return SD_OVL_INCONSISTENT;
    }
    /* slots: the visible ones first (ascending), then appended */
    for (int e = 0; e < nhor; ++e)
        ws->hslot[e] = e < nv ? ws->vis[e] : (sd_ovl_idx)(nlive + (e - nv));
    /* field by field: a whole-struct copy of what was just written in
     * pieces would stall on store forwarding */
    for (int e = 0; e < nhor; ++e) {
        int t = ws->hslot[e], u = ws->hu[e], j = ws->hk[e];
        sd_ovl_tri *nt = &ws->tri[t];
        nt->f[0] = ws->ha[e];
        nt->f[1] = ws->hb[e];
        nt->f[2] = (sd_ovl_idx)g;
        nt->nb[0] = (sd_ovl_idx)u;
        nt->nb[1] = ws->hslot[e + 1 < nhor ? e + 1 : 0];
        nt->nb[2] = ws->hslot[e > 0 ? e - 1 : nhor - 1];
        nt->nk[0] = (uint8_t)j;
        nt->nk[1] = 2;
        nt->nk[2] = 1;
        ws->tri[t].v = ws->hw[e];
        ws->tri[u].nb[j] = (sd_ovl_idx)t;
        ws->tri[u].nk[j] = 0;
    }
    int nl = nlive - nv + nhor;
    /* visible slots left over (the largest, as vis ascends): fill each
     * with the last live triangle */
    for (int i = nv - 1, last = nlive; i >= nhor; --i) {
        int hole = ws->vis[i];
        --last;
        if (last == hole)
            continue;
        ws->tri[hole].v = ws->tri[last].v;
        for (int k = 0; k < 3; ++k) {
            int u = ws->tri[last].nb[k], j = ws->tri[last].nk[k];
            ws->tri[hole].f[k] = ws->tri[last].f[k];
            ws->tri[hole].nb[k] = (sd_ovl_idx)u;
            ws->tri[hole].nk[k] = (uint8_t)j;
            ws->tri[u].nb[j] = (sd_ovl_idx)hole;
        }
    }
    ws->nlive = nl;
    return SD_OVL_BUILT;
}

/* One build: A's dual hull, then B's planes, at tolerance eps. */
SD_HD static SD_INLINE int sd_overlap_build(const sd_convex *a, int na, int nbp,
                                            sd_overlap_workspace *ws, sd_real eps)
{
    const sd_shape *sa = a->shape;
    const int nt = (int)sa->tcount;
    const sd_dtri *dt = a->dtris + sa->tstart;
    ws->nlive = nt;
    for (int t = 0; t < nt; ++t)
        ws->tri[t] = dt[t];
    for (int p = 0; p < na + nbp; ++p) {
        ws->shared[p] = 0;
        ws->hmark[p] = 0;
    }
    /* a plane at least A's bounding radius from x_A cuts nothing and cannot
     * coincide with a face of A: one comparison instead of a scan. The
     * others go in nearest x_A first (deepest cut, insertion sort, ties by
     * index): they remove the most vertices, so later scans are shorter. */
    const sd_real ra = sa->bound + eps;
    int m = 0;
    for (int g = na; g < na + nbp; ++g) {
        sd_real hg = ws->ph[g];
        if (!(hg <= ra))
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

/* Volume, area vectors and moments of the built intersection. Every dual
 * edge (t, k) is the primal edge from w_t to w_u, u = nb[t][k], on face
 * p = f[t][k]; following them around p walks p's boundary (the same sense
 * for every face), so one pass over the edges, each independent of the
 * others, sums every face as a fan of triangles from o_p, the foot of the
 * perpendicular from the mean vertex m onto the plane: with r = w − m,
 * o_p − m = d_p n_p (d_p the pyramid height, eq. 9), n_p · ((o_p − m) × e) = 0,
 * so the fan triangle on edge e = w_u − w_t has area a_e = ½ n_p · (r_t × e)
 * and centroid (d_p n_p + 2 r_t + e) / 3 about m. */
SD_HD static SD_INLINE void sd_overlap_measure(sd_overlap_workspace *ws, int na, int np, const sd_convex *a,
                                               const sd_convex *b, const sd_mat3 *Ra, sd_overlap *out)
{
    const int nl = ws->nlive;
    sd_vec3 m = sd_v3_zero();
    for (int t = 0; t < nl; ++t)
        m = sd_v3_add(m, ws->tri[t].v);
    m = sd_v3_scale(m, SD_R(1.0) / (sd_real)nl);
    for (int p = 0; p < np; ++p) {
        ws->done[p] = 0;
        ws->fa[p] = SD_R(0.0);
        ws->fm[p] = sd_v3_zero();
    }
    for (int t = 0; t < nl; ++t) {
        const sd_vec3 wt = ws->tri[t].v, rt = sd_v3_sub(wt, m);
        const sd_ovl_tri *tr = &ws->tri[t];
        for (int k = 0; k < 3; ++k) {
            int p = tr->f[k];
            sd_vec3 e = sd_v3_sub(ws->tri[tr->nb[k]].v, wt);
            sd_real a2 = sd_v3_dot(ws->pn[p], sd_v3_cross(rt, e)); /* 2 a_e */
            ws->done[p] = 1;
            ws->fa[p] += a2;
            ws->fm[p] = sd_v3_madd(ws->fm[p], a2, sd_v3_madd(e, SD_R(2.0), rt));
        }
    }
    sd_real V = SD_R(0.0);
    sd_vec3 C = sd_v3_zero(), SA = sd_v3_zero(), SB = sd_v3_zero(), TA = sd_v3_zero(), TB = sd_v3_zero();
    int nfaces = 0;
    /* the faces present, listed branch-free (an unpredictable skip per
     * plane would cost more than the list) */
    for (int p = 0; p < np; ++p) {
        ws->vis[nfaces] = (sd_ovl_idx)p;
        nfaces += ws->done[p];
    }
    for (int i = 0; i < nfaces; ++i) {
        const int p = ws->vis[i];
        const sd_vec3 n = ws->pn[p];
        const sd_real d = ws->ph[p] - sd_v3_dot(n, m);
        sd_real area = SD_R(0.5) * ws->fa[p];
        /* first moment of the face about m, then about x_A */
        sd_vec3 mom = sd_v3_madd(sd_v3_scale(ws->fm[p], SD_R(1.0) / SD_R(6.0)), area * d / SD_R(3.0), n);
        /* taking the sign per face keeps a_f >= 0 whatever the sense */
        if (area < SD_R(0.0)) {
            area = -area;
            mom = sd_v3_neg(mom);
        }
        mom = sd_v3_madd(mom, area, m);
        /* pyramid from m on face p: height d_f, volume d_f a_f / 3 (eq. 9),
         * centroid m + 3/4 (c_f - m) */
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
    out->faces = nfaces;
    out->vertices = nl;
    if (!(V > SD_R(0.0))) {
        out->status = SD_OVERLAP_NONE;
        return;
    }
    /* from A's principal frame to the world's orientation */
    m = sd_mat3_mulv(*Ra, m);
    C = sd_mat3_mulv(*Ra, C);
    SA = sd_mat3_mulv(*Ra, SA);
    SB = sd_mat3_mulv(*Ra, SB);
    TA = sd_mat3_mulv(*Ra, TA);
    TB = sd_mat3_mulv(*Ra, TB);
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
    const sd_mat3 Rab = sd_mat3_mul(sd_mat3_transpose(Ra), Rb);
    const sd_vec3 dxa = sd_mat3_tmulv(Ra, dx);
    if (!sd_gjk_finite(dxa)) /* A's orientation not finite */
        return sd_overlap_none(a, SD_OVERLAP_DEGENERATE);
    /* the planes in A's principal frame (A's as stored, B's turned by
     * Ra^T Rb), offsets about x_A; the results turn back by Ra at the end */
    const sd_plane *pa = a->planes + sa->fstart, *pb = b->planes + sb->fstart;
    for (int p = 0; p < na; ++p) {
        ws->pn[p] = pa[p].n;
        ws->ph[p] = pa[p].h;
    }
    for (int p = 0; p < nbp; ++p) {
        sd_vec3 n = sd_mat3_mulv(Rab, pb[p].n);
        ws->pn[na + p] = n;
        ws->ph[na + p] = pb[p].h + sd_v3_dot(n, dxa);
    }
    /* gate: a point strictly inside every plane proves overlap (the hint,
     * else the midpoint of the centres, right for deep overlaps); otherwise
     * GJK decides (the clipping below would find an empty intersection
     * too, but GJK is cheaper for the pairs that are apart) */
    sd_vec3 x = have_hint && sd_gjk_finite(x0_hint) ? sd_mat3_tmulv(Ra, sd_v3_sub(x0_hint, a->x))
                                                     : sd_v3_scale(dxa, SD_R(0.5));
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
        r = sd_overlap_build(a, na, nbp, ws, eps);
    if (r == SD_OVL_EMPTY)
        return sd_overlap_none(a, SD_OVERLAP_NONE);
    if (r == SD_OVL_FULL)
        return sd_overlap_none(a, SD_OVERLAP_OVERFLOW);
    if (r == SD_OVL_INCONSISTENT)
        return sd_overlap_none(a, SD_OVERLAP_DEGENERATE);
    sd_overlap o = sd_overlap_none(a, SD_OVERLAP_NONE);
    sd_overlap_measure(ws, na, np, a, b, &Ra, &o);
    if (o.status != SD_OVERLAP_OK)
        return sd_overlap_none(a, SD_OVERLAP_NONE);
    return o;
}

#endif
