import sys

from aileen.cli import main

sys.exit(main())
