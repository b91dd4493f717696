"""Where the bundled data folders live, in a checkout and in an installed wheel."""

from pathlib import Path

MODEL_PACKAGE = "hrc_drake_models"
"""Name in models/package.xml: model files are `package://hrc_drake_models/...`."""

_HERE = Path(__file__).resolve().parent


def resource_dir(name: str) -> Path:
    """Folder `name` (models, trees, scenarios): inside the installed package, else the checkout.

    pyproject.toml maps the top-level folders into `hrc_drake`, so a wheel has them beside
    this file while an editable install finds them one level up.
    """
    for candidate in (_HERE / name, _HERE.parent / name):
        if candidate.is_dir():
            return candidate
    raise FileNotFoundError(f"hrc_drake data folder '{name}' not found near {_HERE}")


def add_model_package(package_map) -> None:
    """Make `package://hrc_drake_models/...` resolve offline (no drake_models download)."""
    if not package_map.Contains(MODEL_PACKAGE):
        package_map.Add(MODEL_PACKAGE, str(resource_dir("models")))
