"""The exceptions of plumage. Every error a user can cause names where it came from."""


class Error(Exception):
    """Base of every plumage error (the C++ plumage::Error)."""


class ConfigError(Error, ValueError):
    """Bad input in a configuration: unknown key, wrong type, value out of range, missing file,
    unknown plug-in type. str() reads "file:line:column: field: message"; the parts are
    attributes (line and column 1-based, 0 when unknown)."""

    def __init__(self, text, file="", line=0, column=0, field="", message=""):
        super().__init__(text)
        self.file = file
        self.line = line
        self.column = column
        self.field = field
        self.message = message


class InputFileError(Error, ValueError):
    """A damaged or out-of-range data file (.plm, .plt, .ffs, journal, shard, cross section)."""


class OutputPathError(Error, OSError):
    """An output that would destroy something: a symlink, a device, a folder, one of the inputs."""


class MemoryBudgetError(Error, MemoryError):
    """A computation whose memory estimate does not fit (plumage.set_max_memory, or the
    machine's available memory); raised before the computation starts."""


class PluginError(Error):
    """A plug-in library that cannot be used: missing, not a library, wrong ABI or kind."""


class NumericalError(Error, ArithmeticError):
    """A computation that detected its own failure (instability, non-finite result)."""
