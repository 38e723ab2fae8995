#!/usr/bin/env python3
"""png_mad.py — what tests/cli/render.sh asks of a PNG, with the standard library only.

    png_mad.py size FILE            prints "WIDTH HEIGHT" (exit 2 if FILE is not a PNG)
    png_mad.py colours FILE X0      prints "A B": of the coloured pixels (not grey: channels
                                    more than 40 apart) in columns X0 and right of it, A the
                                    colours covering 10 pixels or more, B all colours (a
                                    legend's few swatches, or a colour scale's gradient)
    png_mad.py extent FILE          prints "X0 Y0 X1 Y1", the box of the coloured pixels
                                    (walls are grey, the particles coloured)
    png_mad.py mad A B [--shift N]  prints the mean absolute difference of A and B over
                                    every pixel and channel (0-255) after a 3x3 box blur of
                                    each, B moved N pixels to the right first (its first
                                    column repeated: a one-pixel shift of the picture)

The blur spreads an edge over three pixels, so an edge moved by one pixel
costs a third of what it costs unblurred, while a wrong colour over a
particle's whole area costs as much as before: the tolerance can then tell a
one-pixel shift from a wrong colour map.

Decodes non-interlaced 8-bit RGB and RGBA PNGs (what cairo writes), undoing the
five scanline filters of the PNG specification.
"""
import struct
import sys
import zlib


def read_png(path):
    with open(path, "rb") as f:
        data = f.read()
    if data[:8] != b"\x89PNG\r\n\x1a\n":
        raise ValueError(f"{path}: not a PNG file")
    pos, idat, ihdr = 8, b"", None
    while pos + 8 <= len(data):
        length, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + length]
        if kind == b"IHDR":
            ihdr = struct.unpack(">IIBBBBB", body)
        elif kind == b"IDAT":
            idat += body
        elif kind == b"IEND":
            break
        pos += 12 + length
    if ihdr is None:
        raise ValueError(f"{path}: no IHDR chunk")
    w, h, depth, ctype, _, _, interlace = ihdr
    if depth != 8 or ctype not in (2, 6) or interlace:
        raise ValueError(f"{path}: only 8-bit RGB/RGBA non-interlaced PNGs are read")
    bpp = 3 if ctype == 2 else 4
    raw = zlib.decompress(idat)
    stride = w * bpp
    rows, prev, p = [], bytearray(stride), 0
    for _ in range(h):
        ftype, line = raw[p], bytearray(raw[p + 1:p + 1 + stride])
        p += 1 + stride
        for i in range(stride):
            a = line[i - bpp] if i >= bpp else 0
            b = prev[i]
            c = prev[i - bpp] if i >= bpp else 0
            if ftype == 1:
                line[i] = (line[i] + a) & 255
            elif ftype == 2:
                line[i] = (line[i] + b) & 255
            elif ftype == 3:
                line[i] = (line[i] + (a + b) // 2) & 255
            elif ftype == 4:
                pa, pb, pc = abs(b - c), abs(a - c), abs(a + b - 2 * c)
                pred = a if pa <= pb and pa <= pc else (b if pb <= pc else c)
                line[i] = (line[i] + pred) & 255
        rows.append(bytes(line[k] for k in range(stride) if k % bpp < 3))  # RGB only
        prev = line
    return w, h, rows


def blur(rows, w, h):
    """3x3 box average of every channel, edges clamped."""
    out = []
    for y in range(h):
        up, mid, dn = rows[max(y - 1, 0)], rows[y], rows[min(y + 1, h - 1)]
        r = []
        for x in range(w):
            xs = (3 * max(x - 1, 0), 3 * x, 3 * min(x + 1, w - 1))
            for c in range(3):
                r.append(sum(row[k + c] for row in (up, mid, dn) for k in xs) / 9.0)
        out.append(r)
    return out


def coloured(rgb):
    return max(rgb) - min(rgb) > 40


def main(argv):
    try:
        if len(argv) == 4 and argv[1] == "colours":
            w, h, rows = read_png(argv[2])
            count = {}
            for row in rows:
                for x in range(int(argv[3]), w):
                    rgb = tuple(row[3 * x:3 * x + 3])
                    if coloured(rgb):
                        count[rgb] = count.get(rgb, 0) + 1
            print(sum(1 for n in count.values() if n >= 10), len(count))
            return 0
        if len(argv) == 3 and argv[1] == "extent":
            w, h, rows = read_png(argv[2])
            xs, ys = [], []
            for y, row in enumerate(rows):
                for x in range(w):
                    if coloured(tuple(row[3 * x:3 * x + 3])):
                        xs.append(x)
                        ys.append(y)
            print(*(min(xs), min(ys), max(xs), max(ys)) if xs else (0, 0, 0, 0))
            return 0
        if len(argv) == 3 and argv[1] == "size":
            w, h, _ = read_png(argv[2])
            print(w, h)
            return 0
        if len(argv) in (4, 6) and argv[1] == "mad":
            shift = int(argv[5]) if len(argv) == 6 and argv[4] == "--shift" else 0
            wa, ha, a = read_png(argv[2])
            wb, hb, b = read_png(argv[3])
            if (wa, ha) != (wb, hb):
                print(f"sizes differ: {wa}x{ha} and {wb}x{hb}", file=sys.stderr)
                return 2
            if shift:
                b = [rb[:3 * shift] + rb[:len(rb) - 3 * shift] for rb in b]
            total = 0.0
            for ra, rb in zip(blur(a, wa, ha), blur(b, wb, hb)):
                total += sum(abs(x - y) for x, y in zip(ra, rb))
            print(f"{total / (3 * wa * ha):.4f}")
            return 0
    except (OSError, ValueError, zlib.error) as e:
        print(e, file=sys.stderr)
        return 2
    print(__doc__, file=sys.stderr)
    return 2


if __name__ == "__main__":
    sys.exit(main(sys.argv))
