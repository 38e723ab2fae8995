/* backend.c — the choice of the backend that runs the cells solver's
 * stages (sd_world_def.backend), made once when the world is created.
 *
 * Invariant: after sd_world_create, w->backend is a complete stage table
 * and w->backend_note says why it was chosen (or names the device: slot
 * def.device mod the devices present, in w->stage.device_index), so
 * step.c never asks again and a run can report it (summary.txt, the
 * CLI's last line). `cuda` that cannot run is refused here, before any
 * particle is added or any file written, with the reason: the backend not
 * compiled in, no device, a driver too old. (Out of device memory shows
 * later, at the first upload in sd_world_prepare, with the bytes needed.)
 * The grid solver takes the same choice: on cuda its step runs on the
 * device (grid/grid_step.c, backend/cuda/grid.cu), its own state there
 * rather than the stage table's views.
 */
#include <stdio.h>
#include <string.h>

#include "backend/cuda/cuda.h"
#include "core/error.h"
#include "world/world.h"

static const char *const sd_backend_names[] = {
#define SD_X_NAME(e, name, doc) name,
    SD_BACKENDS(SD_X_NAME)
#undef SD_X_NAME
};

const char *sd_backend_kind_name(sd_backend_kind kind)
{
    return (kind >= 0 && kind < SD_BACKEND_COUNT) ? sd_backend_names[kind] : "unknown";
}

sd_backend_kind sd_backend_kind_from_name(const char *name)
{
    for (int k = 0; k < SD_BACKEND_COUNT; ++k)
        if (name && strcmp(name, sd_backend_names[k]) == 0)
            return (sd_backend_kind)k;
    return SD_BACKEND_COUNT;
}

/* What to do about each reason (the second half of the refusal). */
static const char *sd_backend_hint(sd_cuda_probe_result r)
{
    switch (r) {
    case SD_CUDA_NOT_BUILT:
        return "rebuild with -DSHAPEDEM_CUDA=ON where nvcc is installed, or use backend auto or cpu";
    case SD_CUDA_NO_DEVICE:
        return "run on a machine with an NVIDIA GPU, or use backend auto or cpu";
    case SD_CUDA_OLD_DRIVER:
        return "update the NVIDIA driver, or use backend auto or cpu";
    default:
        return "use backend auto or cpu";
    }
}

sd_status sd_world_choose_backend(sd_world *w, sd_error *err)
{
    sd_backend_kind want = w->def.backend;
    if (want < 0 || want >= SD_BACKEND_COUNT)
        return sd_error_set(err, SD_ERR_INPUT, "", 0, "simulation.backend", "expected auto, cpu or cuda, got %d",
                            (int)want);
    w->backend = &sd_backend_cpu;
    if (want == SD_BACKEND_CPU) {
        snprintf(w->backend_note, sizeof w->backend_note, "asked for");
        return SD_OK;
    }
    char note[sizeof w->backend_note];
    int device = 0;
    sd_cuda_probe_result r = sd_cuda_probe(w->def.device, &device, note, sizeof note);
    const sd_backend *cuda = sd_cuda_backend();
    if (r == SD_CUDA_USABLE && cuda) {
        w->backend = cuda;
        w->stage.device_index = device; /* def.device mod the devices present */
        snprintf(w->backend_note, sizeof w->backend_note, "%s", note);
        return SD_OK;
    }
    if (want == SD_BACKEND_CUDA)
        return sd_error_set(err, SD_ERR_INPUT, "", 0, "simulation.backend", "backend cuda cannot run: %s; %s", note,
                            sd_backend_hint(r));
    snprintf(w->backend_note, sizeof w->backend_note, "%s", note);
    return SD_OK;
}

const char *sd_world_backend(const sd_world *w) { return !w ? "" : w->backend ? w->backend->name : "cpu"; }

const char *sd_world_backend_note(const sd_world *w) { return w ? w->backend_note : ""; }
