"""``robot.view()`` in a real JupyterLab: the widget renders in a notebook, a slider moved in
the page changes ``view.q`` in the kernel, and nothing is fetched from outside the machine.

JupyterLab runs from the test's own folder on a free port of 127.0.0.1 (its configuration,
runtime and IPython folders in the test's temporary folder); Chromium drives it. Slow: the
server and a kernel start.
"""

from __future__ import annotations

import json
import math
import os
import socket
import subprocess
import sys
import time
import urllib.request
from pathlib import Path
from typing import Any

import pytest

pytestmark = pytest.mark.slow

NOTEBOOK = {
    "cells": [
        {
            "cell_type": "code",
            "execution_count": None,
            "metadata": {},
            "outputs": [],
            "source": [
                "import dhsym\n",
                "view = dhsym.load('planar2r').view([0.3, 0.2], workspace=0)\n",
                "view",
            ],
        },
        {
            "cell_type": "code",
            "execution_count": None,
            "metadata": {},
            "outputs": [],
            "source": ["print('Q=' + ','.join(f'{x:.4f}' for x in view.q))"],
        },
    ],
    "metadata": {
        "kernelspec": {"name": "python3", "display_name": "Python 3", "language": "python"}
    },
    "nbformat": 4,
    "nbformat_minor": 5,
}


def _free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return int(s.getsockname()[1])


def _wait_up(url: str, proc: subprocess.Popen[bytes], seconds: float = 120) -> None:
    end = time.monotonic() + seconds
    while time.monotonic() < end:
        if proc.poll() is not None:
            raise RuntimeError(f"jupyter lab stopped with status {proc.returncode}")
        try:
            with urllib.request.urlopen(url, timeout=2):  # noqa: S310 - our own server
                return
        except OSError:
            time.sleep(0.5)
    raise RuntimeError("jupyter lab did not start")


def test_the_widget_moves_q_in_the_kernel(browser: Any, tmp_path: Path, request: Any) -> None:
    request.getfixturevalue("need_jupyter")
    pytest.importorskip("jupyterlab")
    pytest.importorskip("anywidget")
    (tmp_path / "view.ipynb").write_text(json.dumps(NOTEBOOK), encoding="utf-8")
    port, token = _free_port(), "dhsym-test"
    env = {
        **os.environ,
        "JUPYTER_CONFIG_DIR": str(tmp_path / ".config"),
        "JUPYTER_RUNTIME_DIR": str(tmp_path / ".runtime"),
        "IPYTHONDIR": str(tmp_path / ".ipython"),
        "JUPYTERLAB_WORKSPACES_DIR": str(tmp_path / ".workspaces"),
    }
    log = (tmp_path / "lab.log").open("wb")
    proc = subprocess.Popen(  # noqa: S603 - our own interpreter and arguments
        [
            sys.executable,
            "-m",
            "jupyterlab",
            "--no-browser",
            "--ip=127.0.0.1",
            f"--port={port}",
            f"--IdentityProvider.token={token}",
            f"--ServerApp.root_dir={tmp_path}",
            "--ServerApp.open_browser=False",
            "--allow-root",
            "--LabApp.news_url=",
            "--LabApp.check_for_updates_class=jupyterlab.NeverCheckForUpdate",
        ],
        cwd=tmp_path,
        env=env,
        stdout=log,
        stderr=subprocess.STDOUT,
    )
    outside: list[str] = []

    def guard(route: Any) -> None:
        url = route.request.url
        if url.startswith(
            (f"http://127.0.0.1:{port}/", f"ws://127.0.0.1:{port}/", "data:", "blob:")
        ):
            route.continue_()
        else:
            outside.append(url)
            route.abort()

    page = None
    try:
        _wait_up(f"http://127.0.0.1:{port}/api/status?token={token}", proc)
        page = browser.new_page(viewport={"width": 1400, "height": 1000})
        page.route("**/*", guard)
        console: list[str] = []
        page.on("console", lambda m: console.append(f"{m.type}: {m.text}"))
        page.goto(f"http://127.0.0.1:{port}/lab/tree/view.ipynb?token={token}")
        page.wait_for_selector(".jp-Notebook .jp-Cell", timeout=120_000)
        idle = page.get_by_text("Python 3 (ipykernel) | Idle")
        idle.wait_for(timeout=120_000)  # the kernel is up
        for _attempt in range(3):  # a run sent while the kernel connects can be lost
            page.locator(".jp-Cell").nth(0).locator(".jp-InputPrompt").click()
            page.keyboard.press("Shift+Enter")
            try:
                page.wait_for_selector(".dhsym-view canvas", timeout=40_000)
                break
            except Exception:  # noqa: BLE001 - retried, then reported below
                continue
        else:
            page.screenshot(path=str(tmp_path / "lab.png"))
            raise AssertionError(f"no view; outside={outside} console={console[-15:]}")
        slider = page.locator(".dhsym-view input[data-joint='2']")
        assert float(slider.input_value()) == pytest.approx(0.2 * 180 / math.pi)  # degrees
        slider.evaluate("(s) => { s.value = '-40'; s.dispatchEvent(new Event('input')); }")
        page.wait_for_timeout(500)  # the change travels to the kernel
        page.locator(".jp-Cell").nth(1).locator(".jp-InputPrompt").click()
        page.keyboard.press("Shift+Enter")
        output = page.locator(".jp-Cell").nth(1).locator(".jp-OutputArea-output")
        output.wait_for(timeout=60_000)
        assert output.inner_text().strip() == "Q=0.3000,-0.6981"  # -40° in radians
    finally:
        if page is not None:
            page.close()
        proc.terminate()
        try:
            proc.wait(timeout=20)
        except subprocess.TimeoutExpired:
            proc.kill()
        log.close()
    assert outside == []
