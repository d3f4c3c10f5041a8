import sys

from motiontool.cli import main

sys.exit(main())
