"""Dynamics Lab: interactive engineering dynamics lessons in the browser."""

from importlib.metadata import PackageNotFoundError, version

try:
    __version__ = version("dynlab")
except PackageNotFoundError:  # running from a source tree that is not installed
    __version__ = "0.0.0+source"
