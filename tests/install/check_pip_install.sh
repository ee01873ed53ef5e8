#!/usr/bin/env bash
# `pip install --no-build-isolation` of the sources into a fresh virtualenv made with
# --system-site-packages (for Debian's numpy), as README.md tells a user, then the installed
# module used from outside the source and build trees: its version, its configuration found
# inside the package, a compass estimate. The module is built in the test's build folder
# (OMNINAV_BUILD_DIR, setup.py), so that the test does not compile the libraries again; the
# sources are copied first, since pip builds in the source folder.
#   check_pip_install.sh <source dir> <build dir> <python>
set -euo pipefail
source_dir=$1 build_dir=$2 python=$3
work=$build_dir/pip-check
rm -rf "$work"
mkdir -p "$work/source"
cp -r "$source_dir"/{pyproject.toml,setup.py,VERSION,README.md,LICENSE,config,python} "$work/source/"

"$python" -m venv --system-site-packages "$work/venv"
# Nothing from the build tree may leak in: the installed package alone must do.
unset PYTHONPATH OMNINAV_CONFIG_DIR
OMNINAV_BUILD_DIR=$build_dir "$work/venv/bin/python" -m pip install --quiet --no-build-isolation \
  --no-deps --no-index "$work/source" > "$work/pip.log" 2>&1 || { cat "$work/pip.log"; exit 1; }

cd "$work"
"$work/venv/bin/python" - "$source_dir/VERSION" "$work/venv" <<'PY'
import sys
from pathlib import Path

import omninav

version_file, venv = Path(sys.argv[1]), Path(sys.argv[2]).resolve()
package = Path(omninav.__file__).resolve().parent
assert venv in package.parents, f"omninav imported from {package}, not from the virtualenv"
assert omninav.__version__ == version_file.read_text().strip(), omninav.__version__
config = Path(omninav.default_config_dir()).resolve()
assert config == package / "config", f"default configuration {config}, not inside the package"
assert (config / "compass.yaml").is_file() and not config.is_symlink()

world = omninav.World("room", width_px=90, height_px=12)
renderer = omninav.Renderer(world)
compass = omninav.Compass()
estimate = None
for _, pose in world.trajectory("rotate:turns=0.05,rate_deg_s=30,fps=10"):
    estimate = compass.push(renderer.render(pose))
assert estimate is not None
print(f"omninav {omninav.__version__} from {package}: compass at {estimate.heading_rad:.3f} rad")
PY
