"""The gridrt-farm command that `pip install .` makes (pyproject.toml): the farm's own
entry point (tools/gridrt_farm, installed beside this package), which looks for gridrt
beside the command, in the installation's bin folder."""
import sys


def main():
    from gridrt_farm.main import main as farm_main
    return farm_main(sys.argv[1:])
