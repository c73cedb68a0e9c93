"""`cmake --install` puts the package where this python3 looks for packages."""
import os
import subprocess
import sys
import sysconfig

import pytest

BUILD = os.environ.get("FOGNAV_BUILD_DIR")


@pytest.mark.skipif(not BUILD, reason="FOGNAV_BUILD_DIR names the build tree (ctest sets it)")
def test_install_puts_the_package_on_pythons_path(tmp_path):
    cache = open(os.path.join(BUILD, "CMakeCache.txt")).read()
    prefix = next(line.split("=", 1)[1] for line in cache.splitlines()
                  if line.startswith("CMAKE_INSTALL_PREFIX:"))
    env = dict(os.environ, DESTDIR=str(tmp_path))
    subprocess.run(["cmake", "--install", BUILD], check=True, env=env, capture_output=True)
    found = [p for p in (str(tmp_path) + "/" + d.lstrip("/") for d in sys.path if d)
             if os.path.isfile(os.path.join(p, "fognav", "__init__.py"))]
    assert found, f"no fognav under {tmp_path} in a folder of sys.path (prefix {prefix})"
    installed = found[0][len(str(tmp_path)):]
    assert installed.startswith(prefix)
    for name in ("__init__.pyi", "perception.pyi", "py.typed"):
        assert os.path.isfile(os.path.join(found[0], "fognav", name))
    # the installed copy imports and works on its own
    out = subprocess.run([sys.executable, "-c", "import fognav, numpy; "
                          "l, p = fognav.perception.segment(numpy.zeros((4, 4, 3), 'f')); "
                          "print(fognav.__file__, l.shape)"],
                         env=dict(os.environ, PYTHONPATH=found[0]), cwd=tmp_path,
                         check=True, capture_output=True, text=True)
    assert out.stdout.startswith(found[0]) and "(4, 4)" in out.stdout
