#!/usr/bin/env python3
"""Checks screenshots of a mechdiff HTML report (see check_report_in_chromium.sh).

usage: check_report_screenshot.py REPORT.html RUN.json POINT PHI=SHOT.png ...

For each screenshot: finds the red joint (the page paints `mark=POINT` red), takes the centre
of its pixels, and compares it with the solver's position of POINT at drive position PHI (the
run's JSON, columns x_POINT and y_POINT, row with phi == PHI) mapped to pixels by the frame
written on the drawing (`data-scale`, `data-origin-x`, `data-origin-y`). Exit 1 if any is more
than 1.5 px away. Only the standard library: PNG decoded here (8-bit RGB/RGBA, no interlace).
"""
import json
import re
import struct
import sys
import zlib

TOLERANCE_PX = 1.5  # the ring is ~10 px across; its centroid is exact to well under a pixel


def read_png(path):
    data = open(path, "rb").read()
    assert data[:8] == b"\x89PNG\r\n\x1a\n", f"{path} is not a PNG"
    pos, idat, width = 8, b"", None
    while pos < len(data):
        (length,) = struct.unpack(">I", data[pos:pos + 4])
        kind, body = data[pos + 4:pos + 8], data[pos + 8:pos + 8 + length]
        pos += 12 + length
        if kind == b"IHDR":
            width, height, depth, colour, _, _, interlace = struct.unpack(">IIBBBBB", body)
            assert depth == 8 and colour in (2, 6) and interlace == 0, "unsupported PNG"
            channels = 3 if colour == 2 else 4
        elif kind == b"IDAT":
            idat += body
    raw = zlib.decompress(idat)
    stride = width * channels
    rows, prev, k = [], bytearray(stride), 0
    for _ in range(height):
        f, line = raw[k], bytearray(raw[k + 1:k + 1 + stride])
        k += 1 + stride
        for i in range(stride):
            a = line[i - channels] if i >= channels else 0
            b = prev[i]
            c = prev[i - channels] if i >= channels else 0
            if f == 1:
                line[i] = (line[i] + a) & 255
            elif f == 2:
                line[i] = (line[i] + b) & 255
            elif f == 3:
                line[i] = (line[i] + (a + b) // 2) & 255
            elif f == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                pred = a if pa <= pb and pa <= pc else (b if pb <= pc else c)
                line[i] = (line[i] + pred) & 255
        rows.append(line)
        prev = line
    return width, height, channels, rows


def red_centre(path, box=(800, 600)):
    width, height, channels, rows = read_png(path)
    xs = ys = n = 0
    for y in range(min(height, box[1])):
        row = rows[y]
        for x in range(min(width, box[0])):
            r, g, b = row[x * channels], row[x * channels + 1], row[x * channels + 2]
            if r > 200 and g < 60 and b < 60:
                xs, ys, n = xs + x + 0.5, ys + y + 0.5, n + 1
    if n == 0:
        return None
    return xs / n, ys / n, n


def main():
    report, run, point, shots = sys.argv[1], sys.argv[2], sys.argv[3], sys.argv[4:]
    html = open(report, encoding="utf-8").read()
    frame = {k: float(re.search(rf'data-{k}="([^"]+)"', html).group(1))
             for k in ("scale", "origin-x", "origin-y")}
    data = json.load(open(run))
    names = [c["name"] for c in data["columns"]]
    kx, ky = names.index(f"x_{point}"), names.index(f"y_{point}")
    failed = False
    for shot in shots:
        phi, path = shot.split("=", 1)
        row = min(data["rows"], key=lambda r: abs(r[0] - float(phi)))
        if abs(row[0] - float(phi)) > 1e-9 * max(1.0, abs(row[0])):
            print(f"phi = {phi}: not a drive position of the sweep (nearest {row[0]})")
            failed = True
            continue
        want = (frame["origin-x"] + frame["scale"] * row[kx],
                frame["origin-y"] - frame["scale"] * row[ky])
        found = red_centre(path)
        if found is None:
            print(f"phi = {phi}: no red joint in {path}")
            failed = True
            continue
        miss = ((found[0] - want[0]) ** 2 + (found[1] - want[1]) ** 2) ** 0.5
        ok = miss <= TOLERANCE_PX
        failed |= not ok
        print(f"phi = {phi}: {point} solver ({row[kx]:.6g}, {row[ky]:.6g}) -> pixel "
              f"({want[0]:.2f}, {want[1]:.2f}); drawn at ({found[0]:.2f}, {found[1]:.2f}) "
              f"from {found[2]} red pixels; miss {miss:.2f} px: {'ok' if ok else 'FAIL'}")
    sys.exit(1 if failed else 0)


main()
