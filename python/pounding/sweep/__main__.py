"""python3 -m pounding.sweep SWEEP.toml ...: runs pounding.sweep.main (pounding.sweep.command)."""

import sys

if __name__ == "__main__":
    # Nothing is defined in `__main__`: main comes from the package (pounding.sweep.command), as the
    # tasks Dask sends its workers by module name do. The package does not import this file, which
    # runpy would warn about (a module imported before it ran as __main__).
    from pounding.sweep import main as _main
    sys.exit(_main())
