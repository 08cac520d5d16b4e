"""What a command's first tenth of a second is spent on, where it can be spared."""

import sys
from typing import Any


def prepare() -> None:
    """What every command sets before it runs: warnings and pydantic's plugins."""
    import os
    import warnings

    # numpy's and scipy's RuntimeWarnings (an overflow in a step that is then
    # rejected) are noise to a user; what they mean is reported as a result, a
    # failed row or no answer (solve_model silences them too, for in-process use).
    warnings.filterwarnings("ignore", category=RuntimeWarning)

    # pydantic looks for plugins through importlib.metadata when it builds the first
    # model (~25 ms of a 0.3 s run); mdcalc's models use none.
    os.environ.setdefault("PYDANTIC_DISABLE_PLUGINS", "__all__")
    no_plugin_discovery()


def no_plugin_discovery() -> None:
    """Spare the import of importlib.metadata (17 ms, the largest single import of a
    scene's run) that pydantic's plugin loader makes even when PYDANTIC_DISABLE_PLUGINS
    says to load none: the loader's module is replaced by one whose get_plugins()
    returns none, as the real one does then. Any other name pydantic may ask of it
    comes from the real module (tests/test_imports.py guards both)."""
    import os

    name = "pydantic.plugin._loader"
    if name in sys.modules or os.environ.get("PYDANTIC_DISABLE_PLUGINS") not in (
        "__all__",
        "1",
        "true",
    ):
        return
    import types

    loader = types.ModuleType(name)

    def get_plugins() -> tuple[()]:
        return ()

    def real(attribute: str) -> Any:
        if attribute.startswith("__"):  # the import system asks for __path__ and such
            raise AttributeError(attribute)
        import importlib

        del sys.modules[name]
        return getattr(importlib.import_module(name), attribute)

    loader.get_plugins = get_plugins  # type: ignore[attr-defined]
    loader.__getattr__ = real  # type: ignore[method-assign]
    sys.modules[name] = loader
