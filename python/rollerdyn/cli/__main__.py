"""``python -m rollerdyn.cli``: the command line, as the ``rollerdyn`` command."""

from . import app

if __name__ == "__main__":  # pragma: no cover
    app()
