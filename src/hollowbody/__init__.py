"""hollowbody: fast, stable human body models (explicit FE solver, hollow soft tissues)."""

from importlib.metadata import PackageNotFoundError, version

try:
    __version__ = version("hollowbody")
except PackageNotFoundError:  # running from a source tree that is not installed
    __version__ = "0.1.0"
