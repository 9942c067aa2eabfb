"""``python -m railvib``: the ``railvib`` command line, for environments without its script."""

import sys

from railvib.cli.main import main

if __name__ == "__main__":
    sys.exit(main())
