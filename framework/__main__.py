"""`python -m framework DECK.ups ...`: the pysus command line, the same as the `pysus` command."""
import sys

from framework.cli import main

sys.exit(main())
