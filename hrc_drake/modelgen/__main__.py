"""`python -m hrc_drake.modelgen`: rewrite all generated model files."""

from hrc_drake.modelgen import write_all

for path in write_all():
    print(path)
