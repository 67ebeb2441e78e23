"""The ``autobal`` command installed by the wheel: the CLI's own code (``autobal_cli::main_with_args``
in the extension module), so ``pip install autobal`` gives the same command as the binary."""

from __future__ import annotations

import signal
import sys
from typing import List, Optional

from . import _autobal


def main(argv: Optional[List[str]] = None) -> None:
    """Run the command line on ``argv`` (default ``sys.argv``) and exit with its code."""
    args = list(sys.argv if argv is None else argv)
    # Python's own SIGINT handler only raises KeyboardInterrupt when control comes back to
    # Python, and it keeps the CLI's Ctrl-C handler (which stops long work in order, keeping the
    # complete rows) from being installed: the default disposition lets the CLI install it.
    signal.signal(signal.SIGINT, signal.SIG_DFL)
    sys.stdout.flush()
    sys.exit(_autobal.cli_main(["autobal", *args[1:]]))


if __name__ == "__main__":
    main()
