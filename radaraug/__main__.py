"""``python -m radaraug``: the ``radaraug`` command (:mod:`radaraug.cli`)."""

import sys

from radaraug.cli import main

if __name__ == "__main__":
    sys.exit(main())
