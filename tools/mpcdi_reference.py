#!/usr/bin/env python3
"""An independent reading of an MPCDI package, after PyMPCDI's conventions (drwrose/PyMPCDI:
MpcdiFile.py, PfmFile.py, MpacsWarp2DShader.py), written from those stated conventions with
numpy, zipfile, xml.etree and OpenImageIO's Python bindings. It warps one region:

  mpcdi_reference.py --mpcdi FILE --region ID --in FRAME --out OUT [--pfm-rows top-first]

Conventions (docs/MPCDI.md compares them with Cupola's switches):
  * the PFM's first row is the projector raster's TOP row (PyMPCDI); --pfm-rows bottom-first
    reads it as netpbm stores it; the scale's sign gives the byte order (negative: little-endian);
  * (u, v) are local to the region: U = x + xSize*u, V = y + ySize*v, and V runs up, so the
    content image row is read at 1 - V (PyMPCDI's rangeMat then its V flip); the 3d profile's
    content is the region's own frustum render: U = u, V = v;
  * alpha = stored^gammaEmbedded, beta = stored^gammaEmbedded of the beta map (1 when absent);
  * per projector pixel centre: the warp grid sampled bilinearly (fill layout, clamped to the outer
    point centres, like a GL_LINEAR texture clamped to its edge), the content sampled bilinearly,
    then C * alpha * (1 - beta) + beta;
  * where PyMPCDI leaves it undefined (a NaN neighbour, (U, V) outside [0,1]) the pixel is black,
    Cupola's choice.
FRAME is an EXR in linear light, or a PNG decoded with the alpha map's gammaEmbedded (PyMPCDI's
mediaGamma). OUT: an EXR holds linear light; a PNG is encoded with gammaEmbedded (targetGamma).
"""
import argparse
import os
import sys
import tempfile
import zipfile
import xml.etree.ElementTree as ET

import numpy as np
import OpenImageIO as oiio


def attr(node, key):
    """An attribute by name, ignoring case (MPCDI v2.0 section 3.5.2)."""
    for k, v in node.attrib.items():
        if k.lower() == key.lower():
            return v
    raise SystemExit(f"mpcdi_reference: <{node.tag}> has no attribute {key}")


def child(node, key):
    for c in node:
        if c.tag.lower() == key.lower():
            return c
    return None


def read_pfm(data, rows):
    """(height, width, channels) float64, row 0 the raster's top."""
    tokens, pos = [], 2
    magic = data[:2]
    if magic not in (b"PF", b"Pf"):
        raise SystemExit("mpcdi_reference: not a PFM")
    channels = 3 if magic == b"PF" else 1
    while len(tokens) < 3:
        while data[pos:pos + 1].isspace():
            pos += 1
        end = pos
        while not data[end:end + 1].isspace():
            end += 1
        tokens.append(data[pos:end])
        pos = end + 1
    width, height, scale = int(tokens[0]), int(tokens[1]), float(tokens[2])
    dtype = "<f4" if scale < 0 else ">f4"
    pixels = np.frombuffer(data, dtype=dtype, count=width * height * channels, offset=pos)
    grid = pixels.astype(np.float64).reshape(height, width, channels)
    return grid[::-1] if rows == "bottom-first" else grid


def read_image_bytes(data, suffix):
    with tempfile.TemporaryDirectory() as tmp:
        path = os.path.join(tmp, "map" + suffix)
        with open(path, "wb") as f:
            f.write(data)
        return read_image(path)


def read_image(path):
    inp = oiio.ImageInput.open(path)
    if inp is None:
        raise SystemExit(f"mpcdi_reference: cannot read {path}: {oiio.geterror()}")
    pixels = inp.read_image("float")
    inp.close()
    pixels = np.asarray(pixels, dtype=np.float64)
    return pixels[:, :, None] if pixels.ndim == 2 else pixels


def bilinear(image, sx, sy):
    """image (h, w, c) sampled at continuous texel positions (texel k's centre at k), clamped."""
    h, w = image.shape[:2]
    sx = np.clip(sx, 0.0, w - 1.0)
    sy = np.clip(sy, 0.0, h - 1.0)
    x0 = np.minimum(np.floor(sx).astype(int), max(w - 2, 0))
    y0 = np.minimum(np.floor(sy).astype(int), max(h - 2, 0))
    x1, y1 = np.minimum(x0 + 1, w - 1), np.minimum(y0 + 1, h - 1)
    tx, ty = (sx - x0)[..., None], (sy - y0)[..., None]
    top = image[y0, x0] * (1 - tx) + image[y0, x1] * tx
    bottom = image[y1, x0] * (1 - tx) + image[y1, x1] * tx
    return top * (1 - ty) + bottom * ty


