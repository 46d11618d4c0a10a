"""`PYTHONPATH=tools python3 -m sheetgen_tools.farm ...`: sheetgen-farm with build/'s sheetgen by default."""
import sys

from .cli import main

sys.exit(main())
