"""The scripts in data/ that made its models run inside pylinkage's and Pyslvs's own
venvs (they import those packages), not in the suite."""

collect_ignore_glob = ["data/*.py"]
