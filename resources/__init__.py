"""Data files of motiontool (parameter database, command table, samples); see motiontool.resources_path."""
