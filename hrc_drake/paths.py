"""Where the bundled data folders live, in a checkout and in an installed wheel."""

import re
from pathlib import Path

MODEL_PACKAGE = "hrc_drake_models"
"""Name in models/package.xml: model files are `package://hrc_drake_models/...`."""
BUNDLED_MODELS = f"package://{MODEL_PACKAGE}/"
_MODEL_NAME = re.compile(r'<model name="[^"]*"')

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


def bundled_model_file(url: str) -> Path | None:
    """The file of a bundled model's `package://hrc_drake_models/...` URL, if it is one and
    the file exists."""
    if not url.startswith(BUNDLED_MODELS):
        return None
    path = resource_dir("models") / url.removeprefix(BUNDLED_MODELS)
    return path if path.is_file() else None


def add_bundled_model(parser, path: Path, name: str | None = None):
    """The model in the bundled file at `path` (`bundled_model_file`), named `name` if given,
    parsed from its text: Drake's SDFormat builds its whole element description afresh for
    every file it reads (40-60 ms, most of the time a station's models take) but not for
    text. The bundled models (made by hrc_drake.modelgen: one model a file, primitive
    shapes, no other files) parse the same either way; returns its model instance."""
    text = path.read_text()
    if name is not None:
        text = _MODEL_NAME.sub(f'<model name="{name}"', text, count=1)
    (instance,) = parser.AddModelsFromString(text, path.suffix.removeprefix("."))
    return instance
