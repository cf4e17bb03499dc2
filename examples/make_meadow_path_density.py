# Writes an 8-bit grey PNG density map: a winding footpath and a few bare patches on a meadow.
import math, struct, zlib, random
N = 128
random.seed(4)
patches = [(random.uniform(10, 118), random.uniform(10, 118), random.uniform(4, 9)) for _ in range(5)]
rows = []
for j in range(N):            # row 0 = north edge
    y = (N - 1 - j) / (N - 1)  # 0 south .. 1 north
    row = bytearray([0])
    for i in range(N):
        x = i / (N - 1)
        # a footpath winding from the south-west to the north-east
        cx = 0.15 + 0.7 * y + 0.08 * math.sin(6.0 * y)
        d = abs(x - cx) * N
        path = min(1.0, max(0.0, (d - 3.0) / 3.0))          # 3 texels bare each side, 3 of edge
        v = path
        for (px, py, r) in patches:
            dd = math.hypot(i - px, j - py)
            v = min(v, min(1.0, max(0.0, (dd - r) / 4.0)))
        row.append(int(round(255 * v)))
    rows.append(bytes(row))
raw = b"".join(rows)
def chunk(t, d): return struct.pack(">I", len(d)) + t + d + struct.pack(">I", zlib.crc32(t + d) & 0xffffffff)
png = b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", N, N, 8, 0, 0, 0, 0)) + chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b"")
open("examples/meadow_path_density.png", "wb").write(png)
