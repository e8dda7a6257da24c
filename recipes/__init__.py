"""The training recipes (YAML), installed with radaraug as ``radaraug.recipe_files``; read by :mod:`radaraug.recipes`."""
