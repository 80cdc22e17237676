"""The notebook widget in a real browser: JupyterLab started on localhost, a notebook
opened in Debian's Chromium (driven by Playwright's Python package pointed at
/usr/bin/chromium: no browser is downloaded), its cells run from the page, a control
point dragged with real mouse events and the viewer's keys pressed while the widget has
focus. Checked: the kernel's `widget.scene` moved by the dragged amount; the notebook's
cells are unchanged after the keys (JupyterLab's command mode never saw them); the
picture in the page is, within `regress`'s default tolerance, an offscreen render of that
scene with the widget's view (frames sent lossless); a cell assigning a new scene changes
the picture to that scene's.

Everything started here is stopped here; the whole test is bounded (TIMEOUT_S)."""

import json
import os
import time

import pytest

import splinescope as ss

import lab

pytest.importorskip("jupyter_rfb", reason="the notebook extra (jupyter_rfb)")

BACKEND = [b.strip() for b in os.environ.get("SPLINESCOPE_TEST_BACKENDS", "auto").split(",") if b.strip()][0]
TIMEOUT_S = 300
W, H = 400, 300

SETUP = f"""import json, splinescope as ss
scene = ss.Scene([ss.Bezier([[0, 0], [1, 2], [3, 2], [4, 0]]), ss.Bezier([[0, -1], [2, -2], [4, -1]])])
w = ss.Widget(scene, width={W}, height={H}, quality=100, backend={BACKEND!r})
print("AT", json.dumps(w.pixel_of([1, 2])))
w"""

STATE = """def state(name):
    with open(name + ".json", "w") as f:
        json.dump({"scene": w.scene.to_json(), "view": w.view, "size": w.size, "frames": w.frames_rendered}, f)
state("after_drag")"""

ASSIGN = """w.scene = ss.Scene([ss.Bezier([[0, 0], [2, 3], [4, 0]]), ss.Bezier([[0, -2], [1, 1], [3, -1], [4, 1]])])
state("after_assign")"""


def read_state(path):
    lab.wait_for(path.exists, f"the kernel to write {path.name}")
    return lab.wait_for(lambda: _json_or_none(path), f"{path.name} to be complete", timeout=10)


def _json_or_none(path):
    try:
        return json.loads(path.read_text())
    except ValueError:
        return None


def settled_picture(page, tmp_path, name):
    """The page's frame once two reads 0.5 s apart agree (the last frame has landed)."""
    prev = None
    for k in range(60):
        path = tmp_path / f"{name}.png"
        path.write_bytes(lab.frame_png(page))
        cur = ss._splinescope.read_png(str(path))
        if prev is not None and cur.shape == prev.shape and (cur == prev).all():
            return cur
        prev = cur
        time.sleep(0.5)
    pytest.fail(f"the picture in the page kept changing ({name})")


def offscreen(state):
    """The scene rendered offscreen with the widget's view at the widget's size."""
    doc = json.loads(state["scene"])
    doc["view"] = state["view"]
    width, height, ratio = state["size"]
    assert ratio == 1.0, "the page runs at device pixel ratio 1"
    return ss.Scene.from_json(json.dumps(doc)).render(round(width), round(height), backend=BACKEND)


def same_picture(shown, expected, tmp_path, name):
    result = ss.compare_images(shown, expected)
    if not result["matches"]:
        ss._splinescope.write_png(str(tmp_path / f"{name}-expected.png"), expected)
    assert result["matches"], (name, result, f"pictures in {tmp_path}")


def test_the_widget_in_jupyterlab(tmp_path):
    lacking = lab.missing()
    if lacking:
        if os.environ.get("SPLINESCOPE_SKIP_BROWSER_TESTS") == "1":
            print(f"SKIPPED: needs {lacking}; SPLINESCOPE_SKIP_BROWSER_TESTS=1 asked to skip")
            pytest.skip(f"needs {lacking}")
        pytest.fail(
            f"the browser test needs {lacking} (or set SPLINESCOPE_SKIP_BROWSER_TESTS=1 to skip it explicitly)"
        )
    started = time.monotonic()
    with lab.jupyter_lab(tmp_path, [SETUP, STATE, ASSIGN]) as url, lab.browser_page() as page:
        try:
            drive(page, url, tmp_path)
        except Exception as e:
            page.screenshot(path=str(tmp_path / "failure.png"))
            outputs = [lab.cell_output(page, i) for i in range(3)]
            raise AssertionError(f"{e}\ncell outputs: {outputs!r}\npage: {tmp_path / 'failure.png'}") from e
    assert time.monotonic() - started < TIMEOUT_S


def drive(page, url, tmp_path):
    if True:
        lab.open_notebook(page, url)
        lab.run_cell(page, 0)
        text = lab.wait_for(lambda: "AT" in lab.cell_output(page, 0) and lab.cell_output(page, 0), "the widget cell")
        at = json.loads(text.split("AT", 1)[1].strip().splitlines()[0])
        img = lab.widget_image(page)
        page.wait_for_selector(".splinescope-readout", state="attached")
        box = img.bounding_box()
        assert round(box["width"]) == W and round(box["height"]) == H, box

        # The viewer's keys while the widget has focus (a click on empty canvas gives it
        # focus): K twice (comb on, then off), then keys JupyterLab's command mode acts on
        # (insert above/below, delete, to markdown, to heading, undo a cell edit).
        cells_before = lab.cell_texts(page)
        page.mouse.click(box["x"] + 5, box["y"] + 5)
        for key in ["k", "k", "a", "b", "d", "d", "m", "1", "z", "Escape"]:
            page.keyboard.press(key)
        time.sleep(1.0)
        assert lab.cell_texts(page) == cells_before, "a key reached JupyterLab"

        # Drag control point 1 of curve 0 by (dx, dy) page pixels with real mouse events,
        # then undo and redo it from the keyboard.
        dx, dy = 60.0, 25.0
        x0, y0 = box["x"] + at[0], box["y"] + at[1]
        page.mouse.move(x0, y0)
        page.mouse.down()
        page.mouse.move(x0 + dx, y0 + dy, steps=8)
        page.mouse.up()
        time.sleep(0.5)
        page.keyboard.press("Control+z")
        page.keyboard.press("Control+Shift+Z")
        time.sleep(1.0)
        assert lab.cell_texts(page) == cells_before, "Ctrl+Z reached JupyterLab"

        lab.run_cell(page, 1)
        state = read_state(tmp_path / "after_drag.json")
        moved = json.loads(state["scene"])["curves"][0]["points"][1]
        per_px = state["view"]["height"] / state["size"][1]
        # y grows downwards in the page and upwards in the scene; a pixel of slack for
        # where the browser puts a pointer event.
        assert abs(moved[0] - (1.0 + dx * per_px)) <= per_px, (moved, per_px)
        assert abs(moved[1] - (2.0 - dy * per_px)) <= per_px, (moved, per_px)

        shown = settled_picture(page, tmp_path, "page-after-drag")
        same_picture(shown, offscreen(state), tmp_path, "after-drag")

        # A cell assigning a new scene changes the picture to that scene's.
        lab.run_cell(page, 2)
        state2 = read_state(tmp_path / "after_assign.json")
        shown2 = settled_picture(page, tmp_path, "page-after-assign")
        assert not ss.compare_images(shown2, shown)["matches"], "the picture did not change"
        same_picture(shown2, offscreen(state2), tmp_path, "after-assign")
