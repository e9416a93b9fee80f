"""`cmake --install` puts a working package into <prefix>/lib/python3.X/site-packages: imported
from there (no PYTHONPATH into the build, no PLUMAGE_PLUGIN_PATH) it loads the installed core
library and finds the installed plug-ins and data."""
import os
import shutil
import subprocess
import sys

from conftest import BINARY_DIR

PROBE = """
import json, plumage
registry = plumage.default_registry()
libraries = [line.split()[-1] for line in open('/proc/self/maps') if 'libplumage_core' in line]
print(json.dumps({
    'package': plumage.__file__,
    'core': sorted(set(libraries)),
    'plugins': {p['type']: str(p['library']) for p in registry.plugins() if p['library']},
    'problems': registry.problems,
    'data': str(plumage.data_directory()),
}))
"""


def test_installed_package_is_self_contained(tmp_path):
    import json

    prefix = tmp_path / "prefix"
    subprocess.run([shutil.which("cmake"), "--install", str(BINARY_DIR), "--prefix", str(prefix)],
                   check=True, capture_output=True)
    site = prefix / "lib" / f"python{sys.version_info.major}.{sys.version_info.minor}" / "site-packages"
    assert (site / "plumage" / "__init__.py").is_file()
    env = {k: v for k, v in os.environ.items() if not k.startswith("PLUMAGE_") and k != "PYTHONPATH"}
    env["PYTHONPATH"] = str(site)
    result = subprocess.run([sys.executable, "-c", PROBE], cwd=tmp_path, env=env, capture_output=True, text=True)
    assert result.returncode == 0, result.stderr
    found = json.loads(result.stdout)
    assert found["package"].startswith(str(site))
    assert found["core"] and all(path.startswith(str(prefix)) for path in found["core"]), found["core"]
    for plugin in ("multilayer", "bem", "pathtracer", "fdtd_periodic", "photonic_crystal"):
        assert found["plugins"][plugin].startswith(str(prefix / "lib" / "plumage" / "plugins")), found["plugins"]
    assert found["problems"] == []
    assert found["data"] == str(prefix / "share" / "plumage")
