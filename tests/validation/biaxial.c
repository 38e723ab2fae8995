/* biaxial.c — seed 002 §3.2 scaled to CI: random packing and biaxial
 * compression of 500 planar particles (circles, ellipses, polygons,
 * polybéziers and Fourier shapes, equivalent sizes 0.04–0.06 m) in a
 * 1.0 m x 3.0 m box, linear law k = 1e7 N/m, mu = 0.2, local damping 0.7,
 * dt = 1e-4 s, rho = 2700 kg/m^3, g = 9.8 m/s^2, confining stress 100 kPa,
 * loading at 0.1 m/s.
 *
 * Scene: examples/biaxial-2d.yaml (the full 8 s run of the seed); here the
 * stages are shortened by re-timing the walls. Packing: the particles
 * settle under gravity from the 13 x 39 lattice (at 0.3 g, the free fall
 * under local damping 0.7, the top row lands after about 1.1 s) while the
 * top wall is brought down at 0.75 m/s to 1.6 m, above the pile.
 * Consolidation: the top wall is servo-controlled to 100 kPa from 2.1 s (at
 * most 1 m/s), the side walls from 2.2 s. Compression: from 2.7 s to 3.0 s the top wall loads at 0.1 m/s
 * (about 2.2 % axial strain), the sides held at 100 kPa.
 * Checks: while the pile forms (1 s to 2 s) no particle penetrates another or a wall by
 * more than 1.5 % of its size (equivalent diameter; seed 002 §3.2 reports no
 * overlapping particles in its packing; the bound is one impact's, below) and the packing is at rest; the
 * servo walls reach 100 kPa; during compression the lateral stress stays
 * within 2 % of 100 kPa at every step. Prints the deviatoric stress ratio
 * and the volumetric strain at several axial strains, the largest overlap
 * under 100 kPa (with k = 1e7 N/m a contact carrying the mean force
 * sigma d overlaps by about sigma d / k = 1 % of d, so the chains exceed
 * 1 % there: a property of the seed's parameters, not of the engine), and
 * the mean support calls per pair type (seed 002 Table 1).
 */
#include <stdlib.h>
#include <string.h>

#include "test.h"

#include "io/scene.h"
#include "world/world.h"

/* Equivalent diameter of particle k (the circle of the same area). */
static double eq_size(const sd_world *w, size_t k)
{
    int s = w->p.shape[k];
    return 2.0 * (s >= 0 ? (double)w->shapes2d[s].eq_radius : (double)w->p.radius[k]);
}

/* Largest overlap over size: particle pairs (the smaller size) and walls. */
static double worst_penetration(const sd_world *w)
{
    double worst = 0;
    for (size_t e = 0; e < w->pairs.n; ++e)
        if (w->pairs.delta[e] > 0)
            worst = fmax(worst, (double)w->pairs.delta[e] / fmin(eq_size(w, w->pairs.i[e]), eq_size(w, w->pairs.j[e])));
    for (size_t e = 0; e < w->wpairs.n; ++e)
        if (w->wpairs.delta[e] > 0)
            worst = fmax(worst, (double)w->wpairs.delta[e] / eq_size(w, w->wpairs.i[e]));
    return worst;
}

static int wall_index(const sd_world *w, const char *name)
{
    for (size_t k = 0; k < w->wall_count; ++k)
        if (strcmp(w->walls[k].name, name) == 0)
            return (int)k;
    return -1;
}

