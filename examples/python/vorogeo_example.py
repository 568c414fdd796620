#!/usr/bin/env python3
"""Calling the vorogeo runtime from Python with ctypes (no build step, no extension).

    python3 vorogeo_example.py <prefix>/lib/libvorogeo.so BLOB.vgeo
"""
import ctypes
import math
import sys


def load(library_path):
    lib = ctypes.CDLL(library_path)
    size_t, u32, vp = ctypes.c_size_t, ctypes.c_uint32, ctypes.c_void_p
    lib.vg_status_string.restype = ctypes.c_char_p
    lib.vg_status_string.argtypes = [ctypes.c_int]
    lib.vg_version_string.restype = ctypes.c_char_p
    lib.vg_open_size.argtypes = [vp, size_t, ctypes.POINTER(size_t)]
    lib.vg_open.argtypes = [vp, size_t, vp, size_t, ctypes.POINTER(vp)]
    lib.vg_vertex_count.restype = u32
    lib.vg_vertex_count.argtypes = [vp]
    lib.vg_workspace_size.restype = size_t
    lib.vg_workspace_size.argtypes = [vp]
    lib.vg_workspace_init.argtypes = [vp, vp, size_t, ctypes.POINTER(vp)]
    lib.vg_distance.argtypes = [vp, vp, u32, u32, ctypes.POINTER(ctypes.c_float)]
    lib.vg_nearest.argtypes = [vp, vp, u32, ctypes.POINTER(u32), size_t, ctypes.POINTER(size_t),
                               ctypes.POINTER(ctypes.c_float)]
    return lib


def check(lib, status, what):
    if status != 0:
        raise RuntimeError(f"{what}: {lib.vg_status_string(status).decode()}")


def main():
    if len(sys.argv) != 3:
        print("usage: vorogeo_example.py LIBVOROGEO.so BLOB.vgeo", file=sys.stderr)
        return 2
    lib = load(sys.argv[1])
    blob_bytes = open(sys.argv[2], "rb").read()
    # Buffers the runtime reads and writes must stay alive as long as the graph.
    blob = ctypes.create_string_buffer(blob_bytes, len(blob_bytes))
    need = ctypes.c_size_t()
    check(lib, lib.vg_open_size(blob, len(blob_bytes), ctypes.byref(need)), "vg_open_size")
    memory = ctypes.create_string_buffer(need.value)
    graph = ctypes.c_void_p()
    check(lib, lib.vg_open(blob, len(blob_bytes), memory, need.value, ctypes.byref(graph)), "vg_open")
    ws_size = lib.vg_workspace_size(graph)
    ws_memory = ctypes.create_string_buffer(ws_size)
    ws = ctypes.c_void_p()
    check(lib, lib.vg_workspace_init(graph, ws_memory, ws_size, ctypes.byref(ws)), "vg_workspace_init")

    print(f"vorogeo {lib.vg_version_string().decode()} from Python")
    n = lib.vg_vertex_count(graph)
    d = ctypes.c_float()
    check(lib, lib.vg_distance(graph, ws, 0, n // 2, ctypes.byref(d)), "vg_distance")
    print(f"distance 0 -> {n // 2} = {d.value:.5f}")
    targets = (ctypes.c_uint32 * 3)(n - 1, n // 2, n // 3)
    index, nd = ctypes.c_size_t(), ctypes.c_float()
    check(lib, lib.vg_nearest(graph, ws, 0, targets, 3, ctypes.byref(index), ctypes.byref(nd)), "vg_nearest")
    print(f"nearest of 3 targets: index {index.value} at {nd.value:.5f}")
    assert math.isfinite(d.value) and d.value > 0
    return 0


if __name__ == "__main__":
    sys.exit(main())
