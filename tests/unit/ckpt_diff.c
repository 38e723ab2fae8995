/* ckpt_diff.c — the state comparison of bench/gpu/run (tests/tools/
 * ckpt_diff.h) finds what it must: a state read back from its checkpoint
 * image equals itself bit for bit; the same state with one position moved
 * by 1 ulp differs in exactly that dataset and value (and passes a 1e-12
 * relative tolerance); a flipped byte in an integer dataset is beyond any
 * tolerance; a missing dataset and another step are differences. */
#include "test.h"

#include "core/alloc.h"
#include "io/checkpoint.h"
#include "tools/ckpt_diff.h"

#include <shapedem/scene.h>
#include <stdint.h>
#include <string.h>

static sd_snap_item *find_item(sd_snapshot *s, const char *name)
{
    for (size_t k = 0; k < s->n; k++)
        if (!strcmp(s->items[k].name, name))
            return &s->items[k];
    return NULL;
}

int main(void)
{
    const char *src = getenv("SD_SOURCE_DIR");
    char path[4096];
    snprintf(path, sizeof path, "%s/examples/settle-spheres.yaml", src ? src : ".");
    sd_error err;
    sd_scene *scene;
    sd_world *w;
    sd_test_require(sd_scene_load(path, &scene, &err) == SD_OK, path, &err);
    sd_test_require(sd_scene_build(scene, &w, &err) == SD_OK, path, &err);
    sd_test_require(sd_world_step(w, 200, &err) == SD_OK, "200 steps", &err);
    sd_snapshot s0;
    sd_test_require(sd_world_snapshot(w, &s0, &err) == SD_OK, "snapshot", &err);
    void *buf = NULL;
    size_t size = 0;
    sd_test_require(sd_checkpoint_encode(&s0, &buf, &size, &err) == SD_OK, "encode", &err);
    sd_snapshot a, b;
    sd_test_require(sd_checkpoint_decode(buf, size, &a, &err) == SD_OK, "decode a", &err);
    sd_test_require(sd_checkpoint_decode(buf, size, &b, &err) == SD_OK, "decode b", &err);

    sd_ckdiff_result r;
    sd_ckdiff_compare(&a, &b, 0.0, 0, stdout, &r);
    printf("same image: %zu datasets, %zu differ\n", r.datasets, r.differ);
    CHECK(r.datasets == a.n && r.differ == 0 && r.beyond == 0 && !r.header_differs);

    /* one position component, 1 ulp up */
    sd_snap_item *x = find_item(&b, "particles/x");
    CHECK(x && x->type == SD_ST_F64 && x->count > 0);
    if (x) {
        double v;
        memcpy(&v, x->data, 8);
        double up = nextafter(v, INFINITY);
        memcpy(x->data, &up, 8);
        sd_ckdiff_compare(&a, &b, 0.0, 0, stdout, &r);
        double scale = 0.0;
        for (size_t k = 0; k < x->count * x->comps; k++) {
            double e;
            memcpy(&e, (char *)x->data + 8 * k, 8);
            scale = fmax(scale, fabs(e));
        }
        CHECK(r.differ == 1 && r.beyond == 1 && !strcmp(r.worst, "particles/x"));
        CHECK_NEAR("1 ulp in particles/x: relative difference", r.max_rel, (up - v) / scale, 1e-30);
        sd_ckdiff_compare(&a, &b, 1e-12, 0, NULL, &r);
        CHECK(r.differ == 1 && r.beyond == 0); /* within the documented bound */
        memcpy(x->data, &v, 8);
    }
    /* one flipped bit in an integer dataset: beyond any tolerance */
    sd_snap_item *id = find_item(&b, "particles/id");
    CHECK(id && id->count > 1);
    if (id) {
        ((unsigned char *)id->data)[8] ^= 1;
        sd_ckdiff_compare(&a, &b, 1.0, 0, stdout, &r);
        CHECK(r.differ == 1 && r.beyond == 1 && !strcmp(r.worst, "particles/id"));
        ((unsigned char *)id->data)[8] ^= 1;
    }
    /* another step, and a dataset missing from one side */
    b.step++;
    sd_ckdiff_compare(&a, &b, 0.0, 0, stdout, &r);
    CHECK(r.header_differs && r.differ == 0);
    b.step--;
    b.n--; /* drops the last item by name */
    sd_ckdiff_compare(&a, &b, 0.0, 0, stdout, &r);
    CHECK(r.differ == 1 && r.beyond == 1 && r.datasets == a.n);
    b.n++;

    sd_snapshot_free(&a);
    sd_snapshot_free(&b);
    sd_snapshot_free(&s0);
    sd_free(buf);
    sd_world_destroy(w);
    sd_scene_free(scene);
    return sd_test_summary();
}