int main(void)
{
    const char *src = getenv("SD_SOURCE_DIR");
    char path[1024];
    snprintf(path, sizeof path, "%s/examples/biaxial-2d.yaml", src ? src : ".");
    sd_error err;
    sd_scene *scene;
    sd_world *w;
    sd_test_require(sd_scene_load(path, &scene, &err) == SD_OK, "load", &err);
    scene->world.threads = 2;
    sd_test_require(sd_scene_build(scene, &w, &err) == SD_OK, "build", &err);
    CHECK(sd_world_particle_count(w) == 500);
    int kinds[SD_SHAPE2D_KIND_COUNT] = {0};
    for (size_t k = 0; k < w->p.n; ++k)
        kinds[w->p.shape[k] >= 0 ? w->shapes2d[w->p.shape[k]].kind : SD_SHAPE2D_CIRCLE]++;
    printf("particles: %d circles, %d ellipses, %d polygons, %d polybeziers, %d Fourier\n", kinds[0], kinds[1],
           kinds[2], kinds[3], kinds[4]);
    for (int k = 0; k < SD_SHAPE2D_KIND_COUNT; ++k)
        CHECK(kinds[k] > 50);

    /* the CI schedule (see the note above) */
    const double sigma0 = 1e5, t_side = 2.2, t_load = 2.7, t_end = 3.0, rate = 0.1;
    int left = wall_index(w, "left"), right = wall_index(w, "right"), top = wall_index(w, "top");
    sd_test_require(left >= 0 && right >= 0 && top >= 0, "walls left, right, top", NULL);
    sd_wall_motion_def m = sd_wall_motion_def_default();
    m.servo_stress = sigma0;
    m.servo_start = t_side;
    m.servo_max_speed = 0.5;
    CHECK(sd_world_set_wall_motion(w, left, &m, &err) == SD_OK);
    CHECK(sd_world_set_wall_motion(w, right, &m, &err) == SD_OK);
    m.servo_start = t_side - 0.1;
    m.servo_end = t_load;
    m.servo_max_speed = 1.0;
    m.velocity = sd_test_v(0, -0.75, 0);
    m.move_start = 0;
    m.move_end = 1.4 / 0.75;
    CHECK(sd_world_set_wall_motion(w, top, &m, &err) == SD_OK);

    /* packing: sampled every 100 steps from 1 s (the pile forming) to 2 s */
    const double dt = sd_world_dt(w);
    sd_test_require(sd_world_step(w, (long)(1.0 / dt + 0.5), &err) == SD_OK, "packing", &err);
    double pen = 0, top_force = 0;
    sd_stats st;
    long n_sample = (long)((t_side - 0.2 - 1.0) / dt / 100.0 + 0.5);
    for (long k = 0; k < n_sample; ++k) {
        pen = fmax(pen, worst_penetration(w));
        top_force = fmax(top_force, fabs((double)w->walls[top].force.y));
        sd_test_require(sd_world_step(w, 100, &err) == SD_OK, "packing", &err);
    }
    sd_world_stats(w, &st);
    printf("end of packing at %.2f s: %ld contacts, max speed %.4f m/s, kinetic energy %.4g J, top wall at %.3f m\n",
           sd_world_time(w), st.contacts, st.max_speed, st.kinetic_translational + st.kinetic_rotational,
           (double)w->walls[top].point.y);
    /* The largest overlap while the pile forms is set by its hardest
     * impact: a grain landing at v overlaps by about v sqrt(m/k), 1.5 % of
     * its size at 1 m/s, so the figure is a property of one collision of a
     * chaotic pour. Two equally valid trajectories (libm's sin/cos and the
     * engine's own, which differ in the last bit of a few results) gave
     * 0.90 % and 1.20 %; 1.5 % still tells a stiffness or a time step that
     * lets grains sink into each other (several per cent). */
    CHECK_NEAR("packing (1 s to 2 s): max penetration / size", pen, 0.0, 0.015);
    CHECK_NEAR("packing: force on the top wall (N)", top_force, 0.0, 0.0); /* it stayed above the pile */

    /* consolidation: the top wall from 2.1 s, the sides from 2.2 s */
    sd_test_require(sd_world_step(w, (long)((t_load - sd_world_time(w)) / dt + 0.5), &err) == SD_OK, "consolidation",
                    &err);
    sd_biaxial b;
    CHECK(sd_world_biaxial(w, &b) == SD_OK);
    double s_top = -(double)sd_v3_dot(w->walls[top].force, w->walls[top].normal) / b.width;
    printf("after consolidation: width %.4f m, height %.4f m, sigma_xx %.1f Pa, top wall %.1f Pa\n", b.width, b.height,
           b.sigma_xx, s_top);
    CHECK_REL("consolidated: lateral stress (Pa)", b.sigma_xx, sigma0, 0.02);
    CHECK_REL("consolidated: top wall stress (Pa)", s_top, sigma0, 0.02);
    CHECK(sd_world_biaxial_reference(w) == SD_OK); /* strains count from the start of loading */
    /* compression: the top wall now moves at the loading rate */
    m = sd_wall_motion_def_default();
    m.velocity = sd_test_v(0, -rate, 0);
    m.move_start = t_load;
    m.move_end = t_end;
    CHECK(sd_world_set_wall_motion(w, top, &m, &err) == SD_OK);
    double h0 = b.height, pen_load = worst_penetration(w);
    long n_load = (long)((t_end - t_load) / dt + 0.5);

    double dev_max = 0, dev_side_max = 0;
    double marks[] = {0.005, 0.01, 0.015, 0.02};
    int next = 0;
    printf("%-14s %-14s %-14s %-14s %-14s\n", "axial strain", "sigma_xx (Pa)", "sigma_yy (Pa)", "q/p", "vol. strain");
    for (long s = 0; s < n_load; ++s) {
        sd_test_require(sd_world_step(w, 1, &err) == SD_OK, "compression", &err);
        sd_world_biaxial(w, &b);
        dev_max = fmax(dev_max, fabs(b.sigma_xx - sigma0) / sigma0);
        /* each side wall on its own, against its own stress */
        for (int k = 0; k < 2; ++k) {
            const sd_wall *wl = &w->walls[k == 0 ? left : right];
            double sk = -(double)sd_v3_dot(wl->force, wl->normal) / b.height;
            dev_side_max = fmax(dev_side_max, fabs(sk - sigma0) / sigma0);
        }
        if ((s & 63) == 0)
            pen_load = fmax(pen_load, worst_penetration(w));
        if (next < 4 && b.strain_axial >= marks[next]) {
            printf("%-14.5f %-14.1f %-14.1f %-14.5f %-14.6f\n", b.strain_axial, b.sigma_xx, b.sigma_yy, b.stress_ratio,
                   b.strain_volumetric);
            ++next;
        }
    }
    pen_load = fmax(pen_load, worst_penetration(w));
    CHECK(b.has_reference);
    CHECK_NEAR("axial strain at the end = rate t / H0", b.strain_axial, rate * (t_end - t_load) / h0, 1e-6);
    CHECK(next == 4);
    CHECK_NEAR("lateral stress: max |sigma_xx - 100 kPa| / 100 kPa", dev_max, 0.0, 0.02);
    printf("     (each side wall alone: max deviation %.4f)\n", dev_side_max);
    printf("under 100 kPa: max overlap / equivalent size %.4f (mean contact force sigma d over k_n gives "
           "about %.4f)\n",
           pen_load, sigma0 * 0.05 / 1e7 / 0.05);
    CHECK(b.stress_ratio > 0.05); /* loading mobilises friction: q/p grows */

    sd_narrow_stats ns[32];
    size_t nn = sd_world_narrow_stats(w, ns, 32);
    printf("support calls per evaluation (contact / no contact), seed 002 Table 1 reports 2.9-6.4:\n");
    for (size_t i = 0; i < nn && i < 32; ++i) {
        long long apart = ns[i].evaluations - ns[i].contacts;
        printf("  %-11s %-11s %10lld evaluations  %6.2f / %6.2f\n", ns[i].kind_a, ns[i].kind_b, ns[i].evaluations,
               ns[i].contacts ? (double)ns[i].contact_support_calls / (double)ns[i].contacts : 0.0,
               apart ? (double)(ns[i].support_calls - ns[i].contact_support_calls) / (double)apart : 0.0);
    }
    CHECK(nn >= 10);
    sd_world_destroy(w);
    sd_scene_free(scene);
    return sd_test_summary();
}