def blend_map(zf, node, default, width, height, fx, fy):
    if node is None:
        return np.full((height, width, 1), default)
    stored = read_image_bytes(zf.read(child(node, "path").text), ".png")
    gamma_node = child(node, "gammaEmbedded")
    gamma = float(gamma_node.text) if gamma_node is not None else 1.0
    linear = np.mean(stored, axis=2, keepdims=True) ** gamma
    mh, mw = linear.shape[:2]
    return bilinear(linear, fx * mw - 0.5, fy * mh - 0.5)


def find_region(doc, region_id):
    for buffer in doc.iter("buffer"):
        for region in buffer.iter("region"):
            if attr(region, "id") == region_id:
                return region
    raise SystemExit(f"mpcdi_reference: no region {region_id}")


def find_fileset(doc, region_id):
    for fileset in doc.iter("fileset"):
        if attr(fileset, "region") == region_id:
            return fileset
    raise SystemExit(f"mpcdi_reference: no fileset for region {region_id}")


def content_coordinates(doc, region, grid_uv):
    """PyMPCDI's rangeMat (2d profile): content (U, V), V up; the caller flips V for the row."""
    u, v = grid_uv[..., 0], grid_uv[..., 1]
    if attr(doc, "profile") == "2d":
        u = float(attr(region, "x")) + float(attr(region, "xSize")) * u
        v = float(attr(region, "y")) + float(attr(region, "ySize")) * v
    return u, v


def warp(package, region_id, frame, rows):
    zf = zipfile.ZipFile(package)
    doc = ET.fromstring(zf.read("mpcdi.xml"))
    region = find_region(doc, region_id)
    fileset = find_fileset(doc, region_id)
    width, height = int(attr(region, "xResolution")), int(attr(region, "yResolution"))
    grid = read_pfm(zf.read(child(child(fileset, "geometryWarpFile"), "path").text), rows)
    gh, gw = grid.shape[:2]
    py, px = np.mgrid[0:height, 0:width] + 0.5
    fx, fy = px / width, py / height
    # The warp grid at each pixel centre; a NaN among the four neighbours stays NaN.
    uv = bilinear(grid[:, :, :2], fx * gw - 0.5, fy * gh - 0.5)
    u, v = content_coordinates(doc, region, uv)
    shown = np.isfinite(u) & np.isfinite(v) & (u >= 0) & (u <= 1) & (v >= 0) & (v <= 1)
    u, v = np.where(shown, u, 0.0), np.where(shown, v, 0.0)
    ch, cw = frame.shape[:2]
    colour = bilinear(frame, u * cw - 0.5, (1.0 - v) * ch - 0.5) * shown[..., None]
    alpha = blend_map(zf, child(fileset, "alphaMap"), 1.0, width, height, fx, fy)
    beta = blend_map(zf, child(fileset, "betaMap"), 0.0, width, height, fx, fy)
    alpha_node = child(fileset, "alphaMap")
    gamma_node = child(alpha_node, "gammaEmbedded") if alpha_node is not None else None
    gamma = float(gamma_node.text) if gamma_node is not None else 1.0
    return colour * alpha * (1.0 - beta) + beta, gamma


def write_image(path, pixels):
    h, w, c = pixels.shape
    out = oiio.ImageOutput.create(path)
    fmt = "float" if path.lower().endswith(".exr") else "uint8"
    if out is None or not out.open(path, oiio.ImageSpec(w, h, c, fmt)):
        raise SystemExit(f"mpcdi_reference: cannot write {path}: {oiio.geterror()}")
    out.write_image(np.ascontiguousarray(pixels, dtype=np.float32))
    out.close()


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--mpcdi", required=True)
    ap.add_argument("--region", required=True)
    ap.add_argument("--in", dest="frame", required=True)
    ap.add_argument("--out", required=True)
    ap.add_argument("--pfm-rows", choices=["top-first", "bottom-first"], default="top-first")
    args = ap.parse_args()
    frame = read_image(args.frame)
    is_png = not args.frame.lower().endswith(".exr")
    zf_doc = ET.fromstring(zipfile.ZipFile(args.mpcdi).read("mpcdi.xml"))
    alpha_node = child(find_fileset(zf_doc, args.region), "alphaMap")
    media_gamma_node = child(alpha_node, "gammaEmbedded") if alpha_node is not None else None
    media_gamma = float(media_gamma_node.text) if media_gamma_node is not None else 1.0
    if is_png:
        frame = frame ** media_gamma
    result, gamma = warp(args.mpcdi, args.region, frame, args.pfm_rows)
    if not args.out.lower().endswith(".exr"):
        result = np.clip(result, 0.0, 1.0) ** (1.0 / gamma)
    write_image(args.out, result)
    return 0


if __name__ == "__main__":
    sys.exit(main())
