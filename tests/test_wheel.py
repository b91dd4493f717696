"""The wheel works outside the checkout: data folders and systems ship inside the package."""

import os
import subprocess
import sys
import sysconfig
import venv
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def test_wheel_installed_elsewhere_validates_a_bundled_scenario(tmp_path):
    wheels = tmp_path / "wheels"
    subprocess.run(
        [
            sys.executable,
            "-m",
            "pip",
            "wheel",
            "--no-deps",
            "--no-build-isolation",
            "-q",
            "-w",
            str(wheels),
            str(ROOT),
        ],
        check=True,
    )
    (wheel,) = wheels.glob("hrc_drake-*.whl")

    env_dir = tmp_path / "venv"
    venv.create(env_dir, with_pip=True)
    python = env_dir / "bin" / "python"
    # The dependencies (drake, numpy, ...) come from this environment's site-packages as a
    # plain path entry; the package itself only from the wheel.
    site = Path(
        subprocess.check_output(
            [python, "-c", "import sysconfig; print(sysconfig.get_paths()['purelib'])"], text=True
        ).strip()
    )
    (site / "deps.pth").write_text(sysconfig.get_paths()["purelib"] + "\n")
    subprocess.run([python, "-m", "pip", "install", "-q", "--no-deps", str(wheel)], check=True)

    work = tmp_path / "elsewhere"
    work.mkdir()
    env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}
    packages = sorted(
        ".".join(p.parent.relative_to(ROOT).parts)
        for p in (ROOT / "hrc_drake").rglob("__init__.py")
    )
    imports = ", ".join(packages)
    where = subprocess.check_output(
        [
            python,
            "-c",
            f"import {imports}, hrc_drake.systems, hrc_drake.paths as p; "
            "print(p.resource_dir('models'))",
        ],
        cwd=work,
        env=env,
        text=True,
    )
    assert str(env_dir) in where
    result = subprocess.run(
        [env_dir / "bin" / "hrc-drake", "validate", "base"],
        cwd=work,
        env=env,
        capture_output=True,
        text=True,
    )
    assert result.returncode == 0, result.stderr
    assert "ok" in result.stdout
