"""Tests of the CAM editor file formats and the cam CLI."""
