"""What the GPU tests share: the skip where no CUDA device is usable, and arrays to and from the device
(CuPy or PyTorch, the `lib` fixture of conftest.py)."""

import numpy as np
import pytest

import cudahull

GPU_USABLE, GPU_WHY = cudahull._cudahull.cuda_device()
gpu_only = pytest.mark.skipif(not GPU_USABLE, reason=f"no usable CUDA device: {GPU_WHY}")


def on_device(lib, array):
    if lib.__name__ == "cupy":
        return lib.asarray(array)
    return lib.from_numpy(np.ascontiguousarray(array)).cuda()


def to_numpy(array):
    if isinstance(array, np.ndarray):
        return array
    if hasattr(array, "get"):
        return array.get()
    return array.detach().cpu().numpy()
