"""Builds the compiled part of the Python module, omninav._omninav, with the project's CMake.

pyproject.toml holds the package's metadata; this file only teaches setuptools to build the
extension with CMake (setuptools has no CMake support of its own) and to put the default
configuration (config/) inside the package, where the module looks for it.

Environment:
  OMNINAV_BUILD_DIR  an existing, configured omninav build folder to build the module in (no
                     reconfiguration: its options stay), instead of a fresh one under build/
  CMAKE_BUILD_PARALLEL_LEVEL  compile jobs (default: the number of processors)
"""

import os
import shutil
import subprocess
import sys
from pathlib import Path

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

SOURCE_DIR = Path(__file__).resolve().parent


class CMakeExtension(Extension):
    def __init__(self, name):
        super().__init__(name, sources=[])


class CMakeBuild(build_ext):
    def build_extension(self, ext):
        build_dir = os.environ.get("OMNINAV_BUILD_DIR")
        if build_dir:
            build_dir = Path(build_dir).resolve()
        else:
            build_dir = Path(self.build_temp).resolve() / "cmake"
            generator = ["-G", "Ninja"] if shutil.which("ninja") else []
            subprocess.run(
                ["cmake", "-S", str(SOURCE_DIR), "-B", str(build_dir), *generator,
                 "-DCMAKE_BUILD_TYPE=Release", "-DOMNINAV_BUILD_TESTS=OFF",
                 "-DOMNINAV_BUILD_BENCHMARKS=OFF", "-DOMNINAV_BUILD_PYTHON=ON",
                 f"-DPython3_EXECUTABLE={sys.executable}"],
                check=True)
        jobs = os.environ.get("CMAKE_BUILD_PARALLEL_LEVEL", str(os.cpu_count() or 1))
        subprocess.run(["cmake", "--build", str(build_dir), "--target", "omninav_python",
                        "--parallel", jobs], check=True)

        built = sorted((build_dir / "python" / "omninav").glob("_omninav*.so"))
        if not built:
            sys.exit(f"setup.py: CMake built no _omninav*.so in {build_dir / 'python/omninav'}")
        target = Path(self.get_ext_fullpath(ext.name))
        target.parent.mkdir(parents=True, exist_ok=True)
        shutil.copyfile(built[0], target)
        config = target.parent / "config"
        shutil.rmtree(config, ignore_errors=True)
        shutil.copytree(SOURCE_DIR / "config", config)


setup(ext_modules=[CMakeExtension("omninav._omninav")], cmdclass={"build_ext": CMakeBuild})
