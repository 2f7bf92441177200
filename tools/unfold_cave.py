#!/usr/bin/python3
"""Lays a CAVE's wall frames out as the unfolded cube (docs/images): left, front and right in the
top row, the floor under the front, a white line between them.

    tools/unfold_cave.py OUT_DIR FRAME OUTPUT.png [--channels cave-left,cave-front,cave-right,cave-floor]

OUT_DIR is a loopback run's --out (one folder per channel), FRAME the frame number. The frames
must have one size. Uses OpenImageIO's Python bindings (python3-openimageio)."""
import argparse
import sys

import numpy as np
import OpenImageIO as oiio


def read(path):
    buf = oiio.ImageBuf(path)
    if buf.has_error:
        sys.exit("unfold_cave: cannot read %s: %s" % (path, buf.geterror()))
    return buf.get_pixels(oiio.FLOAT)[:, :, :3]


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("out_dir")
    p.add_argument("frame", type=int)
    p.add_argument("output")
    p.add_argument("--channels", default="cave-left,cave-front,cave-right,cave-floor")
    a = p.parse_args()
    names = a.channels.split(",")
    if len(names) != 4:
        sys.exit("unfold_cave: --channels names four channels: left, front, right, floor")
    frames = [read("%s/%s/frame_%06d.png" % (a.out_dir, n, a.frame)) for n in names]
    h, w = frames[0].shape[:2]
    if any(f.shape[:2] != (h, w) for f in frames):
        sys.exit("unfold_cave: the frames differ in size")
    out = np.full((2 * h + 2, 3 * w + 2, 3), 0.13, dtype=np.float32)
    out[h, :] = 1.0
    out[:, w] = 1.0
    out[:, 2 * w + 1] = 1.0
    out[:h, :w], out[:h, w + 1:2 * w + 1], out[:h, 2 * w + 2:] = frames[0], frames[1], frames[2]
    out[h + 1:2 * h + 1, w + 1:2 * w + 1] = frames[3]
    spec = oiio.ImageSpec(out.shape[1], out.shape[0], 3, oiio.UINT8)
    dst = oiio.ImageBuf(spec)
    dst.set_pixels(oiio.ROI(0, out.shape[1], 0, out.shape[0]), out)
    if not dst.write(a.output):
        sys.exit("unfold_cave: cannot write %s: %s" % (a.output, dst.geterror()))


if __name__ == "__main__":
    main()
