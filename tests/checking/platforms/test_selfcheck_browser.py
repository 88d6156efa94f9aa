"""The self-check widget in a real browser: JupyterLab headless, Chromium via Playwright.

JupyterLab serves a temporary notebook on 127.0.0.1; Debian's Chromium (no browser
download) opens it, runs the cell, types an answer into the widget, clicks *Check* and
reads the verdict back from the page.
"""

from __future__ import annotations

import json
import os
import secrets
import signal
import socket
import subprocess
import sys
import time
import urllib.request
from pathlib import Path

import pytest

pytestmark = [pytest.mark.browser, pytest.mark.jupyter, pytest.mark.slow]

CHROMIUM_ARGS = [
    "--headless",
    "--no-sandbox",
    "--disable-gpu",
    "--disable-background-networking",
    "--disable-component-update",
    "--disable-sync",
    "--no-first-run",
]
RIGHT = "[[C12, -S12, 0, a1*C1 + a2*C12], [S12, C12, 0, a1*S1 + a2*S12], [0, 0, 1, 0]]"
WRONG = RIGHT.replace("a1*C1 + a2*C12", "a1*C1 - a2*C12")


def _free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def _api(base: str, token: str, method: str, path: str, body: dict | None = None) -> object:
    data = json.dumps(body).encode() if body is not None else None
    req = urllib.request.Request(
        f"{base}{path}",
        data=data,
        method=method,
        headers={"Authorization": f"token {token}", "Content-Type": "application/json"},
    )
    with urllib.request.urlopen(req, timeout=30) as r:
        return json.loads(r.read() or b"null")


def _notebook(path: Path) -> None:
    cell = {
        "cell_type": "code",
        "execution_count": None,
        "id": "selfcheck",
        "metadata": {},
        "outputs": [],
        "source": ["import dhsym\n", 'dhsym.check(key="planar2r", question="T0_2")'],
    }
    nb = {
        "cells": [cell],
        "metadata": {
            "kernelspec": {"display_name": "Python 3", "language": "python", "name": "python3"}
        },
        "nbformat": 4,
        "nbformat_minor": 5,
    }
    path.write_text(json.dumps(nb), encoding="utf-8")


@pytest.fixture
def jupyter_lab(tmp_path, need_jupyter, need_ipywidgets):
    port, token = _free_port(), secrets.token_hex(16)
    _notebook(tmp_path / "selfcheck.ipynb")
    env = {
        **os.environ,
        "JUPYTERLAB_SETTINGS_DIR": str(tmp_path / ".settings"),
        "JUPYTERLAB_WORKSPACES_DIR": str(tmp_path / ".workspaces"),
        "JUPYTER_RUNTIME_DIR": str(tmp_path / ".runtime"),
    }
    log = (tmp_path / "jupyter.log").open("w")
    proc = subprocess.Popen(
        [
            sys.executable,
            "-m",
            "jupyter",
            "lab",
            "--no-browser",
            "--ip=127.0.0.1",
            f"--port={port}",
            "--port-retries=0",
            f"--IdentityProvider.token={token}",
            "--allow-root",  # CI runs as root
            f"--ServerApp.root_dir={tmp_path}",
            "--LabApp.news_url=None",
            "--LabApp.check_for_updates_class=jupyterlab.NeverCheckForUpdate",
        ],
        cwd=tmp_path,
        env=env,
        stdout=log,
        stderr=subprocess.STDOUT,
        start_new_session=True,
    )
    base = f"http://127.0.0.1:{port}"
    try:
        deadline = time.monotonic() + 90
        while True:
            try:
                with urllib.request.urlopen(f"{base}/api/status?token={token}", timeout=2):
                    break
            except OSError:
                if proc.poll() is not None or time.monotonic() > deadline:
                    pytest.fail(
                        "JupyterLab did not start:\n" + (tmp_path / "jupyter.log").read_text()
                    )
                time.sleep(0.5)
        # Start the notebook's session (and kernel) through the REST API, so that the page
        # attaches to it instead of choosing a kernel itself (on a slow machine the kernel
        # list can arrive after the notebook opens, and Lab then asks which kernel to use).
        _api(
            base,
            token,
            "POST",
            "/api/sessions",
            {
                "path": "selfcheck.ipynb",
                "name": "selfcheck.ipynb",
                "type": "notebook",
                "kernel": {"name": "python3"},
            },
        )
        yield f"{base}/lab/tree/selfcheck.ipynb?token={token}"
    finally:
        if proc.poll() is None:
            os.killpg(proc.pid, signal.SIGTERM)
            try:
                proc.wait(timeout=30)
            except subprocess.TimeoutExpired:
                os.killpg(proc.pid, signal.SIGKILL)
                proc.wait(timeout=10)
        log.close()


def test_widget_checks_an_answer_in_jupyterlab(
    jupyter_lab, need_chromium, need_playwright, tmp_path_factory
):
    from playwright.sync_api import expect, sync_playwright

    shots = tmp_path_factory.mktemp("screenshots")

    with sync_playwright() as p:
        browser = p.chromium.launch(
            executable_path="/usr/bin/chromium", headless=True, args=CHROMIUM_ARGS
        )
        try:
            page = browser.new_page(viewport={"width": 1280, "height": 900})
            page.goto(jupyter_lab, wait_until="domcontentloaded")
            editor = page.locator(".jp-Notebook .jp-Cell .cm-content").first
            editor.wait_for(timeout=90_000)
            answer = page.locator(".dhsym-answer textarea")
            dialog = page.locator(".jp-Dialog", has_text="Select Kernel")
            for _ in range(3):  # run the cell; if Lab asks for a kernel (slow start), accept
                editor.click()
                page.keyboard.press("Shift+Enter")
                try:
                    answer.or_(dialog).first.wait_for(timeout=90_000)
                except Exception:
                    page.screenshot(path=str(shots / "no-widget.png"))
                    raise
                if not dialog.count():
                    break
                dialog.locator(".jp-mod-accept").click()
                dialog.wait_for(state="detached", timeout=30_000)
            answer.wait_for(timeout=90_000)
            preview = page.locator(".dhsym-preview")
            expect(preview).to_contain_text("Type your answer", timeout=30_000)

            answer.fill(WRONG)
            expect(preview).to_contain_text("dhsym reads", timeout=30_000)
            expect(preview.locator("mjx-container").first).to_be_visible(timeout=30_000)
            page.locator("button.dhsym-check").click()
            verdict = page.locator(".dhsym-verdict")
            expect(verdict).to_contain_text("INCORRECT", timeout=30_000)
            text = verdict.inner_text()
            assert "wrong sign" in text and "Most likely mistake" in text
            expect(verdict.locator("mjx-container").first).to_be_visible(timeout=30_000)

            answer.fill(RIGHT)
            page.locator("button.dhsym-check").click()
            expect(verdict.locator(".dhsym-verdict-word")).to_have_text("CORRECT", timeout=30_000)
            assert "All 16 entries are right" in verdict.inner_text()
        finally:
            browser.close()
