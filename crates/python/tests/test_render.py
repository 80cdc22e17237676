"""The GPU picture from Python equals `splinescope render`'s, on every backend the test
run names (SPLINESCOPE_TEST_BACKENDS, as for the Rust GPU tests); image comparison
against figures computed here."""

import os
import struct
import zlib

import numpy as np
import pytest

import splinescope as ss

from conftest import SCENES, no_adapter

BACKENDS = [
    b.strip() for b in os.environ.get("SPLINESCOPE_TEST_BACKENDS", "auto").split(",") if b.strip()
]


def render_or_fail(scene, *args, **kw):
    """Renders, failing with how to install an adapter when there is none (skipping only
    when SPLINESCOPE_SKIP_GPU_TESTS=1 asks)."""
    try:
        return scene.render(*args, **kw)
    except ss.GpuError as e:
        no_adapter(e)


def decode_png(data: bytes) -> np.ndarray:
    """An 8-bit RGBA, non-interlaced PNG (what the program writes) as (H, W, 4)."""
    assert data[:8] == b"\x89PNG\r\n\x1a\n"
    pos, idat, width = 8, b"", None
    while pos < len(data):
        (length,) = struct.unpack(">I", data[pos : pos + 4])
        kind = data[pos + 4 : pos + 8]
        body = data[pos + 8 : pos + 8 + length]
        if kind == b"IHDR":
            width, height, depth, color, _, _, interlace = struct.unpack(">IIBBBBB", body)
            assert (depth, color, interlace) == (8, 6, 0)
        elif kind == b"IDAT":
            idat += body
        pos += 12 + length
    raw = zlib.decompress(idat)
    stride = width * 4
    out = np.zeros((height, stride), np.int32)
    prev = np.zeros(stride, np.int32)
    for y in range(height):
        f = raw[y * (stride + 1)]
        line = np.frombuffer(raw, np.uint8, stride, y * (stride + 1) + 1).astype(np.int32)
        cur = np.zeros(stride, np.int32)
        for x in range(stride):
            a = cur[x - 4] if x >= 4 else 0
            b = prev[x]
            c = prev[x - 4] if x >= 4 else 0
            if f == 0:
                p = 0
            elif f == 1:
                p = a
            elif f == 2:
                p = b
            elif f == 3:
                p = (a + b) // 2
            else:
                pa, pb, pc = abs(b - c), abs(a - c), abs(a + b - 2 * c)
                p = a if pa <= pb and pa <= pc else (b if pb <= pc else c)
            cur[x] = (line[x] + p) & 0xFF
        out[y] = cur
        prev = cur
    return out.reshape(height, width, 4).astype(np.uint8)


@pytest.mark.parametrize("backend", BACKENDS)
@pytest.mark.parametrize("name", ["gallery", "bezier3d", "paper001_fig1"])
def test_render_equals_the_command_lines_png(cli, tmp_path, backend, name):
    path = SCENES / f"{name}.json"
    scene = ss.load(path)
    image = render_or_fail(scene, 96, 64, backend=backend)
    assert image.shape == (64, 96, 4) and image.dtype == np.uint8
    out = tmp_path / "cli.png"
    cli("render", path, "-o", out, "--width", 96, "--height", 64, "--gpu-backend", backend)
    cli_png = out.read_bytes()
    assert scene.png(96, 64, backend=backend) == cli_png
    np.testing.assert_array_equal(image, decode_png(cli_png))
    # Not a blank picture: the curves are drawn over the background.
    assert len(np.unique(image.reshape(-1, 4), axis=0)) > 3


def test_repr_png_is_a_png_of_the_scene():
    scene = ss.Scene([ss.Bezier([[0, 0], [1, 2], [2, 0]])], name="arch")
    render_or_fail(scene, 8, 8)
    data = scene._repr_png_()
    assert data[:8] == b"\x89PNG\r\n\x1a\n"
    assert decode_png(data).shape == (500, 800, 4)


def test_compare_images_counts_what_changed():
    rng = np.random.default_rng(2)
    a = rng.integers(0, 256, (40, 50, 4), dtype=np.uint8)
    a[..., 3] = 255
    same = ss.compare_images(a, a.copy())
    assert same["matches"] and same["differing_pixels"] == 0 and same["flip_mean"] == 0
    b = a.copy()
    b[5, 7, 0] ^= 0x80  # one pixel off by 128 in red
    b[9, 9, 1] = np.uint8((int(b[9, 9, 1]) + 10) % 256) if b[9, 9, 1] < 246 else 0
    r = ss.compare_images(b, a, "channel=24,pixels=0%")
    assert r["max_channel_diff"] == 128
    assert r["differing_pixels"] == 1 + (abs(int(b[9, 9, 1]) - int(a[9, 9, 1])) > 24)
    assert not r["matches"] and r["flip_mean"] > 0
    assert ss.compare_images(b, a, "channel=200,pixels=0%")["matches"]
    rgb = ss.compare_images(a[..., :3].copy(), a)
    assert rgb["matches"] and rgb["differing_pixels"] == 0


def test_export_writes_svg_pdf_and_png_figures(tmp_path):
    scene = ss.load(SCENES / "paper002_examples.json")
    render_or_fail(scene, 8, 8)
    scene.export(tmp_path / "f.svg", 600, 400, labels=True, legend=True, axes=True, grid=True)
    text = (tmp_path / "f.svg").read_text()
    assert text.startswith("<svg") and text.count('<path id="curve-') == len(scene.curves)
    for c in scene.curves:
        assert c.name in text
    scene.export(tmp_path / "f.pdf", 600, 400, labels=True)
    assert (tmp_path / "f.pdf").read_bytes().startswith(b"%PDF")
    scene.export(tmp_path / "f.png", 60, 40)
    assert decode_png((tmp_path / "f.png").read_bytes()).shape == (40, 60, 4)
    with pytest.raises(ss.ImageError, match="unknown figure format .txt"):
        scene.export(tmp_path / "f.txt")
    with pytest.raises(ss.ImageError, match="tolerance"):
        scene.export(tmp_path / "g.svg", tolerance=0.0)
    assert not (tmp_path / "g.svg").exists()
    with pytest.raises(ss.ImageError, match="2D views only"):
        ss.load(SCENES / "bezier3d.json").export(tmp_path / "h.svg", axes=True)
