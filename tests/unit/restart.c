/* restart.c — checkpoints restart bit for bit (issue 17).
 *
 * For each scene: world A runs `warm` steps (contacts form), then `half`
 * steps, writes a checkpoint, and runs `half` more; world B is built fresh
 * from the same scene with 2 threads, restores the checkpoint and runs
 * `half` steps. B must equal A bit for bit: every particle's position,
 * velocity, spin, orientation, force and torque by stable id, every wall's
 * force and torque, the step and the time, and the whole saved state (pair
 * lists and contact history included, item by item). The
 * scenes cover spheres, convex shapes, sharp polyhedra (volume law), the
 * planar mode with servo walls, the grid solver with its pour and outlet,
 * periodic boundaries and moving walls, the cells solver's insertion and
 * outlets (a checkpoint with particles inserted and removed since the
 * last rebuild), a fixed and a rotating mesh wall (wall history keyed per
 * plane group, the mesh's pose at the last rebuild, its facet bins),
 * composites (history per element pair) and a servo floor under a bed whose
 * corner an outlet takes at the checkpoint's step (the drift of a servo
 * wall in a world changed since its last rebuild: it once summed the
 * contact stiffness through stale gather lists, entries past the compacted
 * list among them, and the restart differed in 143 particles).
 */
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "test.h"

#include <shapedem/process.h>
#include <shapedem/scene.h>

#include "broad/pairs.h"
#include "world/snapshot.h"

typedef struct restart_case {
    const char *scene;
    long warm, half;
} restart_case;

static const restart_case cases[] = {
    {"examples/settle-spheres.yaml", 4500, 500},
    {"bench/scenes/spheres-settle-8000.yaml", 300, 100},
    {"bench/scenes/sharp-cubes-settle.yaml", 6000, 500},
    {"examples/mixed-shapes.yaml", 12000, 500},
    {"examples/biaxial-2d.yaml", 4000, 500},
    {"tests/unit/scenes/restart-grid.yaml", 2500, 500},
    {"examples/periodic-chute.yaml", 1000, 500},
    {"tests/unit/scenes/restart-feed-drain.yaml", 3000, 500},
    {"tests/unit/scenes/restart-mesh-hopper.yaml", 6000, 500},
    {"tests/unit/scenes/restart-mesh-drum.yaml", 6000, 500},
    {"tests/unit/scenes/restart-composites.yaml", 6000, 500},
    {"tests/unit/scenes/restart-servo-outlet.yaml", 3000, 500},
};

static int same_bits(const void *a, const void *b, size_t n) { return memcmp(a, b, n) == 0; }

/* Two saved items alike: bitwise, but the history keys member by member
 * (their structs have padding whose bytes mean nothing). */
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
            if (ka[k].id != kb[k].id || ka[k].wall != kb[k].wall || ka[k].sub != kb[k].sub)
                return 0;
        return 1;
    }
    return same_bits(a->data, b->data, a->count * a->comps * sd_state_type_size(a->type));
}

/* Every particle of a and b by stable id, bitwise; returns the mismatches. */
static long compare_particles(const sd_world *a, const sd_world *b, const char *scene)
{
    long bad = 0;
    size_t n = sd_world_particle_count(a);
    if (n != sd_world_particle_count(b)) {
        printf("  %s: %zu particles against %zu\n", scene, n, sd_world_particle_count(b));
        return 1;
    }
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
        if (!same_bits(va, vb, sizeof va)) {
            if (bad < 3)
                printf("  %s: particle id %llu differs (x %.17g against %.17g)\n", scene,
                       (unsigned long long)pa.id, pa.position.x, pb.position.x);
            ++bad;
        }
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

static void run_case(const char *src, const restart_case *c)
{
    char path[4096], ckpt[256];
    snprintf(path, sizeof path, "%s/%s", src, c->scene);
    snprintf(ckpt, sizeof ckpt, "restart-test-%d.h5", (int)getpid());
    sd_error err;
    sd_scene *sa, *sb;
    sd_world *a, *b;
    sd_test_require(sd_scene_load(path, &sa, &err) == SD_OK, c->scene, &err);
    sd_test_require(sd_scene_load(path, &sb, &err) == SD_OK, c->scene, &err);
    sd_scene_set_threads(sa, 1);
    sd_scene_set_threads(sb, 2);
    sd_test_require(sd_scene_build(sa, &a, &err) == SD_OK, c->scene, &err);
    sd_test_require(sd_scene_build(sb, &b, &err) == SD_OK, c->scene, &err);
    /* warm-up and the first half in two calls (a run's output chunks) */
    sd_test_require(sd_world_step(a, c->warm, &err) == SD_OK, c->scene, &err);
    sd_test_require(sd_world_step(a, c->half, &err) == SD_OK, c->scene, &err);
    sd_stats st;
    sd_world_stats(a, &st);
    sd_process_info pi;
    sd_world_get_process(a, &pi);
    size_t n_ckpt = sd_world_particle_count(a);
    CHECK(sd_checkpoint_write(a, ckpt, &err) == SD_OK);
    sd_test_require(sd_world_step(a, c->half, &err) == SD_OK, c->scene, &err);

    sd_status rs = sd_checkpoint_restore(b, ckpt, &err);
    if (rs != SD_OK) {
        char buf[1024];
        sd_error_format(&err, buf, sizeof buf);
        printf("FAIL %s: restore: %s\n", c->scene, buf);
    }
    CHECK(rs == SD_OK);
    CHECK(sd_world_step_count(b) == c->warm + c->half);
    if (rs == SD_OK)
        sd_test_require(sd_world_step(b, c->half, &err) == SD_OK, c->scene, &err);
    long bad = compare_particles(a, b, c->scene);
    sd_snapshot xa, xb;
    CHECK(sd_world_snapshot(a, &xa, &err) == SD_OK);
    CHECK(sd_world_snapshot(b, &xb, &err) == SD_OK);
    int same_state = xa.n == xb.n;
    for (size_t k = 0; k < xa.n && k < xb.n; ++k)
        if (!same_item(&xa.items[k], &xb.items[k])) {
            printf("  %s: state '%s' differs\n", c->scene, xa.items[k].name);
            same_state = 0;
        }
    printf("  %-44s %6zu particles %6ld contacts (%ld with walls) at the checkpoint (step %ld", c->scene,
           n_ckpt, st.contacts + st.wall_contacts, st.wall_contacts, c->warm + c->half);
    if (pi.inserted || pi.removed)
        printf(", %zu inserted and %zu removed by then", pi.inserted, pi.removed);
    printf("): %ld particles or walls differ, %zu state arrays %s\n", bad, xa.n,
           same_state ? "all equal" : "NOT all equal");
    CHECK(bad == 0);
    CHECK(same_state);
    CHECK(sd_world_step_count(a) == sd_world_step_count(b) && sd_world_time(a) == sd_world_time(b));
    CHECK(st.contacts + st.wall_contacts > 0); /* the restart carries live contacts */
    sd_snapshot_free(&xa);
    sd_snapshot_free(&xb);
    remove(ckpt);
    sd_world_destroy(a);
    sd_world_destroy(b);
    sd_scene_free(sa);
    sd_scene_free(sb);
}

int main(int argc, char **argv)
{
    const char *src = getenv("SD_SOURCE_DIR");
    sd_test_require(src != NULL, "SD_SOURCE_DIR is set (ctest sets it)", NULL);
    for (size_t c = 0; c < sizeof cases / sizeof cases[0]; ++c)
        if (argc < 2 || strstr(cases[c].scene, argv[1]))
            run_case(src, &cases[c]);
    return sd_test_summary();
}
