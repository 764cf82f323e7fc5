"""The gridrt-farm command that `pip install .` makes (pyproject.toml): the farm's own
entry point (tools/gridrt_farm, installed beside this package), which looks for gridrt
beside the command, in the installation's bin folder. The farm's Dask comes with
`pip install '.[farm]'`; without it the command says so in one line."""
import sys


def main():
    try:
        from gridrt_farm.main import main as farm_main
    except ImportError as e:
        print(f"gridrt-farm: {e.name or e} is not installed: the farm needs Dask's "
              "distributed (pip install 'gridrt[farm]')", file=sys.stderr)
        return 1
    return farm_main(sys.argv[1:])
