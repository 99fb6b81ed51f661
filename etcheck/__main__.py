import sys

from etcheck.cli.main import main

sys.exit(main())
