/* out_of_memory.c — every allocation of world set-up and stepping may fail:
 * the library returns SD_ERR_MEMORY and never crashes (STYLE.md 8). */
#include <string.h>

#include "test.h"

#include "core/alloc.h"

static sd_status attempt(void)
{
    sd_error err;
    sd_world *w = NULL;
    sd_world_def d = sd_world_def_default();
    d.threads = 1;
    sd_status st = sd_world_create(&d, &w, &err);
    if (st != SD_OK)
        return st;
    sd_material_def m = sd_material_def_default();
    m.youngs_modulus = 1e7;
    int mat = sd_world_add_material(w, &m, &err);
    if (mat < 0) {
        sd_world_destroy(w);
        return err.code;
    }
    if (sd_world_add_box(w, "box", sd_test_v(0, 0, 0), sd_test_v(0.01, 0.01, 0.01), 0, mat, &err) < 0) {
        sd_world_destroy(w);
        return err.code;
    }
    sd_sphere_def s[64];
    for (int k = 0; k < 64; ++k) {
        memset(&s[k], 0, sizeof s[k]);
        s[k].position = sd_test_v(0.001 + 0.002 * (k % 4), 0.001 + 0.002 * ((k / 4) % 4), 0.001 + 0.002 * (k / 16));
        s[k].radius = 0.00099;
        s[k].material = mat;
    }
    st = sd_world_add_spheres(w, 64, s, &err);
    if (st == SD_OK)
        st = sd_world_step(w, 50, &err);
    sd_world_destroy(w);
    return st;
}

int main(void)
{
    int failures_seen = 0, other = 0;
    long n;
    for (n = 1; n < 500; ++n) {
        sd_alloc_fail_after(n);
        sd_status st = attempt();
        sd_alloc_fail_after(0);
        if (st == SD_OK)
            break;
        if (st == SD_ERR_MEMORY)
            failures_seen++;
        else
            other++;
    }
    printf("     %d injected allocation failures all reported as SD_ERR_MEMORY; success once %ld allocations "
           "succeed\n",
           failures_seen, n - 1);
    CHECK(failures_seen > 10);
    CHECK(other == 0);
    CHECK(sd_memory_in_use() == 0); /* nothing leaked on any path */
    return sd_test_summary();
}
