/* cuda_emulated.c — the CUDA backend, emulated on the host
 * (src/backend/cuda/emulate.h), gives the CPU backend's states bit for bit.
 *
 * For each scene: world A (backend cpu, 1 thread) runs `warm` steps so that
 * contacts form and writes a checkpoint; world B (backend cuda, emulated)
 * is built from the same scene and restores it; both then run `run` steps
 * in three calls (the host changes the state between calls: insertions and
 * outlets, the restore itself). B must equal A bit for bit: every
 * particle's position, velocity, spin, orientation, force and torque by
 * stable id, every wall's force and torque, and the whole saved state (the
 * pair lists with their history and results, the narrow-phase tallies), so
 * the uploads, the read backs and every kernel are checked, not only the
 * positions. The scenes cover spheres under Hertz-Mindlin with history and
 * under the linear law, box and plane walls, moving and servo walls (2D
 * biaxial), periodic boundaries, convex shapes (GJK/EPA), sharp polyhedra
 * under the volume law, the planar mode, mesh walls (fixed and rotating),
 * composites, insertion with outlets, and the grid solver (solver: grid,
 * with its pour and its outlet).
 *
 * Then the refusals of the device probe and of the upload: no device, a
 * driver too old, too little device memory (the message names the MiB it
 * needed), through the emulator's knobs.
 */
#define _POSIX_C_SOURCE 200809L /* setenv, unsetenv */
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "test.h"

#include <shapedem/process.h>
#include <shapedem/scene.h>

#include "broad/pairs.h"
#include "grid/grid.h"
#include "world/snapshot.h"

typedef struct emu_case {
    const char *scene;
    long warm, run;
    const char *covers;
} emu_case;

static const emu_case cases[] = {
    {"examples/settle-spheres.yaml", 4500, 240, "spheres, Hertz-Mindlin with history, box wall"},
    {"examples/periodic-chute.yaml", 1000, 240, "periodic boundaries, linear law, moving wall"},
    {"examples/biaxial-2d.yaml", 4000, 240, "planar mode, 2D shapes, servo walls"},
    {"examples/mixed-shapes.yaml", 12000, 240, "convex shapes (GJK/EPA)"},
    {"bench/scenes/sharp-cubes-settle.yaml", 6000, 240, "sharp polyhedra, volume law"},
    {"tests/unit/scenes/restart-mesh-hopper.yaml", 6000, 240, "mesh walls"},
    {"tests/unit/scenes/restart-mesh-drum.yaml", 6000, 240, "rotating mesh wall"},
    {"tests/unit/scenes/restart-composites.yaml", 6000, 240, "composites"},
    {"tests/unit/scenes/restart-feed-drain.yaml", 3000, 240, "insertion and outlets"},
    /* the grid solver (its own state on the device, grid.cu): the stencil's
     * six colours, the slots, the box as mirror particles, a sheet poured
     * at steps 2500, 3750, ... (on the host between a read back and an
     * upload), the outlet opening at step 3500 inside a call, and the
     * removals through it (the host's rebin) */
    {"tests/unit/scenes/restart-grid.yaml", 2500, 7500, "solver grid: stencil, pour, outlet, removals"},
};

static int same_bits(const void *a, const void *b, size_t n) { return memcmp(a, b, n) == 0; }

/* keys compared member by member (their padding is not state) */
static int same_item(const sd_snap_item *a, const sd_snap_item *b)
{
    if (strcmp(a->name, b->name) || a->type != b->type || a->count != b->count || a->comps != b->comps)
        return 0;
    if (!strcmp(a->name, "pairs/key")) {
        const sd_pair_key *ka = a->data, *kb = b->data;
        for (size_t k = 0; k < a->count; ++k)
            if (ka[k].id_lo != kb[k].id_lo || ka[k].id_hi != kb[k].id_hi || ka[k].sub_lo != kb[k].sub_lo ||
                ka[k].sub_hi != kb[k].sub_hi)
                return 0;
        return 1;
    }
    if (!strcmp(a->name, "wall_pairs/key")) {
        const sd_wall_pair_key *ka = a->data, *kb = b->data;
        for (size_t k = 0; k < a->count; ++k)
            if (ka[k].id != kb[k].id || ka[k].wall != kb[k].wall || ka[k].sub != kb[k].sub ||
                ka[k].elem != kb[k].elem)
                return 0;
        return 1;
    }
    return same_bits(a->data, b->data, a->count * a->comps * sd_state_type_size(a->type));
}

