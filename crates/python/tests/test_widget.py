"""The notebook widget without a browser: the page's events (jupyter_rfb's event spec)
fed to `handle_event`, frames taken with `get_frame` as jupyter_rfb takes them. The
scene moves by the dragged amount (computed here from the view), edits reach callbacks,
a scene assigned during a drag keeps the drag, nothing is rendered while nothing
changes, and the picture is the offscreen render of the scene with the widget's view.
The browser test (tests/test_widget_browser.py) drives the same widget in JupyterLab."""

import json
import os

import numpy as np
import pytest

import splinescope as ss

from conftest import no_adapter

jupyter_rfb = pytest.importorskip("jupyter_rfb", reason="the notebook extra (jupyter_rfb)")

BACKEND = [b.strip() for b in os.environ.get("SPLINESCOPE_TEST_BACKENDS", "auto").split(",") if b.strip()][0]
W, H = 320, 200


def cubic_scene():
    return ss.Scene(
        [
            ss.Bezier([[0.0, 0.0], [1.0, 2.0], [3.0, 2.0], [4.0, 0.0]]),
            ss.Bezier([[0.0, -1.0], [2.0, -2.0], [4.0, -1.0]]),
        ]
    )


def widget(scene=None, **kw):
    w = ss.Widget(scene or cubic_scene(), width=W, height=H, backend=BACKEND, **kw)
    try:
        w.get_frame()  # the first frame, as the page asks for it
    except ss.GpuError as e:
        no_adapter(e, "the widget")
    return w


def ev(kind, **fields):
    return {"event_type": kind, **fields}


def drag(w, start, end, steps=1, frames=True):
    w.handle_event(ev("pointer_move", x=start[0], y=start[1], buttons=()))
    w.handle_event(ev("pointer_down", x=start[0], y=start[1], button=1, buttons=(1,), modifiers=()))
    for k in range(1, steps + 1):
        f = k / steps
        x = start[0] + f * (end[0] - start[0])
        y = start[1] + f * (end[1] - start[1])
        w.handle_event(ev("pointer_move", x=x, y=y, buttons=(1,)))
        if frames:
            w.get_frame()
    w.handle_event(ev("pointer_up", x=end[0], y=end[1], button=1, buttons=(), modifiers=()))


def world_per_pixel(w):
    view = w.view
    assert view["kind"] == "2d"
    return view["height"] / H


def test_a_drag_moves_the_point_by_the_dragged_amount():
    w = widget()
    at = w.pixel_of([1.0, 2.0])
    drag(w, at, (at[0] + 40.0, at[1] - 10.0), steps=4)
    got = w.scene.curves[0].control_points[1]
    s = world_per_pixel(w)
    # y grows downwards in the page and upwards in the scene.
    np.testing.assert_allclose(got, [1.0 + 40.0 * s, 2.0 + 10.0 * s], rtol=0, atol=1e-9)
    assert w.selected == 0
    # The other points and the other curve did not move.
    np.testing.assert_array_equal(w.scene.curves[0].control_points[[0, 2, 3]], [[0, 0], [3, 2], [4, 0]])
    np.testing.assert_array_equal(w.scene.curves[1].control_points, cubic_scene().curves[1].control_points)


def test_undo_redo_and_the_comb_key():
    w = widget()
    at = w.pixel_of([3.0, 2.0])
    drag(w, at, (at[0], at[1] + 30.0))
    moved = w.scene.curves[0].control_points[2].copy()
    assert moved[1] < 2.0
    w.handle_event(ev("key_down", key="z", modifiers=("Control",)))
    np.testing.assert_array_equal(w.scene.curves[0].control_points[2], [3.0, 2.0])
    w.handle_event(ev("key_down", key="Z", modifiers=("Control", "Shift")))
    np.testing.assert_array_equal(w.scene.curves[0].control_points[2], moved)
    assert not w.comb
    before = w.get_frame()
    w.handle_event(ev("key_down", key="k", modifiers=()))
    assert w.comb
    with_comb = w.get_frame()
    assert with_comb is not None
    assert (before is None) or not np.array_equal(before, with_comb)


def test_nothing_is_rendered_while_nothing_changes():
    w = widget()
    n = w.frames_rendered
    assert n == 1
    for _ in range(5):
        assert w.get_frame() is None
    # Hovering over empty canvas changes no picture: no frame.
    for x in range(5, 60, 5):
        w.handle_event(ev("pointer_move", x=float(x), y=5.0, buttons=()))
        assert w.get_frame() is None
    # A key that changes nothing, a wheel of 0.
    w.handle_event(ev("key_down", key="x", modifiers=()))
    w.handle_event(ev("wheel", x=10.0, y=10.0, dx=0.0, dy=0.0, modifiers=()))
    assert w.get_frame() is None
    assert w.frames_rendered == n
    # Something that changes the picture renders exactly one frame.
    w.handle_event(ev("key_down", key="p", modifiers=()))
    assert w.get_frame() is not None
    assert w.get_frame() is None
    assert w.frames_rendered == n + 1


