"""JupyterLab on localhost and Debian's Chromium under Playwright, for the widget's
browser test and its latency benchmark (scripts/bench-widget): started here, stopped
here, no browser downloaded."""

import contextlib
import json
import os
import signal
import socket
import subprocess
import sys
import time
from pathlib import Path

CHROMIUM = os.environ.get("SPLINESCOPE_CHROMIUM", "/usr/bin/chromium")

# What Chromium needs on a machine without a network, as root, without a display.
CHROMIUM_ARGS = [
    "--no-sandbox",
    "--disable-gpu",
    "--disable-quic",
    "--no-first-run",
    "--disable-background-networking",
    "--disable-component-update",
    "--disable-sync",
]


def missing():
    """What the browser tests need and this machine lacks, as an install hint (or None)."""
    if not Path(CHROMIUM).exists():
        return f"Chromium at {CHROMIUM} (Debian/Ubuntu: sudo apt-get install chromium)"
    for module, package in [("playwright", "playwright"), ("jupyterlab", "jupyterlab")]:
        try:
            __import__(module)
        except ImportError:
            return f"the Python package {package} (pip install {package}; scripts/python-dev does)"
    return None


def notebook(cells):
    """A notebook of code cells for the python3 kernel."""
    return {
        "cells": [
            {"cell_type": "code", "execution_count": None, "metadata": {}, "outputs": [], "source": src}
            for src in cells
        ],
        "metadata": {
            "kernelspec": {"display_name": "Python 3", "language": "python", "name": "python3"},
            "language_info": {"name": "python"},
        },
        "nbformat": 4,
        "nbformat_minor": 5,
    }


def _free_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


@contextlib.contextmanager
def jupyter_lab(root, cells, name="widget.ipynb", start_timeout=90):
    """JupyterLab serving `root` with the notebook `name` of `cells`; yields its URL.
    Its settings, workspaces and runtime files stay under `root`; the server is stopped
    (its whole process group) on the way out."""
    root = Path(root)
    (root / name).write_text(json.dumps(notebook(cells)))
    port, token = _free_port(), "splinescope"
    env = dict(
        os.environ,
        JUPYTER_RUNTIME_DIR=str(root / ".runtime"),
        JUPYTER_CONFIG_DIR=str(root / ".config"),
        JUPYTERLAB_SETTINGS_DIR=str(root / ".settings"),
        JUPYTERLAB_WORKSPACES_DIR=str(root / ".workspaces"),
    )
    log_path = root / "lab.log"
    with open(log_path, "w") as log:
        server = subprocess.Popen(
            [
                sys.executable, "-m", "jupyterlab",
                "--no-browser", f"--port={port}", "--ip=127.0.0.1",
                f"--IdentityProvider.token={token}", f"--ServerApp.root_dir={root}",
                "--LabApp.news_url=",
                "--LabApp.check_for_updates_class=jupyterlab.NeverCheckForUpdate",
                "--LabApp.extension_manager=readonly",
            ]
            + (["--allow-root"] if hasattr(os, "geteuid") and os.geteuid() == 0 else []),
            cwd=root, env=env, stdout=log, stderr=subprocess.STDOUT, start_new_session=True,
        )
        try:
            deadline = time.monotonic() + start_timeout
            while True:
                if server.poll() is not None:
                    raise RuntimeError(f"JupyterLab exited: {log_path.read_text()[-3000:]}")
                try:
                    with socket.create_connection(("127.0.0.1", port), timeout=1):
                        break
                except OSError:
                    if time.monotonic() > deadline:
                        raise RuntimeError(
                            f"JupyterLab did not listen within {start_timeout} s: {log_path.read_text()[-3000:]}"
                        ) from None
                    time.sleep(0.3)
            yield f"http://127.0.0.1:{port}/lab/tree/{name}?token={token}"
        finally:
            with contextlib.suppress(ProcessLookupError):
                os.killpg(server.pid, signal.SIGTERM)
            try:
                server.wait(timeout=20)
            except subprocess.TimeoutExpired:
                with contextlib.suppress(ProcessLookupError):
                    os.killpg(server.pid, signal.SIGKILL)
                server.wait(timeout=20)