/* Particles by stable id and walls, bitwise; the mismatches, and the
 * largest difference of a position component (m) for the message. */
static long compare_particles(const sd_world *a, const sd_world *b, double *max_dx)
{
    long bad = 0;
    *max_dx = 0;
    size_t n = sd_world_particle_count(a);
    if (n != sd_world_particle_count(b))
        return 1 + (long)n;
    for (size_t k = 0; k < n; ++k) {
        sd_particle_state pa, pb;
        sd_world_get_particle(a, k, &pa);
        size_t j = sd_world_find_particle(b, pa.id);
        if (j == (size_t)-1) {
            ++bad;
            continue;
        }
        sd_world_get_particle(b, j, &pb);
        double va[] = {pa.position.x, pa.position.y, pa.position.z, pa.velocity.x, pa.velocity.y, pa.velocity.z,
                       pa.angular_velocity.x, pa.angular_velocity.y, pa.angular_velocity.z, pa.quat[0], pa.quat[1],
                       pa.quat[2], pa.quat[3], pa.force.x, pa.force.y, pa.force.z, pa.torque.x, pa.torque.y,
                       pa.torque.z};
        double vb[] = {pb.position.x, pb.position.y, pb.position.z, pb.velocity.x, pb.velocity.y, pb.velocity.z,
                       pb.angular_velocity.x, pb.angular_velocity.y, pb.angular_velocity.z, pb.quat[0], pb.quat[1],
                       pb.quat[2], pb.quat[3], pb.force.x, pb.force.y, pb.force.z, pb.torque.x, pb.torque.y,
                       pb.torque.z};
        if (!same_bits(va, vb, sizeof va))
            ++bad;
        for (int c = 0; c < 3; ++c)
            if (fabs(va[c] - vb[c]) > *max_dx)
                *max_dx = fabs(va[c] - vb[c]);
    }
    for (size_t k = 0; k < sd_world_wall_count(a); ++k) {
        sd_wall_info wa, wb;
        sd_world_get_wall(a, k, &wa);
        sd_world_get_wall(b, k, &wb);
        double va[] = {wa.force.x, wa.force.y, wa.force.z, wa.torque.x, wa.torque.y, wa.torque.z};
        double vb[] = {wb.force.x, wb.force.y, wb.force.z, wb.torque.x, wb.torque.y, wb.torque.z};
        if (!same_bits(va, vb, sizeof va))
            ++bad;
    }
    return bad;
}

/* How many of the two worlds' state arrays (sd_world_snapshot) differ in a
 * bit, naming the first few; *n: the arrays compared. */
static size_t differing_arrays(const sd_world *a, const sd_world *b, const char *label, size_t *n)
{
    sd_error err;
    sd_snapshot xa, xb;
    CHECK(sd_world_snapshot(a, &xa, &err) == SD_OK);
    CHECK(sd_world_snapshot(b, &xb, &err) == SD_OK);
    size_t differ = xa.n == xb.n ? 0 : 1;
    for (size_t k = 0; k < xa.n && k < xb.n; ++k)
        if (!same_item(&xa.items[k], &xb.items[k])) {
            if (differ < 4)
                printf("  %s: state '%s' differs\n", label, xa.items[k].name);
            ++differ;
        }
    *n = xa.n;
    sd_snapshot_free(&xa);
    sd_snapshot_free(&xb);
    return differ;
}

static sd_status build(const char *path, sd_backend_kind backend, int threads, sd_scene **s, sd_world **w,
                       sd_error *err)
{
    sd_status st = sd_scene_load(path, s, err);
    if (st != SD_OK)
        return st;
    sd_scene_set_threads(*s, threads);
    sd_scene_set_backend(*s, backend);
    st = sd_scene_build(*s, w, err);
    if (st != SD_OK) {
        sd_scene_free(*s);
        *s = NULL;
    }
    return st;
}

