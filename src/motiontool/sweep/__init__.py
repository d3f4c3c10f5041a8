"""Parameter sweeps (`motiontool sweep`, docs/sweep.md): the points, the measures and the runs. Qt-free."""
