/* composite_presets.c — glued composites from the built-in presets through
 * the public C API ([Rakotonirina 2019]): an L (boxes glued flush, exact
 * mass sums), a 3D cross and a 12-segment ring (overlapping elements: the
 * voxel lattice), and a T edited before it is glued (a sphere added at the
 * foot of its stem). It prints each template's mass properties, drops one
 * of each onto a floor and reports where they came to rest.
 *
 *     cc -std=c17 composite_presets.c $(pkg-config --cflags --libs shapedem) -lm -o composite_presets
 *     ./composite_presets
 *
 * The suite compiles and runs it (tests/unit/example_composite_presets.c);
 * exit status 0 when the L's volume is its closed form to 1e-12 and every
 * body rests on the floor after 1 s, 1 otherwise, 2 when the API refuses
 * a call.
 */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include <shapedem/shapedem.h>

static int refused(const char *what, const sd_error *err)
{
    char buf[1024];
    sd_error_format(err, buf, sizeof buf);
    fprintf(stderr, "composite_presets: %s: %s\n", what, buf);
    return 2;
}

int main(void)
{
    sd_error err;
    sd_world *w;
    sd_world_def wd = sd_world_def_default();
    wd.law = SD_LAW_LINEAR;
    wd.dt = 1e-5;
    wd.gravity = (sd_v3d){0, 0, -9.81};
    wd.threads = 1;
    if (sd_world_create(&wd, &w, &err) != SD_OK)
        return refused("world", &err);
    sd_material_def md = sd_material_def_default();
    md.density = 1200;
    md.stiffness = 2e4;
    md.restitution = 0.3;
    md.friction = 0.5;
    int mat = sd_world_add_material(w, &md, &err);
    if (mat < 0 || sd_world_add_plane(w, "floor", (sd_v3d){0, 0, 0}, (sd_v3d){0, 0, 1}, mat, &err) < 0)
        return refused("material and floor", &err);

    /* three presets as they come */
    const double L = 0.02, W = 0.005, T = 0.004;
    sd_composite_preset_def lp = sd_composite_preset_def_default();
    lp.preset = "lshape";
    lp.length = L;
    lp.width = W;
    lp.thickness = T;
    sd_composite_preset_def cp = sd_composite_preset_def_default();
    cp.preset = "cross3d";
    cp.length = 0.02;
    cp.diameter = 0.005;
    sd_composite_preset_def rp = sd_composite_preset_def_default();
    rp.preset = "ring";
    rp.diameter = 0.02;
    rp.width = 0.003;
    rp.length = 0.01;
    rp.count = 12;
    int shapes[4];
    shapes[0] = sd_world_add_composite_preset(w, "L", &lp, &err);
    if (shapes[0] < 0)
        return refused("lshape", &err);
    shapes[1] = sd_world_add_composite_preset(w, "cross", &cp, &err);
    if (shapes[1] < 0)
        return refused("cross3d", &err);
    shapes[2] = sd_world_add_composite_preset(w, "ring", &rp, &err);
    if (shapes[2] < 0)
        return refused("ring", &err);

    /* a T, its element list edited before gluing: a sphere at its foot */
    sd_composite_preset_def tp = sd_composite_preset_def_default();
    tp.preset = "tshape";
    tp.length = L;
    tp.width = W;
    tp.thickness = T;
    sd_composite_element el[65];
    size_t n = 0;
    if (sd_composite_preset(w, "T", &tp, el, 64, &n, &err) != SD_OK)
        return refused("tshape", &err);
    sd_shape_desc ball = sd_shape_desc_default();
    ball.kind = "sphere";
    ball.size = (sd_v3d){0.004, 0, 0};
    int bs = sd_world_add_shape(w, "T.foot", &ball, &err);
    if (bs < 0)
        return refused("sphere", &err);
    memset(&el[n], 0, sizeof el[n]);
    el[n].shape = bs;
    el[n].position = (sd_v3d){0, -L, 0}; /* the stem's end: the T's top edge is at y = 0 */
    sd_composite_desc cd = sd_composite_desc_default();
    cd.elements = el;
    cd.element_count = n + 1;
    shapes[3] = sd_world_add_composite(w, "T with a foot", &cd, &err);
    if (shapes[3] < 0)
        return refused("T with a foot", &err);

    printf("%-14s %8s %12s %14s %12s  %s\n", "template", "elements", "volume m^3", "bound radius m", "I_max m^5",
           "mass properties");
    for (int k = 0; k < 4; ++k) {
        sd_shape_info si;
        sd_world_get_shape(w, (size_t)shapes[k], &si);
        double imax = fmax(si.inertia.x, fmax(si.inertia.y, si.inertia.z));
        char how[64];
        if (si.lattice)
            snprintf(how, sizeof how, "lattice %d per direction, est. error %.1e", si.lattice, si.lattice_error);
        else
            snprintf(how, sizeof how, "exact sums");
        printf("%-14s %8zu %12.5e %14.5e %12.5e  %s\n", si.name, si.element_count, si.volume, si.bounding_radius,
               imax, how);
    }
    int bad = 0;
    sd_shape_info li;
    sd_world_get_shape(w, (size_t)shapes[0], &li);
    double lv = L * W * T + W * (L - W) * T;
    printf("L volume %.12e m^3, closed form %.12e m^3\n", li.volume, lv);
    bad |= fabs(li.volume - lv) > 1e-12 * lv;

    sd_body_def b[4];
    memset(b, 0, sizeof b);
    for (int k = 0; k < 4; ++k) {
        b[k].shape = shapes[k];
        b[k].material = mat;
        b[k].position = (sd_v3d){-0.045 + 0.03 * k, 0, 0.03};
        b[k].orientation[0] = cos(0.2 * (k + 1));
        b[k].orientation[1] = sin(0.2 * (k + 1));
    }
    if (sd_world_add_bodies(w, 4, b, &err) != SD_OK)
        return refused("bodies", &err);
    if (sd_world_step(w, 100000, &err) != SD_OK)
        return refused("step", &err);
    for (size_t k = 0; k < 4; ++k) {
        sd_particle_state p;
        sd_world_get_particle(w, k, &p);
        sd_shape_info si;
        sd_world_get_shape(w, (size_t)shapes[k], &si);
        double sp = sqrt(p.velocity.x * p.velocity.x + p.velocity.y * p.velocity.y + p.velocity.z * p.velocity.z);
        printf("%-14s at rest at z = %.5f m (bound radius %.5f m), speed %.2e m/s\n", si.name, p.position.z,
               si.bounding_radius, sp);
        bad |= !(p.position.z > 0 && p.position.z < si.bounding_radius && sp < 1e-3);
    }
    sd_world_destroy(w);
    printf("%s\n", bad ? "FAILED" : "done");
    return bad;
}