def test_moves_faster_than_frames_are_coalesced():
    w = widget()
    edits = []
    w.on_edit(lambda scene, curve, point: edits.append((curve, point, scene.curves[0].control_points[1].copy())))
    at = w.pixel_of([1.0, 2.0])
    w.handle_event(ev("pointer_move", x=at[0], y=at[1], buttons=()))
    w.handle_event(ev("pointer_down", x=at[0], y=at[1], button=1, buttons=(1,), modifiers=()))
    frames = w.frames_rendered
    for dx in range(1, 21):  # twenty moves, no frame between them
        w.handle_event(ev("pointer_move", x=at[0] + dx, y=at[1], buttons=(1,)))
    assert w.get_frame() is not None
    assert w.frames_rendered == frames + 1
    assert len(edits) == 1, "the last position wins"
    curve, point, p = edits[0]
    assert (curve, point) == (0, 1)
    np.testing.assert_allclose(p, [1.0 + 20.0 * world_per_pixel(w), 2.0], atol=1e-9)
    w.handle_event(ev("pointer_up", x=at[0] + 20, y=at[1], button=1, buttons=(), modifiers=()))


def test_a_scene_assigned_during_a_drag_keeps_the_drag():
    """A callback runs paper 000's solver on each edit: curve 1 is made to pass through
    the dragged point of curve 0, and the drag goes on over the new scene."""
    w = widget()
    calls = []

    def follow(scene, curve, point):
        calls.append((curve, point))
        if curve != 0:
            return
        target = scene.curves[0].control_points[1]
        c1, _ = scene.curves[1].pass_through(target, t=0.5)
        w.scene = ss.Scene([scene.curves[0], c1])

    w.on_edit(follow)
    at = w.pixel_of([1.0, 2.0])
    drag(w, at, (at[0] + 30.0, at[1]), steps=3)
    s = world_per_pixel(w)
    p = w.scene.curves[0].control_points[1]
    np.testing.assert_allclose(p, [1.0 + 30.0 * s, 2.0], atol=1e-9)
    # The solved curve passes through the dragged point at t = 1/2.
    np.testing.assert_allclose(w.scene.curves[1].eval(0.5), p, atol=1e-9)
    assert calls and all(c == (0, 1) for c in calls), calls
    # The whole gesture is one undo step back to the start.
    w.handle_event(ev("key_down", key="z", modifiers=("Control",)))
    for a, b in zip(w.scene.curves, cubic_scene().curves):
        np.testing.assert_array_equal(a.control_points, b.control_points)


def test_the_picture_is_the_offscreen_render_with_the_widgets_view():
    w = widget(comb=False)
    at = w.pixel_of([3.0, 2.0])
    drag(w, at, (at[0] + 25.0, at[1] + 15.0))
    w.handle_event(ev("wheel", x=100.0, y=80.0, dx=0.0, dy=-100.0, modifiers=()))
    frame = w.get_frame()
    assert frame is not None and frame.shape == (H, W, 4)
    doc = json.loads(w.scene.to_json())
    doc["view"] = w.view
    offscreen = ss.Scene.from_json(json.dumps(doc)).render(W, H, backend=BACKEND)
    result = ss.compare_images(frame, offscreen)
    assert result["matches"], result


def test_the_wheel_zooms_at_the_pointer():
    w = widget()
    x, y = 90.0, 70.0
    w.handle_event(ev("pointer_move", x=x, y=y, buttons=()))
    before = np.array(w._model.world_at(x, y))
    h0 = w.view["height"]
    w.handle_event(ev("wheel", x=x, y=y, dx=0.0, dy=-300.0, modifiers=()))
    assert w.view["height"] < h0
    np.testing.assert_allclose(w._model.world_at(x, y), before, atol=1e-9 * h0)


def test_the_pixel_ratio_sets_the_frames_size():
    w = widget()
    w.handle_event(ev("resize", width=float(W), height=float(H), pixel_ratio=2.0))
    frame = w.get_frame()
    assert frame.shape == (2 * H, 2 * W, 4)
    # A drag in logical pixels moves the point by the same world amount.
    at = w.pixel_of([1.0, 2.0])
    drag(w, at, (at[0] + 20.0, at[1]))
    np.testing.assert_allclose(
        w.scene.curves[0].control_points[1], [1.0 + 20.0 * world_per_pixel(w), 2.0], atol=1e-9
    )


def test_readouts_name_the_selected_curve():
    w = widget()
    assert w.readout == ""
    at = w.pixel_of([1.0, 2.0])
    drag(w, at, at)  # a click on a point selects its curve
    w.handle_event(ev("pointer_move", x=at[0], y=at[1] + 40.0, buttons=()))
    w.get_frame()
    text = w.readout
    length = w.scene.curves[0].length()
    assert f"length {length:.6g}" in text, text
    assert "κ" in text and "at pointer" in text, text
    # The readouts follow an edit of the selected curve (they are kept between pointer
    # moves, not after the curve changes).
    drag(w, at, (at[0] + 30.0, at[1] - 20.0))
    w.handle_event(ev("pointer_move", x=at[0], y=at[1] + 40.0, buttons=()))
    moved = w.scene.curves[0].length()
    assert abs(moved - length) > 1e-3
    assert f"length {moved:.6g}" in w.readout, w.readout


