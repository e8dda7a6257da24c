"""The file helpers sit below every layer, and the twin's layers do not import the capture layer.

``radaraug.files`` (atomic writes, temporary names, safe reads) is imported by scenes, the ray
tracer, the receiver, captures, transforms and training; it may import nothing of radaraug but
``radaraug.errors``, or it would tie those layers together.
"""

from __future__ import annotations

import subprocess
import sys

from tests.conftest import REPO_ROOT
from tests.test_import_cycles import _imported_names

ALLOWED = {"radaraug", "radaraug.errors"}


def test_files_module_imports_nothing_of_radaraug_but_errors() -> None:
    path = REPO_ROOT / "radaraug" / "files.py"
    found = {m for m in _imported_names("radaraug.files", path) if m == "radaraug" or m.startswith("radaraug.")}
    # "from radaraug.errors import X" also counts as "radaraug.errors.X"
    bad = sorted(m for m in found if m not in ALLOWED and not m.startswith("radaraug.errors."))
    assert not bad, f"radaraug.files must import nothing of radaraug but radaraug.errors, found {bad}"


def test_twin_layers_do_not_load_the_capture_layer() -> None:
    """Scenes, the ray tracer and the receiver write files without importing radaraug.io (h5py...)."""
    code = (
        "import sys\n"
        "import radaraug.scene, radaraug.scene.scene, radaraug.raytrace, radaraug.raytrace.figures, radaraug.sensor\n"
        "print(sorted(m for m in sys.modules if m == 'h5py' or m == 'radaraug.io' or m.startswith('radaraug.io.')))\n"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True, cwd=REPO_ROOT)
    assert out.stdout.strip() == "[]", out.stdout
