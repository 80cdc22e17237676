"""The viewer inside Jupyter: :class:`Widget`, a ``jupyter_rfb`` remote frame buffer.

The kernel holds the viewer's window-free model (the same picking, dragging, paper 000's
pull, zoom, pan, orbit, keys and undo as ``splinescope view``) and draws its picture on
the GPU (a software adapter works); the page shows the frames and sends pointer and key
events back. Needs the optional extra: ``pip install splinescope[notebook]``.
"""

from __future__ import annotations

import base64
from typing import Any, Callable, Dict, Iterable, List, Optional

import numpy as np

try:
    from jupyter_rfb import RemoteFrameBuffer
    from jupyter_rfb.widget import JS as _RFB_JS
    from traitlets import Unicode
except ImportError as e:  # pragma: no cover - exercised by the import error test
    raise ImportError(
        "splinescope.Widget needs jupyter_rfb: pip install 'splinescope[notebook]'"
    ) from e

from . import Scene, SceneError, _error
from . import _splinescope as _native

__all__ = ["Widget", "MARKERS"]

#: The marker names ``markers=`` takes (as ``Scene.render`` names them).
MARKERS = ("inflections", "curvature_extrema", "intersections", "joints")

# jupyter_rfb's front end, wrapped: a line of readouts under the picture, and a hook
# that records when each frame is drawn in the page (window.__splinescopeFrames, in
# performance.now() milliseconds) for the latency benchmark.
_DEFAULT_EXPORT = "export default () =>"
if _DEFAULT_EXPORT not in _RFB_JS:  # pragma: no cover - a jupyter_rfb we do not know
    raise ImportError("splinescope.Widget: this jupyter_rfb version's front end is not supported")
# jupyter_rfb throttles pointer moves in the page to one per 20 ms; the kernel coalesces
# them itself (the last position wins), so the widget sends each move at once and saves
# that wait on every drag step.
_THROTTLE = "this.setThrottle(20)"
_ESM = (
    _RFB_JS.replace(_DEFAULT_EXPORT, "const rfbLifecycle = () =>", 1).replace(
        _THROTTLE, "this.setThrottle(0)", 1
    )
    + """
export default () => {
  const inner = rfbLifecycle()
  return {
    initialize (ctx) { return inner.initialize(ctx) },
    render (ctx) {
      const done = inner.render(ctx)
      const line = document.createElement('div')
      line.className = 'splinescope-readout'
      line.style.font = '12px monospace'
      line.style.minHeight = '1.4em'
      line.style.whiteSpace = 'pre-wrap'
      line.style.maxWidth = ctx.model.get('css_width')
      ctx.el.appendChild(line)
      const update = () => { line.textContent = ctx.model.get('readout') }
      ctx.model.on('change:readout', update)
      update()
      window.__splinescopeFrames = window.__splinescopeFrames || []
      const onLoad = (ev) => {
        if (ev.target && ev.target.tagName === 'IMG') {
          window.__splinescopeFrames.push(performance.now())
        }
      }
      ctx.el.addEventListener('load', onLoad, true)
      return () => {
        ctx.model.off('change:readout', update)
        ctx.el.removeEventListener('load', onLoad, true)
        if (done) { done() }
      }
    }
  }
}
"""
)

EditCallback = Callable[[Scene, Optional[int], Optional[int]], Any]


def _positive_int(value: Any, name: str) -> int:
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or value <= 0:
        raise _error(SceneError, f"Widget: {name} must be a whole number above 0, not {value!r}", name)
    return int(value)


def _number_or_none(value: Any) -> Optional[float]:
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        return None
    return float(value)


def _position(event: Dict[str, Any]) -> Optional[tuple]:
    """An event's (x, y), or None when it has none (a page's event may lack them)."""
    x, y = _number_or_none(event.get("x")), _number_or_none(event.get("y"))
    return None if x is None or y is None else (x, y)