static void run_case(const char *src, const emu_case *c)
{
    char path[4096], ckpt[256];
    snprintf(path, sizeof path, "%s/%s", src, c->scene);
    snprintf(ckpt, sizeof ckpt, "%s/sd-cuda-emulated-%d.h5", getenv("TMPDIR") ? getenv("TMPDIR") : "/tmp",
             (int)getpid());
    sd_error err;
    sd_scene *sa, *sb;
    sd_world *a, *b;
    sd_test_require(build(path, SD_BACKEND_CPU, 1, &sa, &a, &err) == SD_OK, c->scene, &err);
    sd_test_require(build(path, SD_BACKEND_CUDA, 1, &sb, &b, &err) == SD_OK, c->scene, &err);
    CHECK(!strcmp(sd_world_backend(a), "cpu") && !strcmp(sd_world_backend(b), "cuda"));
    sd_test_require(sd_world_step(a, c->warm, &err) == SD_OK, c->scene, &err);
    CHECK(sd_checkpoint_write(a, ckpt, &err) == SD_OK);
    sd_stats st;
    sd_world_stats(a, &st);
    sd_status rs = sd_checkpoint_restore(b, ckpt, &err);
    remove(ckpt);
    if (rs != SD_OK) {
        char buf[1024];
        sd_error_format(&err, buf, sizeof buf);
        printf("FAIL %s: restore: %s\n", c->scene, buf);
    }
    CHECK(rs == SD_OK);
    /* three calls: the device takes the host's state at each */
    long parts[3] = {c->run / 3, c->run / 3, c->run - 2 * (c->run / 3)};
    for (int k = 0; k < 3 && rs == SD_OK; ++k) {
        sd_test_require(sd_world_step(a, parts[k], &err) == SD_OK, c->scene, &err);
        sd_status bs = sd_world_step(b, parts[k], &err);
        if (bs != SD_OK) {
            char buf[1024];
            sd_error_format(&err, buf, sizeof buf);
            printf("FAIL %s: the emulated CUDA step: %s\n", c->scene, buf);
            rs = bs;
        }
    }
    CHECK(rs == SD_OK);
    double max_dx = 0;
    long bad = compare_particles(a, b, &max_dx);
    size_t arrays = 0, differ = differing_arrays(a, b, c->scene, &arrays);
    printf("%-4s %-44s %6zu particles, %5ld contacts (%ld with walls) at step %ld, +%ld steps: "
           "%ld particles or walls differ (max |dx| %.3g m), %zu of %zu state arrays differ [%s]\n",
           bad == 0 && differ == 0 ? "ok" : "FAIL", c->scene, sd_world_particle_count(a),
           st.contacts + st.wall_contacts, st.wall_contacts, c->warm, c->run, bad, max_dx, differ, arrays, c->covers);
    sd_grid_info gi;
    sd_grid_get_info(b, &gi);
    if (gi.active) /* which of the grid's paths the device run took */
        printf("     grid on the device: %zu poured, outlet %s, %zu removed, %ld cell conflicts (at most %zu without "
               "a cell), %ld slot overflows\n",
               gi.poured, gi.outlet_open ? "open" : "closed", gi.removed, gi.conflicts, gi.max_overflow,
               gi.slot_overflows);
    CHECK(bad == 0);
    CHECK(differ == 0);
    CHECK(sd_world_step_count(a) == sd_world_step_count(b) && sd_world_time(a) == sd_world_time(b));
    CHECK(st.contacts + st.wall_contacts > 0); /* the comparison runs with live contacts */
    sd_world_destroy(a);
    sd_world_destroy(b);
    sd_scene_free(sa);
    sd_scene_free(sb);
}

/* The grid solver's cell conflicts (no scene above has one): pairs of
 * spheres whose centres share a cell (grid_rules.c's case, three times
 * over, and a fourth sphere between two of them), on the CPU and on the
 * emulated device: the particles without a cell interact in one thread
 * after the colours, then claim cells as they are pushed apart (the
 * lowest storage index first). Every state array compared bit for bit. */
