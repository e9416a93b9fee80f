"""plumage: appearance of iridescent bird feathers from their nanostructure (Yu et al. 2024).

A numpy-first shell over the C++ library: configs in, arrays out. Every call that takes a
``registry`` uses the session's default one (plumage.default_registry()) when it is None.
Units are in the names, as on the command line (lambda_nm, theta_deg). docs/python.md has the
API by task and the Python call of each ``plumage`` command.
"""

from . import errors
from .errors import (ConfigError, Error, InputFileError, MemoryBudgetError, NumericalError,
                     OutputPathError, PluginError)
from ._plumage import *  # noqa: F401,F403  (the bindings; their names are listed in __all__)
from ._plumage import __version__  # noqa: F401
from . import _plumage

__all__ = [name for name in dir(_plumage) if not name.startswith("_")] + [
    "errors", "Error", "ConfigError", "InputFileError", "OutputPathError", "MemoryBudgetError",
    "PluginError", "NumericalError",
]
