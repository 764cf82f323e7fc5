"""gridrt-farm: renders tiles and frames of one gridrt job on a Dask cluster and merges
each frame bit for bit into what one gridrt process writes (docs/farm.md)."""
