"""Pages opened as a user sees them: Debian's headless Chromium (`make chromium` installs it,
as Graphviz is installed), driven by playwright through `executable_path`, so no browser is
downloaded."""

import contextlib
import shutil
import tempfile
from pathlib import Path

from playwright.sync_api import sync_playwright

CHROMIUM_FLAGS = [
    "--headless",
    "--no-sandbox",
    "--disable-gpu",
    "--disable-quic",
    "--no-first-run",
    "--disable-background-networking",
    "--disable-component-update",
    "--disable-sync",
]
VIEWPORT = {"width": 1280, "height": 720}


@contextlib.contextmanager
def chromium_page():
    """A fresh page of a headless Chromium with its own profile, closed afterwards."""
    chromium = shutil.which("chromium")
    assert chromium, "Chromium is missing: run `make chromium` (Debian's chromium package)"
    with sync_playwright() as playwright:
        context = playwright.chromium.launch_persistent_context(
            tempfile.mkdtemp(prefix="chromium-"),
            executable_path=chromium,
            args=CHROMIUM_FLAGS,
            headless=True,
            viewport=VIEWPORT,
        )
        try:
            yield context.new_page()
        finally:
            context.close()


def opened(page, path: Path):
    """`page` showing the file at `path`."""
    page.goto(Path(path).resolve().as_uri())
    return page
