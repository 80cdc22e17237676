"""Notebooks: the example tour (`examples/tour.ipynb`) runs headless with nbclient in a
fresh kernel, every cell without error; scenes and curves show themselves as SVG figures
(`_repr_svg_`, labelled) besides the PNG."""

import os

import pytest

import splinescope as ss

from conftest import ROOT


def test_the_tour_notebook_runs_in_a_fresh_kernel():
    try:
        import nbclient
        import nbformat
    except ImportError as e:  # pragma: no cover - depends on the environment
        pytest.fail(f"nbclient and nbformat are test extras: scripts/python-dev installs them ({e})")
    nb = nbformat.read(ROOT / "examples" / "tour.ipynb", as_version=4)
    client = nbclient.NotebookClient(
        nb,
        timeout=300,
        kernel_name="python3",
        resources={"metadata": {"path": str(ROOT)}},
    )
    client.execute()  # raises CellExecutionError naming the cell on any error
    outputs = [o for cell in nb.cells if cell.cell_type == "code" for o in cell.outputs]
    assert not [o for o in outputs if o.output_type == "error"]
    # The curve and the scene cells showed themselves as SVG.
    svgs = [o for o in outputs if "image/svg+xml" in o.get("data", {})]
    assert len(svgs) >= 2, [sorted(o.get("data", {})) for o in outputs]


def test_scenes_and_curves_show_themselves_as_labelled_svg():
    curve = ss.Bezier([[0, 0], [1, 2], [3, 1]])
    svg = curve._repr_svg_()
    assert svg.startswith("<svg") or svg.startswith("<?xml"), svg[:60]
    assert "<path" in svg and "bezier" in svg, "a curve and its label"
    scene = ss.Scene([curve, ss.Nurbs.circle([5, 0], 1.0)], name="two")
    text = scene._repr_svg_()
    assert text.count("<path") >= 2 and "nurbs" in text
    assert "nurbs" not in scene.svg(labels=False)
    with pytest.raises(ss.CurveError, match="width"):
        scene.svg(width=0)