class Widget(RemoteFrameBuffer):
    """The viewer's picture of ``scene``, live in a notebook, taking the viewer's gestures.

    Drag a control point (the curve and its overlays follow; on a Bézier, rational
    Bézier or NURBS curve a drag elsewhere on the curve pulls it through the pointer,
    paper 000), turn the wheel to zoom at the pointer, drag the background to pan (orbit
    in 3D; right or middle drag pans), click to select. While the widget has focus it
    takes the viewer's keys (``K`` comb, ``P`` polygons, ``C`` points, ``F`` fit,
    ``[``/``]`` select, ``I`` insert a point, ``Delete``, ``Ctrl+D`` duplicate, ``Ctrl+Z``
    undo, ``Ctrl+Shift+Z``/``Ctrl+Y`` redo, ``Esc``), and they do not reach JupyterLab.
    The selected curve's readouts (length, box, κ at the point nearest the pointer) show
    under the picture; a saved notebook keeps a still picture.

    ``widget.scene`` is the edited scene (a new :class:`Scene` value each time);
    assigning one redraws it (during a drag the drag goes on over it). ``on_edit(fn)``
    calls ``fn(scene, curve, point)`` after each edit: the new scene, the curve edited
    (``None`` when the list of curves changed) and the control point dragged (``None``
    otherwise).

    Frames are drawn only when the picture changes, at the page's pixel ratio; pointer
    moves that arrive faster than frames are coalesced (the last position wins).

    ``width``, ``height``: the picture's size in logical pixels; ``comb``: curvature
    combs on; ``markers``: any of :data:`MARKERS`; ``backend``: the GPU backend, as for
    :meth:`Scene.render`. Other keyword arguments go to ``jupyter_rfb``
    (``quality=100`` sends lossless frames).
    """

    _esm = _ESM
    readout = Unicode("").tag(sync=True)

    def __init__(
        self,
        scene: Scene,
        width: int = 800,
        height: int = 500,
        comb: bool = False,
        markers: Iterable[str] = (),
        backend: str = "auto",
        **kwargs: Any,
    ) -> None:
        if not isinstance(scene, Scene):
            raise TypeError(f"Widget: scene must be a splinescope.Scene, not {type(scene).__name__}")
        w = _positive_int(width, "width")
        h = _positive_int(height, "height")
        if isinstance(markers, str):
            markers = (markers,)
        markers = tuple(markers)
        for m in markers:
            if m not in MARKERS:
                raise _error(
                    SceneError,
                    f"Widget: marker {m!r} is not one of {', '.join(MARKERS)}",
                    "markers",
                )
        kwargs.setdefault("resizable", False)
        super().__init__(css_width=f"{w}px", css_height=f"{h}px", **kwargs)
        self._backend = backend
        self._model = _native._Interaction(scene._s, float(w), float(h), 1.0)
        self._model.comb = bool(comb)
        for m in markers:
            self._model.set_marker(m, True)
        self._callbacks: List[EditCallback] = []
        self._pending_move: Optional[tuple] = None
        self._in_callback = False
        #: How many frames the widget has rendered (a picture that did not change is
        #: never rendered again).
        self.frames_rendered = 0
        self._still: Optional[np.ndarray] = None
        self._update_readout()

    # ---- the scene and edits

    @property
    def scene(self) -> Scene:
        """The edited scene (a new value); assigning a scene shows it."""
        self._apply_pending_move()
        return Scene._wrap(self._model.scene())

    @scene.setter
    def scene(self, value: Scene) -> None:
        if not isinstance(value, Scene):
            raise TypeError(f"Widget.scene must be a splinescope.Scene, not {type(value).__name__}")
        self._model.set_scene(value._s)
        self._update_readout()
        self.request_draw()

    def on_edit(self, callback: EditCallback, remove: bool = False) -> None:
        """Calls ``callback(scene, curve, point)`` after each edit (``remove=True``
        stops it)."""
        if remove:
            self._callbacks.remove(callback)
        elif not callable(callback):
            raise TypeError(f"Widget.on_edit: {callback!r} is not callable")
        else:
            self._callbacks.append(callback)

    @property
    def view(self) -> Dict[str, Any]:
        """The view as the scene format writes it (``{"kind": "2d", "center": [x, y],
        "height": h}`` or the 3D orbit): a scene given this view renders as the widget
        shows it."""
        return self._model.view()

    @property
    def size(self) -> tuple:
        """The picture's size in logical pixels and the page's pixel ratio, ``(width,
        height, ratio)``: what the page last said (its frame may be a little smaller than
        ``width × height`` asked for, by the frame's border)."""
        return self._model.size

    @property
    def selected(self) -> Optional[int]:
        """The selected curve, if any."""
        return self._model.selected

    @property
    def comb(self) -> bool:
        """Whether the curvature combs are drawn (``K``)."""
        return self._model.comb

    @comb.setter
    def comb(self, on: bool) -> None:
        self._model.comb = bool(on)
        self.request_draw()

    @property
    def message(self) -> Optional[str]:
        """What the viewer would say about the last gesture (a refused drag), if any."""
        return self._model.message

    def pixel_of(self, point: Any) -> Optional[tuple]:
        """Where the scene point ``point`` (2 or 3 numbers) is drawn, in logical pixels of
        the picture (``None`` behind a 3D camera)."""
        p = [float(v) for v in point]
        if len(p) == 2:
            p.append(0.0)
        if len(p) != 3:
            raise _error(SceneError, f"Widget.pixel_of: a point has 2 or 3 numbers, not {len(p)}", "point")
        return self._model.pixel_of(tuple(p))

    def picture(self) -> np.ndarray:
        """The picture as the widget shows it, rendered now: ``(H, W, 4)`` uint8."""
        self._apply_pending_move()
        return self._model.render(self._backend)

    # ---- jupyter_rfb

    def close(self, *args: Any, **kwargs: Any) -> None:
        """Closes the widget's views (a widget whose construction failed has none)."""
        if getattr(self, "_event_compatibility", None) is None:
            return
        super().close(*args, **kwargs)

    def get_frame(self) -> Optional[np.ndarray]:
        """The next frame, or ``None`` when the picture did not change (nothing is sent)."""
        self._apply_pending_move()
        if not self._model.take_stale():
            return None
        frame = self._model.render(self._backend)
        self.frames_rendered += 1
        self._still = frame
        return frame

    def handle_event(self, event: Dict[str, Any]) -> None:
        """One event from the page (``jupyter_rfb``'s event spec)."""
        kind = event.get("event_type") or event.get("type")
        at = _position(event)
        if kind == "pointer_move":
            # Coalesced: applied when the next frame is drawn, before any other event,
            # or when the scene is read, whichever comes first.
            if at is not None:
                self._pending_move = at
                self.request_draw()
            return
        self._apply_pending_move()
        changed = False
        if kind == "resize":
            size = [_number_or_none(event.get(k)) for k in ("width", "height")]
            ratio = _number_or_none(event.get("pixel_ratio", event.get("ratio", 1.0)))
            if None not in size and ratio is not None:
                changed = self._model.resize(size[0], size[1], ratio)
        elif kind == "pointer_down":
            if at is not None:
                self._model.pointer_move(*at)
            button = event.get("button", 1)
            changed = self._model.pointer_down(button if isinstance(button, int) and 0 <= button < 2**31 else 1)
        elif kind == "pointer_up":
            # The drag ends where the button came up (the page may have dropped a
            # throttled move just before it).
            if at is not None:
                changed = self._model.pointer_move(*at)
                # Its edit's callbacks run while the drag is open, so that what they
                # assign folds into the drag's one undo step.
                self._after_input()
            changed = self._model.pointer_up() or changed
        elif kind == "wheel":
            if at is not None:
                self._model.pointer_move(*at)
            dy = _number_or_none(event.get("dy", 0.0))
            # About 100 logical pixels a notch; scrolling up (dy < 0) zooms in.
            if dy is not None:
                changed = self._model.wheel(-dy / 100.0)
        elif kind == "key_down":
            mods = event.get("modifiers", ())
            mods = mods if isinstance(mods, (tuple, list)) else ()
            ctrl = "Control" in mods or "Meta" in mods
            changed = self._model.key(str(event.get("key", "")), ctrl, "Shift" in mods)
        self._after_input()
        if changed:
            self.request_draw()

    def _apply_pending_move(self) -> None:
        move, self._pending_move = self._pending_move, None
        if move is not None:
            self._model.pointer_move(*move)
            self._after_input()

    def _after_input(self) -> None:
        self._update_readout()
        edits = self._model.take_edits()
        if not edits or not self._callbacks or self._in_callback:
            return
        self._in_callback = True
        try:
            for curve, point in edits:
                scene = Scene._wrap(self._model.scene())
                for callback in list(self._callbacks):
                    callback(scene, curve, point)
        finally:
            self._in_callback = False
        # A callback may have assigned a scene (and queued no edit of its own).
        self._model.take_edits()

    def _update_readout(self) -> None:
        r = self._model.readout()
        if r is None:
            text = "" if self._model.selected is None else f"curve {self._model.selected}"
        else:
            lo, hi = r["box"]
            parts = [f"{r['name']}"]
            if r["length"] is not None:
                parts.append(f"length {r['length']:.6g}")
            parts.append(
                "box [" + ", ".join(f"{v:.4g}" for v in lo[:2]) + "] – [" + ", ".join(f"{v:.4g}" for v in hi[:2]) + "]"
            )
            if r["area"] is not None:
                parts.append(f"area {r['area']:.6g}")
            if "t" in r:
                k = r.get("curvature")
                parts.append(
                    f"at pointer: t {r['t']:.4f}, distance {r['distance']:.4g}"
                    + (f", κ {k:.6g}" if k is not None else "")
                )
            text = " · ".join(parts)
        if self._model.message:
            text = (text + "  — " if text else "") + self._model.message
        if text != self.readout:
            self.readout = text

    def _repr_mimebundle_(self, **kwargs: Any) -> Any:
        """The live widget, and a still picture for saved and exported notebooks."""
        result = super()._repr_mimebundle_(**kwargs)
        data = result[0] if isinstance(result, tuple) else result
        if isinstance(data, dict):
            still = self._still if self._still is not None else self.picture()
            png = _native.png_bytes(still)
            src = "data:image/png;base64," + base64.b64encode(png).decode()
            w, h = (int(float(v[:-2])) for v in (self.css_width, self.css_height))
            data["text/html"] = f'<img src="{src}" width="{w}" height="{h}" alt="splinescope widget"/>'
        return result
