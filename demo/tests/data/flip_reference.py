"""Reference FLIP values for `demo/src/metrics.rs` from NVIDIA's own implementation.

NVIDIA's FLIP (Andersson et al. 2020, LDR-FLIP; Andersson et al. 2021, HDR-FLIP) as the
`flip-evaluator` package on PyPI (pybind11 over the C++ `FLIP.h`, v1.7). Rerun with

    python3 -m venv /tmp/flipvenv && /tmp/flipvenv/bin/pip install flip-evaluator numpy
    /tmp/flipvenv/bin/python demo/tests/data/flip_reference.py

It writes the LDR pair `flip_ldr_reference.png`, `flip_ldr_test.png` (32x32, 8-bit sRGB) beside
itself (the Rust test reads these files) and prints the values the Rust tests hard-code:

- LDR: the mean LDR-FLIP of the PNG pair (67 pixels per degree), read by the package's loader.
- HDR: the mean HDR-FLIP of a linear pair defined by `hdr_pair()` (dyadic values, exact in
  f32; `metrics.rs` builds the same pair), with the exposures the package chose, and the same
  metric with each exposure's tone-mapped image quantised to 8-bit sRGB before LDR-FLIP (what
  the crate's `flip_hdr` does, since `nv-flip` takes 8-bit input), and the mean absolute
  per-pixel difference of the two maps: the effect of that quantisation on this pair, which
  bounds the difference of the two means.
"""

import os
import struct
import zlib

import numpy as np
import flip_evaluator as flip

HERE = os.path.dirname(os.path.abspath(__file__))
N = 32
PPD = 67.0


def write_png(path, rgb):
    """An 8-bit RGB PNG (stdlib only: zlib, one filter byte 0 per row)."""
    h, w, _ = rgb.shape
    raw = b"".join(b"\x00" + rgb[y].astype(np.uint8).tobytes() for y in range(h))

    def chunk(kind, data):
        c = struct.pack(">I", len(data)) + kind + data
        return c + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)

    png = b"\x89PNG\r\n\x1a\n"
    png += chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 2, 0, 0, 0))
    png += chunk(b"IDAT", zlib.compress(raw, 9))
    png += chunk(b"IEND", b"")
    with open(path, "wb") as f:
        f.write(png)


def hash16(x, y, c):
    """A 16-bit integer hash of a pixel and channel (deterministic noise)."""
    v = ((x * 1973 + y * 9277 + c * 26699 + 1) * 2654435761) & 0xFFFFFFFF
    return v >> 16


def ldr_pair():
    """A smooth highlight on a dark tinted background (reference) and the same with noise,
    three isolated bright pixels and the highlight moved by two pixels (test), 8-bit sRGB."""
    ref = np.zeros((N, N, 3), dtype=np.int64)
    test = np.zeros((N, N, 3), dtype=np.int64)
    tint = (255, 200, 150)
    for y in range(N):
        for x in range(N):
            for c in range(3):
                base = 20 + 3 * ((x + 2 * y + 5 * c) % 11)
                dome = max(0, 220 - 3 * ((x - 16) ** 2 + (y - 14) ** 2)) * tint[c] // 255
                dome_t = max(0, 220 - 3 * ((x - 18) ** 2 + (y - 14) ** 2)) * tint[c] // 255
                noise = hash16(x, y, c) % 25 - 12
                ref[y, x, c] = min(255, base + dome)
                test[y, x, c] = min(255, max(0, base + dome_t + noise))
    for (x, y) in [(4, 5), (27, 9), (9, 26)]:
        test[y, x, :] = 255
    return ref, test


def hdr_pair():
    """Linear radiance, every value a dyadic rational (exact in f32):
    reference: a tinted ramp `(1 + (x + y) % 8) / 32 * (4 - c) / 4`, a disk of radius 3
    around (12, 20) at 16 and one pixel (25, 6) at 64;
    test: the reference with the pixels where `(3 x + 5 y) % 7 == 0` times 3/2, the disk at
    half its value, the pixel (25, 6) at 0.5 and a false glint (5, 5) at 32."""
    ref = np.zeros((N, N, 3), dtype=np.float32)
    test = np.zeros((N, N, 3), dtype=np.float32)
    for y in range(N):
        for x in range(N):
            disk = (x - 12) ** 2 + (y - 20) ** 2 < 9
            for c in range(3):
                r = (1 + (x + y) % 8) / 32 * (4 - c) / 4
                t = r * 1.5 if (3 * x + 5 * y) % 7 == 0 else r
                if disk:
                    r, t = 16.0, 8.0
                ref[y, x, c], test[y, x, c] = r, t
    ref[6, 25, :] = 64.0
    test[6, 25, :] = 0.5
    test[5, 5, :] = 32.0
    return ref, test


def aces(x):
    """FLIP's ACES fit (Narkowicz) with its 0.6 pre-exposure, clamped to [0, 1]."""
    x = 0.6 * x
    return np.clip(x * (2.51 * x + 0.03) / (x * (2.43 * x + 0.59) + 0.14), 0.0, 1.0)


def srgb8(v):
    """Linear [0, 1] to 8-bit sRGB, rounded half up."""
    v = np.clip(v, 0.0, 1.0)
    s = np.where(v <= 0.0031308, 12.92 * v, 1.055 * np.power(v, 1.0 / 2.4) - 0.055)
    return np.floor(s * 255.0 + 0.5)


def main():
    ref8, test8 = ldr_pair()
    ref_path = os.path.join(HERE, "flip_ldr_reference.png")
    test_path = os.path.join(HERE, "flip_ldr_test.png")
    write_png(ref_path, ref8)
    write_png(test_path, test8)
    _, ldr_mean, _ = flip.evaluate(ref_path, test_path, "LDR", applyMagma=False)
    # The same from arrays (bytes / 255, sRGB), as `nv-flip` converts its input.
    _, ldr_arr, _ = flip.evaluate(
        (ref8 / 255.0).astype(np.float32), (test8 / 255.0).astype(np.float32), "LDR",
        applyMagma=False)
    print(f"LDR mean (PNG files):          {ldr_mean:.9f}")
    print(f"LDR mean (arrays, bytes / 255): {ldr_arr:.9f}")

    ref, test = hdr_pair()
    hdr_map, hdr_mean, params = flip.evaluate(ref, test, "HDR", applyMagma=False)
    hdr_map = np.asarray(hdr_map, dtype=np.float64).reshape(N, N)
    start, stop, n = params["startExposure"], params["stopExposure"], params["numExposures"]
    print(f"HDR mean:                       {hdr_mean:.9f}")
    print(f"HDR exposures:                  start {start:.9f} stop {stop:.9f} count {n}")
    # Each exposure through 8-bit sRGB, LDR-FLIP of the package, per-pixel maximum.
    worst = np.zeros((N, N), dtype=np.float64)
    for i in range(n):
        e = start + i * (stop - start) / (n - 1)
        r8 = srgb8(aces(ref.astype(np.float64) * 2.0 ** e)) / 255.0
        t8 = srgb8(aces(test.astype(np.float64) * 2.0 ** e)) / 255.0
        m, _, _ = flip.evaluate(r8.astype(np.float32), t8.astype(np.float32), "LDR",
                                applyMagma=False)
        worst = np.maximum(worst, np.asarray(m).reshape(N, N))
    print(f"HDR mean, 8-bit exposures:      {worst.mean():.9f}")
    print(f"mean |8-bit - float| per pixel: {np.abs(worst - hdr_map).mean():.3e}")


if __name__ == "__main__":
    main()