static sd_world *conflict_world(sd_backend_kind backend)
{
    sd_error err;
    sd_world *w;
    sd_world_def d = sd_world_def_default();
    d.dt = 1e-4;
    d.law = SD_LAW_LINEAR;
    d.gravity = sd_test_v(0, 0, -9.81);
    d.solver = SD_SOLVER_GRID;
    d.threads = 1;
    d.backend = backend;
    sd_test_require(sd_world_create(&d, &w, &err) == SD_OK, "grid world", &err);
    sd_material_def m = sd_test_material_set1();
    int mat = sd_world_add_material(w, &m, &err);
    sd_world_add_box(w, "box", sd_test_v(0, 0, 0), sd_test_v(1, 1, 1), 0, mat, &err);
    static const double xyz[][3] = {{0.5101, 0.5101, 0.5101}, {0.5301, 0.5301, 0.5201}, {0.3101, 0.5101, 0.1101},
                                    {0.3301, 0.5201, 0.1301}, {0.7101, 0.3101, 0.7101}, {0.7301, 0.3301, 0.7301},
                                    {0.6201, 0.3201, 0.7201}};
    for (size_t k = 0; k < sizeof xyz / sizeof xyz[0]; ++k) {
        sd_sphere_def sp;
        memset(&sp, 0, sizeof sp);
        sp.position = sd_test_v(xyz[k][0], xyz[k][1], xyz[k][2]);
        sp.velocity = sd_test_v(0.1 * (double)k, 0, -0.2);
        sp.radius = 0.05;
        sp.material = mat;
        sd_test_require(sd_world_add_spheres(w, 1, &sp, &err) == SD_OK, "sphere", &err);
    }
    return w;
}

/* Worlds a (CPU) and b (emulated CUDA) after the same steps: every
 * particle, wall and state array bit for bit; `label` names the case. */
static void compare_grid_worlds(const sd_world *a, const sd_world *b, const char *label)
{
    double max_dx = 0;
    long bad = compare_particles(a, b, &max_dx);
    size_t arrays = 0, differ = differing_arrays(a, b, label, &arrays);
    sd_grid_info gi;
    sd_grid_get_info(b, &gi);
    printf("%-4s %s: %zu particles (%zu poured), %ld cell conflicts (at most %zu without a cell, %zu now), step "
           "%ld: %ld particles or walls differ (max |dx| %.3g m), %zu of %zu state arrays differ\n",
           bad == 0 && differ == 0 ? "ok" : "FAIL", label, sd_world_particle_count(a), gi.poured, gi.conflicts,
           gi.max_overflow, gi.in_overflow, sd_world_step_count(b), bad, max_dx, differ, arrays);
    CHECK(bad == 0);
    CHECK(differ == 0);
    CHECK(sd_world_step_count(a) == sd_world_step_count(b));
}

static void grid_conflicts(void)
{
    sd_error err;
    sd_world *a = conflict_world(SD_BACKEND_CPU), *b = conflict_world(SD_BACKEND_CUDA);
    CHECK(!strcmp(sd_world_backend(b), "cuda"));
    long parts[3] = {5, 95, 300};
    for (int k = 0; k < 3; ++k) {
        sd_test_require(sd_world_step(a, parts[k], &err) == SD_OK, "grid conflicts, cpu", &err);
        sd_test_require(sd_world_step(b, parts[k], &err) == SD_OK, "grid conflicts, emulated cuda", &err);
    }
    compare_grid_worlds(a, b, "grid conflicts");
    sd_grid_info gi;
    sd_grid_get_info(b, &gi);
    CHECK(gi.conflicts >= 3); /* the case runs the conflict path */
    sd_world_destroy(a);
    sd_world_destroy(b);
}

/* A grid world that starts empty and pours (examples/hopper-grid.yaml):
 * the first call uploads no particle, its first step pours a sheet on the
 * host; both backends from the scene itself (no checkpoint). */
static void grid_from_empty(const char *src)
{
    char path[4096];
    snprintf(path, sizeof path, "%s/examples/hopper-grid.yaml", src);
    sd_error err;
    sd_scene *sa, *sb;
    sd_world *a, *b;
    sd_test_require(build(path, SD_BACKEND_CPU, 1, &sa, &a, &err) == SD_OK, "hopper-grid", &err);
    sd_test_require(build(path, SD_BACKEND_CUDA, 1, &sb, &b, &err) == SD_OK, "hopper-grid", &err);
    CHECK(sd_world_particle_count(a) == 0);
    long parts[2] = {1, 2999};
    for (int k = 0; k < 2; ++k) {
        sd_test_require(sd_world_step(a, parts[k], &err) == SD_OK, "hopper-grid, cpu", &err);
        sd_test_require(sd_world_step(b, parts[k], &err) == SD_OK, "hopper-grid, emulated cuda", &err);
    }
    compare_grid_worlds(a, b, "grid from empty (examples/hopper-grid.yaml)");
    CHECK(sd_world_particle_count(a) > 0);
    sd_world_destroy(a);
    sd_world_destroy(b);
    sd_scene_free(sa);
    sd_scene_free(sb);
}