@contextlib.contextmanager
def browser_page(width=1400, height=1000):
    """A headless Chromium page (device pixel ratio 1)."""
    from playwright.sync_api import sync_playwright

    with sync_playwright() as p:
        browser = p.chromium.launch(executable_path=CHROMIUM, headless=True, args=CHROMIUM_ARGS)
        try:
            page = browser.new_page(viewport={"width": width, "height": height}, device_scale_factor=1)
            page.set_default_timeout(90_000)
            yield page
        finally:
            browser.close()


def wait_for(predicate, what, timeout=60.0):
    """`predicate()`'s first truthy value, polled; TimeoutError naming `what`."""
    deadline = time.monotonic() + timeout
    while True:
        value = predicate()
        if value:
            return value
        if time.monotonic() > deadline:
            raise TimeoutError(f"timed out after {timeout} s waiting for {what}")
        time.sleep(0.1)


def open_notebook(page, url):
    """Opens the notebook and waits for its kernel to be idle (the status bar says so)."""
    page.goto(url)
    page.wait_for_selector(".jp-Notebook .jp-Cell .cm-content")
    wait_for(
        lambda: "Idle" in page.locator(".jp-StatusBar-Widget, #jp-main-statusbar").first.inner_text(),
        "the kernel to be idle",
        timeout=120,
    )


def run_cell(page, index, tries=5):
    """Runs cell `index` from the page (a click in it, then Shift+Enter), until its prompt
    shows it queued or run (a press while the kernel is still connecting is dropped)."""
    cell = page.locator(".jp-Notebook .jp-Cell").nth(index)
    prompt = cell.locator(".jp-InputPrompt").first
    before = prompt.inner_text().strip()
    for _ in range(tries):
        cell.locator(".cm-content").click()
        page.keyboard.press("Shift+Enter")
        try:
            wait_for(lambda: prompt.inner_text().strip() not in ("[ ]:", before), f"cell {index} to run", timeout=5)
            return
        except TimeoutError:
            continue
    raise TimeoutError(f"cell {index} did not run after {tries} tries (its prompt: {prompt.inner_text()!r})")


def cell_output(page, index):
    """The text of cell `index`'s outputs."""
    return page.locator(".jp-Notebook .jp-Cell").nth(index).locator(".jp-OutputArea").first.inner_text()


def cell_texts(page):
    """Every cell's kind and source, as the page shows them."""
    return page.evaluate(
        "() => Array.from(document.querySelectorAll('.jp-Notebook .jp-Cell')).map("
        "c => [c.className.includes('jp-CodeCell') ? 'code' : 'other', "
        "(c.querySelector('.cm-content') || {}).innerText || ''])"
    )


def widget_image(page):
    """The locator of the widget's picture (jupyter_rfb's <img>), once a frame arrived."""
    img = page.locator(".jp-OutputArea-output img").last
    wait_for(lambda: img.evaluate("i => i.naturalWidth") > 1, "the widget's first frame")
    return img


def frame_png(page):
    """The widget's current frame in the page, as PNG bytes (drawn into a canvas)."""
    import base64

    url = page.evaluate(
        """() => {
        const views = Array.from(document.querySelectorAll('.jp-OutputArea-output img'))
          .filter(i => i.naturalWidth > 1);
        const view = views[views.length - 1];
        const c = document.createElement('canvas');
        c.width = view.naturalWidth; c.height = view.naturalHeight;
        c.getContext('2d').drawImage(view, 0, 0);
        return c.toDataURL('image/png');
    }"""
    )
    return base64.b64decode(url.split(",", 1)[1])
