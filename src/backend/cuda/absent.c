/* absent.c — the CUDA backend's interface (backend/cuda/cuda.h) in a
 * library built without it (SHAPEDEM_CUDA=OFF, or AUTO without nvcc): no
 * device is ever usable and there is no stage table, so `backend: auto`
 * takes the CPU and `backend: cuda` is refused with the reason.
 */
#include <stdio.h>

#include "backend/cuda/cuda.h"

sd_cuda_probe_result sd_cuda_probe(char *note, size_t size)
{
    if (note && size)
        snprintf(note, size, "not compiled with CUDA");
    return SD_CUDA_NOT_BUILT;
}

const sd_backend *sd_cuda_backend(void) { return NULL; }