/* backend cuda refused (SD_ERR_INPUT) or failing (want) with a message
 * containing `words`, under one emulator knob. */
static void refusal(const char *src, const char *knob, const char *value, sd_status want, const char *words)
{
    char path[4096];
    snprintf(path, sizeof path, "%s/examples/settle-spheres.yaml", src);
    setenv(knob, value, 1);
    sd_error err;
    memset(&err, 0, sizeof err);
    sd_scene *s = NULL;
    sd_world *w = NULL;
    sd_status st = build(path, SD_BACKEND_CUDA, 1, &s, &w, &err);
    char buf[1024];
    sd_error_format(&err, buf, sizeof buf);
    int ok = st == want && strstr(buf, words) != NULL;
    printf("%-4s %s=%s: status %d (expected %d), message: %s\n", ok ? "ok" : "FAIL", knob, value, (int)st, (int)want,
           st == SD_OK ? "(none)" : buf);
    CHECK(ok);
    if (w)
        sd_world_destroy(w);
    if (s)
        sd_scene_free(s);
    /* auto falls back to the CPU, saying why */
    if (want == SD_ERR_INPUT) {
        sd_test_require(build(path, SD_BACKEND_AUTO, 1, &s, &w, &err) == SD_OK, "auto", &err);
        int fell = !strcmp(sd_world_backend(w), "cpu") && strstr(sd_world_backend_note(w), words) != NULL;
        printf("%-4s   auto: backend %s (%s)\n", fell ? "ok" : "FAIL", sd_world_backend(w), sd_world_backend_note(w));
        CHECK(fell);
        sd_world_destroy(w);
        sd_scene_free(s);
    }
    unsetenv(knob);
}

/* The grid solver's state does not fit: the first step stops with the
 * bytes it needs (its upload is at the start of each call). */
static void grid_memory(const char *src)
{
    char path[4096];
    snprintf(path, sizeof path, "%s/tests/unit/scenes/restart-grid.yaml", src);
    setenv("SD_CUDA_EMULATE_MEMORY", "100000", 1);
    sd_error err;
    memset(&err, 0, sizeof err);
    sd_scene *s = NULL;
    sd_world *w = NULL;
    sd_test_require(build(path, SD_BACKEND_CUDA, 1, &s, &w, &err) == SD_OK, "grid world", &err);
    sd_status st = sd_world_step(w, 1, &err);
    char buf[1024];
    sd_error_format(&err, buf, sizeof buf);
    int ok = st == SD_ERR_MEMORY && strstr(buf, "out of device memory: the grid solver's state") && strstr(buf, "MiB");
    printf("%-4s grid, SD_CUDA_EMULATE_MEMORY=100000: status %d (expected %d), message: %s\n", ok ? "ok" : "FAIL",
           (int)st, (int)SD_ERR_MEMORY, st == SD_OK ? "(none)" : buf);
    CHECK(ok);
    sd_world_destroy(w);
    sd_scene_free(s);
    unsetenv("SD_CUDA_EMULATE_MEMORY");
}

int main(int argc, char **argv)
{
    const char *src = getenv("SD_SOURCE_DIR");
    if (!src)
        src = ".";
    /* one scene by name (a debugging aid), else all */
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; ++k)
        if (argc < 2 || strstr(cases[k].scene, argv[1]))
            run_case(src, &cases[k]);
    if (argc < 2 || strstr("grid conflicts", argv[1]))
        grid_conflicts();
    if (argc < 2 || strstr("grid from empty", argv[1]))
        grid_from_empty(src);
    refusal(src, "SD_CUDA_EMULATE_DEVICES", "0", SD_ERR_INPUT, "no CUDA device");
    refusal(src, "SD_CUDA_EMULATE_DRIVER", "11040", SD_ERR_INPUT, "driver too old: it supports CUDA 11.4");
    refusal(src, "SD_CUDA_EMULATE_MEMORY", "100000", SD_ERR_MEMORY, "out of device memory");
    grid_memory(src);
    return sd_test_summary();
}