def test_bad_arguments_are_named():
    with pytest.raises(ss.SceneError, match="width"):
        ss.Widget(cubic_scene(), width=0)
    with pytest.raises(ss.SceneError, match="bogus"):
        ss.Widget(cubic_scene(), markers=["bogus"])
    with pytest.raises(TypeError, match="Scene"):
        ss.Widget("scene.json")
    w = ss.Widget(cubic_scene(), width=W, height=H)
    with pytest.raises(TypeError, match="Scene"):
        w.scene = 3


def test_a_saved_notebook_keeps_a_still_picture():
    w = widget()
    bundle = w._repr_mimebundle_()
    data = bundle[0] if isinstance(bundle, tuple) else bundle
    assert "application/vnd.jupyter.widget-view+json" in data
    assert data["text/html"].startswith('<img src="data:image/png;base64,')


def test_hostile_events_never_break_the_widget():
    """Events as a broken or hostile page could send them: non-finite and huge
    coordinates, unknown keys and event types, missing fields, zero and negative sizes,
    in long random runs. The widget never raises anything but a typed error for a bad
    size, and keeps a valid scene and frames of its size."""
    import random

    rng = random.Random(20261206)
    values = [0.0, -1.0, 1e308, -1e308, float("nan"), float("inf"), 5.0, 150.0, 1e-300]
    keys = ["k", "p", "c", "f", "i", "z", "y", "d", "[", "]", "Delete", "Backspace", "Escape", "F1", "?", "",
            "Unidentified", "ArrowLeft", "ß", "😀", "Control"]
    w = widget()
    for step in range(1500):
        kind = rng.choice(["pointer_move", "pointer_down", "pointer_up", "wheel", "key_down", "resize", "bogus"])
        e = {"event_type": kind}
        if rng.random() < 0.9:
            e["x"], e["y"] = rng.choice(values + [rng.uniform(-50, 400)]), rng.choice(values + [rng.uniform(-50, 300)])
        if kind == "pointer_down":
            e["button"] = rng.choice([0, 1, 2, 3, 99])
        if kind == "wheel":
            e["dy"] = rng.choice(values + [-100.0, 100.0])
        if kind == "key_down":
            e["key"] = rng.choice(keys)
            e["modifiers"] = tuple(rng.sample(["Control", "Shift", "Alt", "Meta"], rng.randint(0, 2)))
        if kind == "resize":
            e["width"], e["height"] = rng.choice([0.0, -5.0, float("nan"), 1e9, 200.0, 321.0]), rng.choice(
                [0.0, 150.0, 201.0, float("inf")]
            )
            e["pixel_ratio"] = rng.choice([1.0, 2.0, 0.0, float("nan")])
        try:
            w.handle_event(e)
        except ss.SceneError as err:
            assert kind == "resize", (step, e, err)
        if step % 50 == 0:
            frame = w.get_frame()
            if frame is not None:
                assert frame.ndim == 3 and frame.shape[2] == 4
            scene = w.scene
            assert len(scene.curves) >= 0
            json.loads(scene.to_json())  # still a valid scene document
    # Still a working widget: undo everything back to the start.
    while w._model.history_len()[0]:
        w.handle_event(ev("key_down", key="z", modifiers=("Control",)))
    for a, b in zip(w.scene.curves, cubic_scene().curves):
        np.testing.assert_array_equal(a.control_points, b.control_points)


def test_the_windows_file_commands_do_nothing_in_a_notebook():
    """Ctrl+S (a notebook user's reflex), Ctrl+O, Ctrl+N, Ctrl+Q would open the window's
    dialogs or prompts, unseen here, and stop the widget: they do nothing, and the widget
    goes on taking edits."""
    w = widget()
    at = w.pixel_of([1.0, 2.0])
    drag(w, at, (at[0] + 10.0, at[1]))  # an unsaved edit: New and Quit would ask first
    w.get_frame()
    for key in ["s", "S", "o", "n", "q"]:
        w.handle_event(ev("key_down", key=key, modifiers=("Control",)))
        w.handle_event(ev("key_down", key=key, modifiers=("Control", "Shift")))
    assert w.get_frame() is None, "nothing changed"
    at = w.pixel_of([3.0, 2.0])
    drag(w, at, (at[0], at[1] + 20.0))
    np.testing.assert_allclose(
        w.scene.curves[0].control_points[2], [3.0, 2.0 - 20.0 * world_per_pixel(w)], atol=1e-9
    )
    assert len(w.scene.curves) == 2
